// SPDX-License-Identifier: GPL-3.0-or-later
// Collisions per second of the engines (Google Benchmark), on the paper's
// workload: r = 0.9, delta = 1e-2, elastic sub-threshold, equally spaced
// particles with velocities uniform on [-1, 1], run to t = 300.
//
//   fast       EventEngine: exact time windows, what make_engine picks
//   reference  ReferenceEventEngine: the global-order loop it is bit-identical to
//   textbook   a plain peer kept only here: absolute positions and velocities
//              in separate arrays, std::priority_queue with lazy invalidation
//   passthrough PassThroughEngine: elastic collisions counted, not processed
//              (collisions per second count every collision, elastic ones
//              included: "equivalent" collisions)
//   hybrid     HybridEngine: EventEngine until nearly all collisions are elastic,
//              then passthrough (on this short workload it never switches)
//
// SHOCKGAS_BENCH_LONG=1 adds the speed goals' side-by-side long workloads
// (docs/measurements.md, "The speed goals over time"), one thread, fast,
// passthrough and hybrid on the same start: r = 0.9, delta = 1e-2,
// N = 10^5 to t = 10^4 and to t = 10^5, and Fig. 5's r = 0.99, delta = 1e-4,
// N = 2 10^4 to t = 10^4 and 10^5 (tens of CPU minutes), with the CPU seconds
// and ratios printed.
//
// SHOCKGAS_BENCH_CROSSOVER=1 measures where the hybrid's switch should be
// (HybridSwitchRule): EventEngine runs from check to check (the hybrid's
// check times), and from its state at each check a pass-through engine runs the
// same stretch; printed per stretch: the inelastic share of the stretch's
// collisions (what the rule reads) and both engines' CPU seconds.
// SHOCKGAS_BENCH_CROSSOVER=paper (r = 0.9, delta = 1e-2, N = 1e5, about two
// CPU minutes) or =fig5 (Fig. 5's setting, N = 2e4, about twenty) runs one.
//
// Run: build/bin/bench_engine  (N = 10^3 .. 10^6, a few minutes)
//      SHOCKGAS_BENCH_LARGE=1 build/bin/bench_engine   adds N = 10^7
//      --benchmark_filter=fast  etc. selects engines.
// The ratio fast/textbook is printed at the end for each N.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <queue>
#include <string>
#include <vector>

#include "shockgas/model/collision.hpp"
#include "reference_event_engine.hpp"
#include "event_engine.hpp"
#include "hybrid_engine.hpp"
#include "passthrough_engine.hpp"

namespace {

constexpr double restitution = 0.9;
constexpr double threshold = 1e-2;
constexpr double t_end = 300.0;

std::map<std::pair<std::string, std::int64_t>, double>& rates() {
    static std::map<std::pair<std::string, std::int64_t>, double> table;
    return table;
}

// The textbook event-driven ring: x_i at clock t_i, v_i; each particle counts
// its collisions, and a queued event is stale when either count has moved on.
class TextbookRing {
public:
    explicit TextbookRing(const shockgas::InitialCondition& initial)
        : n_(initial.size()),
          length_(initial.ring_length),
          position_(initial.position),
          velocity_(initial.velocity),
          clock_(static_cast<std::size_t>(n_), 0.0),
          count_(static_cast<std::size_t>(n_), 0) {
        for (std::int64_t i = 0; i < n_; ++i) predict(i, 0.0);
    }

    std::uint64_t run(double t_stop) {
        const shockgas::CollisionModel model{restitution, threshold, shockgas::Subthreshold::elastic};
        std::uint64_t collisions = 0;
        while (!queue_.empty() && queue_.top().time <= t_stop) {
            const Event e = queue_.top();
            queue_.pop();
            const std::int64_t j = (e.left + 1) % n_;
            if (e.left_count != count_[idx(e.left)] || e.right_count != count_[idx(j)]) continue;
            advance(e.left, e.time);
            advance(j, e.time);
            const double g = velocity_[idx(e.left)] - velocity_[idx(j)];
            const double r = shockgas::classify(model, g) == shockgas::CollisionKind::elastic ? 1.0 : restitution;
            const auto after = shockgas::collide(1.0, velocity_[idx(e.left)], 1.0, velocity_[idx(j)], r);
            velocity_[idx(e.left)] = after.left_velocity;
            velocity_[idx(j)] = after.right_velocity;
            ++count_[idx(e.left)];
            ++count_[idx(j)];
            ++collisions;
            predict((e.left + n_ - 1) % n_, e.time);
            predict(e.left, e.time);
            predict(j, e.time);
        }
        return collisions;
    }
    static constexpr std::size_t bytes_per_particle() {
        // position, velocity, clock, count, and on average about two queued events
        return 3 * sizeof(double) + sizeof(std::uint32_t) + 2 * sizeof(Event);
    }

private:
    struct Event {
        double time;
        std::int64_t left;
        std::uint32_t left_count;
        std::uint32_t right_count;
        bool operator<(const Event& other) const { return time > other.time; }  // min-heap
    };
    static std::size_t idx(std::int64_t i) { return static_cast<std::size_t>(i); }
    void advance(std::int64_t i, double t) {
        position_[idx(i)] += velocity_[idx(i)] * (t - clock_[idx(i)]);
        clock_[idx(i)] = t;
    }
    void predict(std::int64_t i, double now) {
        const std::int64_t j = (i + 1) % n_;
        const double closing = velocity_[idx(i)] - velocity_[idx(j)];
        if (!(closing > 0.0)) return;
        const double xi = position_[idx(i)] + velocity_[idx(i)] * (now - clock_[idx(i)]);
        double xj = position_[idx(j)] + velocity_[idx(j)] * (now - clock_[idx(j)]);
        if (j == 0) xj += length_;
        queue_.push({now + std::max(0.0, xj - xi) / closing, i, count_[idx(i)], count_[idx(j)]});
    }

    std::int64_t n_;
    double length_;
    std::vector<double> position_;
    std::vector<double> velocity_;
    std::vector<double> clock_;
    std::vector<std::uint32_t> count_;
    std::priority_queue<Event> queue_;
};

template <class Run>
void measure(benchmark::State& state, const std::string& engine, std::size_t bytes, Run run) {
    const auto particles = state.range(0);
    std::uint64_t collisions = 0;
    std::uint64_t seed = 1;
    double seconds = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        const auto initial =
            shockgas::generate_initial_condition(particles, static_cast<double>(particles), seed++, 0);
        state.ResumeTiming();
        const auto start = std::chrono::steady_clock::now();
        collisions += run(initial);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    const double rate = static_cast<double>(collisions) / seconds;
    auto& best = rates()[{engine, particles}];
    best = std::max(best, rate);
    state.counters["collisions_per_second"] = rate;
    state.counters["collisions_per_particle"] =
        static_cast<double>(collisions) / static_cast<double>(state.iterations()) / static_cast<double>(particles);
    state.counters["bytes_per_particle"] = static_cast<double>(bytes);
}

const shockgas::CollisionModel paper_gas{restitution, threshold, shockgas::Subthreshold::elastic};

// Collisions of one realization to t_end with an engine that takes a collapse criterion.
template <class EngineType>
std::uint64_t collisions_to_end(const shockgas::InitialCondition& initial, const shockgas::CollisionModel& model) {
    EngineType engine(initial, model, {});
    engine.advance_to(t_end);
    return engine.collisions();
}

void BM_fast(benchmark::State& state) {
    measure(state, "fast", shockgas::EventEngine::bytes_per_particle(), [](const auto& initial) {
        return collisions_to_end<shockgas::EventEngine>(initial, paper_gas);
    });
}
void BM_reference(benchmark::State& state) {
    measure(state, "reference", shockgas::ReferenceEventEngine::bytes_per_particle(), [](const auto& initial) {
        return collisions_to_end<shockgas::ReferenceEventEngine>(initial, paper_gas);
    });
}
void BM_textbook(benchmark::State& state) {
    measure(state, "textbook", TextbookRing::bytes_per_particle(), [](const auto& initial) {
        TextbookRing ring(initial);
        return ring.run(t_end);
    });
}

void BM_passthrough(benchmark::State& state) {
    measure(state, "passthrough", shockgas::PassThroughEngine::bytes_per_particle(), [](const auto& initial) {
        shockgas::PassThroughEngine engine(initial, paper_gas);
        engine.advance_to(t_end);
        return engine.collisions();
    });
}

void BM_hybrid(benchmark::State& state) {
    measure(state, "hybrid", shockgas::PassThroughEngine::bytes_per_particle(), [](const auto& initial) {
        return collisions_to_end<shockgas::HybridEngine>(initial, paper_gas);
    });
}

// The pure inelastic gas (delta = 0) of fig_haff's smallest epsilon, r = 0.998:
// collapse is possible, so the event engine keeps its copy to go back to
// (event_engine.hpp); to t = 300 no realization collapses at these sizes.
const shockgas::CollisionModel pure_gas{0.998, 0.0, shockgas::Subthreshold::elastic};

void BM_pure_fast(benchmark::State& state) {
    measure(state, "pure_fast", shockgas::EventEngine::bytes_per_particle(), [](const auto& initial) {
        return collisions_to_end<shockgas::EventEngine>(initial, pure_gas);
    });
}
void BM_pure_reference(benchmark::State& state) {
    measure(state, "pure_reference", shockgas::ReferenceEventEngine::bytes_per_particle(), [](const auto& initial) {
        return collisions_to_end<shockgas::ReferenceEventEngine>(initial, pure_gas);
    });
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// CPU seconds an engine takes to advance to t.
double seconds_to(shockgas::Engine& engine, double t) {
    const double start = cpu_seconds();
    engine.advance_to(t);
    return cpu_seconds() - start;
}

// One long workload, the engines from the same start: CPU seconds each.
struct LongWorkload {
    const char* name;
    std::int64_t particles;
    shockgas::CollisionModel model;
    double t_end;
};

struct LongSeconds {
    double fast;
    double passthrough;
    double hybrid;
    double switch_time;
};

std::map<std::string, LongSeconds>& long_seconds() {
    static std::map<std::string, LongSeconds> table;
    return table;
}

void run_long(benchmark::State& state, const LongWorkload& w) {
    for (auto _ : state) {
        const auto initial = shockgas::generate_initial_condition(w.particles, static_cast<double>(w.particles), 1, 0);
        shockgas::EventEngine fast(initial, w.model, {});
        const double fast_seconds = seconds_to(fast, w.t_end);
        shockgas::PassThroughEngine pass(initial, w.model);
        const double pass_seconds = seconds_to(pass, w.t_end);
        shockgas::HybridEngine hybrid(initial, w.model, {});
        const double hybrid_seconds = seconds_to(hybrid, w.t_end);
        long_seconds()[w.name] = {fast_seconds, pass_seconds, hybrid_seconds, hybrid.switch_time()};
        state.counters["fast_s"] = fast_seconds;
        state.counters["passthrough_s"] = pass_seconds;
        state.counters["hybrid_s"] = hybrid_seconds;
        state.counters["switch_time"] = hybrid.switch_time();
        state.counters["collisions_fast"] = static_cast<double>(fast.collisions());
        state.counters["collisions_passthrough"] = static_cast<double>(pass.collisions());
        state.counters["collisions_hybrid"] = static_cast<double>(hybrid.collisions());
    }
}

const shockgas::CollisionModel fig5_gas{0.99, 1e-4, shockgas::Subthreshold::elastic};

void register_long() {
    static const std::vector<LongWorkload> workloads = {{"long/N=1e5,t=1e4", 100000, paper_gas, 1e4},
                                                        {"long/N=1e5,t=1e5", 100000, paper_gas, 1e5},
                                                        {"long/fig5,N=2e4,t=1e4", 20000, fig5_gas, 1e4},
                                                        {"long/fig5,N=2e4,t=1e5", 20000, fig5_gas, 1e5}};
    for (const LongWorkload& w : workloads)
        benchmark::RegisterBenchmark(w.name, [&w](benchmark::State& state) { run_long(state, w); })
            ->Iterations(1)
            ->Unit(benchmark::kSecond);
}

// The crossover measurement (SHOCKGAS_BENCH_CROSSOVER=1): per stretch between
// the hybrid's checks, the inelastic share and both engines' CPU seconds from
// the same state.
void crossover(const LongWorkload& w) {
    const auto initial = shockgas::generate_initial_condition(w.particles, static_cast<double>(w.particles), 1, 0);
    const shockgas::HybridSwitchRule rule = shockgas::HybridSwitchRule::measured();
    shockgas::EventEngine fast(initial, w.model, {});
    std::printf("\ncrossover %s\n%12s %12s %14s %12s %12s %10s\n", w.name, "from t", "to t", "inelastic %",
                "fast CPU s", "passthru s", "fast/pt");
    for (double from = rule.first_check, to = from * rule.check_factor; from < w.t_end;
         from = to, to *= rule.check_factor) {
        fast.advance_to(from);
        const shockgas::MidRunState state = fast.mid_run_state();
        const double fast_seconds = seconds_to(fast, to);
        const double share = static_cast<double>(fast.inelastic_collisions() - state.inelastic_collisions) /
                             static_cast<double>(fast.collisions() - state.collisions);
        double pass_seconds = std::nan("");
        if (from >= w.t_end / 1000.0) {  // early stretches: the pass-through engine is far slower
            shockgas::PassThroughEngine pass(state, w.model);
            pass_seconds = seconds_to(pass, to);
        }
        std::printf("%12.4g %12.4g %14.4f %12.4f %12.4f %10.3f\n", from, to, 100.0 * share, fast_seconds,
                    pass_seconds, fast_seconds / pass_seconds);
        std::fflush(stdout);
    }
}

void register_all(std::int64_t particles) {
    // One iteration is 40-odd collisions per particle: enough from N = 10^5 on.
    const auto iterations = particles >= 100000 ? 1 : (particles >= 10000 ? 3 : 30);
    for (auto* bench : {&BM_fast, &BM_reference, &BM_textbook, &BM_passthrough, &BM_hybrid}) {
        const char* name = bench == &BM_fast          ? "fast"
                           : bench == &BM_reference   ? "reference"
                           : bench == &BM_textbook    ? "textbook"
                           : bench == &BM_passthrough ? "passthrough"
                                                      : "hybrid";
        benchmark::RegisterBenchmark(name, bench)
            ->Arg(particles)
            ->Iterations(iterations)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    }
}

}  // namespace

int main(int argc, char** argv) {
    // SHOCKGAS_BENCH_CROSSOVER=1 measures both settings; =paper or =fig5 one.
    if (const char* c = std::getenv("SHOCKGAS_BENCH_CROSSOVER"); c != nullptr) {
        const std::string which(c);
        if (which == "1" || which == "paper") crossover({"r=0.9,delta=1e-2,N=1e5", 100000, paper_gas, 1e5});
        if (which == "1" || which == "fig5") crossover({"fig5,r=0.99,delta=1e-4,N=2e4", 20000, fig5_gas, 1e5});
        return 0;
    }
    for (const std::int64_t n : {1000, 10000, 100000, 1000000}) register_all(n);
    for (const std::int64_t n : {10000, 100000})
        for (auto* bench : {&BM_pure_fast, &BM_pure_reference})
            benchmark::RegisterBenchmark(bench == &BM_pure_fast ? "pure_gas/fast" : "pure_gas/reference", bench)
                ->Arg(n)
                ->Iterations(n >= 100000 ? 1 : 3)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
    if (const char* large = std::getenv("SHOCKGAS_BENCH_LARGE"); large != nullptr && std::string(large) == "1")
        register_all(10000000);
    if (const char* long_runs = std::getenv("SHOCKGAS_BENCH_LONG"); long_runs != nullptr && std::string(long_runs) == "1")
        register_long();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::printf("\n%10s %14s %14s %14s %14s %14s %8s %8s %8s %10s %10s\n", "N", "fast c/s", "reference c/s",
                "textbook c/s", "passthru c/s", "hybrid c/s", "fast/tb", "pt/fast", "hyb/fast", "B/p fast", "B/p tb");
    std::map<std::int64_t, bool> sizes;
    for (const auto& [key, rate] : rates()) sizes[key.second] = true;
    for (const auto& [n, present] : sizes) {
        auto get = [&](const char* engine) {
            const auto it = rates().find({engine, n});
            return it == rates().end() ? std::nan("") : it->second;
        };
        std::printf("%10lld %14.3e %14.3e %14.3e %14.3e %14.3e %8.2f %8.2f %8.2f %10zu %10zu\n",
                    static_cast<long long>(n), get("fast"), get("reference"), get("textbook"), get("passthrough"),
                    get("hybrid"), get("fast") / get("textbook"), get("passthrough") / get("fast"),
                    get("hybrid") / get("fast"),
                    shockgas::EventEngine::bytes_per_particle(), TextbookRing::bytes_per_particle());
    }
    std::printf("\npure inelastic gas (delta = 0, r = 0.998, to t = %g)\n%10s %14s %14s %10s\n", t_end, "N",
                "fast c/s", "reference c/s", "fast/ref");
    for (const auto& [n, present] : sizes) {
        const auto fast = rates().find({"pure_fast", n});
        const auto reference = rates().find({"pure_reference", n});
        if (fast == rates().end() || reference == rates().end()) continue;
        std::printf("%10lld %14.3e %14.3e %10.2f\n", static_cast<long long>(n), fast->second, reference->second,
                    fast->second / reference->second);
    }
    if (!long_seconds().empty()) {
        std::printf("\n%-26s %12s %14s %12s %10s %8s %8s\n", "long workload", "fast CPU s", "passthru CPU s",
                    "hybrid CPU s", "switch t", "fast/pt", "fast/hyb");
        for (const auto& [name, s] : long_seconds())
            std::printf("%-26s %12.2f %14.2f %12.2f %10.4g %8.2f %8.2f\n", name.c_str(), s.fast, s.passthrough,
                        s.hybrid, s.switch_time, s.fast / s.passthrough, s.fast / s.hybrid);
    }
    return 0;
}
