// Collisions per second of the event engine (Google Benchmark).
// The workload is the paper's: r = 0.9, delta = 1e-2, elastic sub-threshold,
// equally spaced particles with velocities uniform on [-1, 1], run to t_end.
// Run: build/bench/bench_engine   (README "Speed" has the table)
#include <benchmark/benchmark.h>

#include "shockgas/event_engine.hpp"

namespace {

void run_to(benchmark::State& state, double restitution, double threshold, shockgas::Subthreshold mechanism,
            double t_end) {
    const auto particles = state.range(0);
    std::uint64_t collisions = 0;
    std::uint64_t seed = 1;
    for (auto _ : state) {
        state.PauseTiming();
        const auto initial =
            shockgas::generate_initial_condition(particles, static_cast<double>(particles), seed++, 0);
        state.ResumeTiming();
        shockgas::EventEngine engine(initial, {restitution, threshold, mechanism}, {});
        engine.advance_to(t_end);
        collisions += engine.collisions();
        benchmark::DoNotOptimize(engine.time());
    }
    state.counters["collisions_per_second"] =
        benchmark::Counter(static_cast<double>(collisions), benchmark::Counter::kIsRate);
    state.counters["collisions_per_particle"] =
        static_cast<double>(collisions) / static_cast<double>(state.iterations()) / static_cast<double>(particles);
    state.counters["bytes_per_particle"] = static_cast<double>(shockgas::EventEngine::bytes_per_particle());
}

// To t = 100 the paper's gas makes ~11 collisions per particle.
void BM_EventEngine_r09(benchmark::State& state) { run_to(state, 0.9, 1e-2, shockgas::Subthreshold::elastic, 100.0); }
BENCHMARK(BM_EventEngine_r09)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The sticky gas: at most N - 1 merges in all.
void BM_EventEngine_sticky(benchmark::State& state) {
    run_to(state, 0.0, 0.0, shockgas::Subthreshold::elastic, 1e6);
}
BENCHMARK(BM_EventEngine_sticky)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
