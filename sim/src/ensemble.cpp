#include "shockgas/ensemble.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include <sys/resource.h>

#include <fmt/format.h>

#include "shockgas/event_engine.hpp"
#include "shockgas/fast_engine.hpp"
#include "shockgas/observables.hpp"

namespace shockgas {

namespace {

constexpr double not_reached = std::numeric_limits<double>::quiet_NaN();

bool contains(const std::vector<double>& times, double t) {
    return std::find(times.begin(), times.end(), t) != times.end();
}

// Everything one realization produces, gathered by its worker and merged into
// the ensemble in realization order afterwards.
struct RealizationOutput {
    std::vector<SnapshotRecord> snapshots;
    std::vector<std::vector<double>> histogram_counts;  // one per histogram time
    std::vector<CollapseRecord> collapse;
    RealizationStatus status = RealizationStatus::not_run;
    std::uint64_t collisions = 0;
};

class EnsembleRunner {
public:
    EnsembleRunner(const SimulationParameters& parameters, const InitialCondition* initial_override,
                   const std::atomic<bool>* stop)
        : parameters_(parameters), initial_override_(initial_override), stop_(stop) {
        result_.times = sample_grid(parameters);
        result_.realizations = parameters.realizations;
        result_.engine = resolve_engine_name(parameters);
        histogram_times_ = parameters.histogram_times;
        std::sort(histogram_times_.begin(), histogram_times_.end());
        histogram_times_.erase(std::unique(histogram_times_.begin(), histogram_times_.end()), histogram_times_.end());
        const std::size_t cells = static_cast<std::size_t>(parameters.realizations) * result_.times.size();
        for (auto* table : {&result_.temperature, &result_.collisions_per_particle, &result_.clusters,
                            &result_.kinetic_energy})
            table->assign(cells, not_reached);
        outputs_.resize(static_cast<std::size_t>(parameters.realizations));
        live_ = std::vector<LiveStatus>(static_cast<std::size_t>(parameters.realizations));
        for (auto& live : live_) live.stop = stop;
        finished_ = std::vector<std::atomic<bool>>(static_cast<std::size_t>(parameters.realizations));
    }

    EnsembleResult run(const ProgressCallback& progress) {
        const auto wall_start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
        const int threads = std::clamp<int>(parameters_.threads > 0 ? parameters_.threads : static_cast<int>(hardware),
                                            1, parameters_.realizations);
        std::vector<std::thread> workers;
        for (int w = 0; w < threads; ++w) workers.emplace_back([this] { work(); });
        for (;;) {
            std::unique_lock lock(progress_mutex_);
            const bool all_finished = progress_condition_.wait_for(lock, std::chrono::seconds(1),
                                                                   [&] { return finished_workers_ == threads; });
            if (all_finished) break;
            lock.unlock();
            if (progress) progress(snapshot_progress(wall_start));
        }
        for (auto& worker : workers) worker.join();
        // A worker's exception (std::bad_alloc at huge N, an engine's internal
        // check) is rethrown here, on the caller's thread: escaping a
        // std::thread it would have aborted the process.
        if (failure_) std::rethrow_exception(failure_);
        result_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        result_.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        result_.peak_memory_bytes = 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux reports KiB
        if (progress) progress(snapshot_progress(wall_start));
        merge_outputs();
        return std::move(result_);
    }

private:
    void work() {
        for (;;) {
            const std::int64_t k = next_.fetch_add(1);
            if (k >= parameters_.realizations || (stop_ && stop_->load())) break;
            try {
                run_realization(k);
            } catch (...) {
                std::lock_guard lock(progress_mutex_);
                if (!failure_) failure_ = std::current_exception();
                next_.store(parameters_.realizations);  // no further realizations
                break;
            }
            finished_[static_cast<std::size_t>(k)].store(true);
            done_.fetch_add(1);
        }
        {
            std::lock_guard lock(progress_mutex_);
            ++finished_workers_;
        }
        progress_condition_.notify_all();
    }

    void run_realization(std::int64_t k) {
        const auto index = static_cast<std::size_t>(k);
        RealizationOutput& out = outputs_[index];
        const InitialCondition initial =
            initial_override_ ? *initial_override_
                              : generate_initial_condition(parameters_.particles, parameters_.effective_ring_length(),
                                                           parameters_.seed, parameters_.first_realization + k);
        try {
            run_realization_with(k, initial, make_engine(parameters_, initial, &live_[index]));
        } catch (const StallUndecidable&) {
            // The windowed engine cannot decide the stall detector (see
            // StallUndecidable): redo the realization with the global loop,
            // which it matches bit for bit up to that point and which detects
            // the stall exactly. Discard the partial rows and records first.
            out = RealizationOutput{};
            const std::size_t samples = result_.times.size();
            for (auto* table : {&result_.temperature, &result_.collisions_per_particle, &result_.clusters,
                                &result_.kinetic_energy})
                std::fill_n(table->begin() + static_cast<std::ptrdiff_t>(index * samples), samples, not_reached);
            run_realization_with(k, initial,
                                 std::make_unique<EventEngine>(initial, parameters_.collision, parameters_.collapse,
                                                               &live_[index]));
        }
    }

    void run_realization_with(std::int64_t k, const InitialCondition& initial, std::unique_ptr<Engine> engine) {
        const auto index = static_cast<std::size_t>(k);
        RealizationOutput& out = outputs_[index];
        const double particles = static_cast<double>(initial.size());
        out.histogram_counts.assign(histogram_times_.size(), {});
        ClusterState state;
        const std::size_t samples = result_.times.size();
        out.status = RealizationStatus::complete;
        for (std::size_t s = 0; s < samples; ++s) {
            const double t = result_.times[s];
            if (!engine->advance_to(t)) {
                out.status = engine->collapse() ? RealizationStatus::collapsed : RealizationStatus::interrupted;
                break;
            }
            engine->clusters(state);
            const Moments moments = velocity_moments(state.velocity, state.mass);
            const std::size_t cell = index * samples + s;
            result_.temperature[cell] = moments.temperature;
            result_.kinetic_energy[cell] = moments.kinetic_energy;
            result_.collisions_per_particle[cell] = static_cast<double>(engine->collisions()) / particles;
            result_.clusters[cell] = static_cast<double>(engine->cluster_count());
            if (contains(parameters_.snapshot_times, t)) out.snapshots.push_back({k, state});
            const auto h = std::find(histogram_times_.begin(), histogram_times_.end(), t);
            if (h != histogram_times_.end()) {
                const auto edges = histogram_edges(t, parameters_.histogram_bins, parameters_.histogram_range);
                accumulate_histogram(state, moments.mean_velocity, edges,
                                     out.histogram_counts[static_cast<std::size_t>(h - histogram_times_.begin())]);
            }
        }
        if (const auto& report = engine->collapse()) {
            CollapseRecord record{k, *report, engine->collisions(), {}};
            engine->clusters(record.state);
            out.collapse.push_back(std::move(record));
        }
        out.collisions = engine->collisions();
        live_[index].collisions.store(out.collisions);
        live_[index].time.store(engine->time());
    }

    Progress snapshot_progress(std::chrono::steady_clock::time_point start) const {
        Progress p;
        p.realizations = parameters_.realizations;
        p.realizations_done = done_.load();
        p.elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        double work = 0.0;
        std::uint64_t collisions = 0;
        for (std::size_t k = 0; k < live_.size(); ++k) {
            const double t = live_[k].time.load(std::memory_order_relaxed);
            collisions += live_[k].collisions.load(std::memory_order_relaxed);
            p.latest_time = std::max(p.latest_time, t);
            // Collisions up to time t grow roughly as t^(2/3) once the gas
            // clusters, so (t / t_max)^(2/3) estimates the share of work done.
            work += finished_[k].load() ? 1.0 : std::pow(std::min(1.0, t / parameters_.t_max), 2.0 / 3.0);
        }
        p.fraction_done = std::min(1.0, std::max(work, static_cast<double>(p.realizations_done)) / parameters_.realizations);
        p.collisions_per_second = p.elapsed_seconds > 0 ? static_cast<double>(collisions) / p.elapsed_seconds : 0.0;
        p.eta_seconds = p.fraction_done > 0.01 ? p.elapsed_seconds * (1.0 - p.fraction_done) / p.fraction_done : -1.0;
        return p;
    }

    void merge_outputs() {
        const auto bins = static_cast<std::size_t>(parameters_.histogram_bins) + 2;
        for (const double t : histogram_times_) {
            HistogramRecord record;
            record.time = t;
            record.edges = histogram_edges(t, parameters_.histogram_bins, parameters_.histogram_range);
            record.counts.assign(static_cast<std::size_t>(parameters_.realizations) * bins, 0.0);
            result_.histograms.push_back(std::move(record));
        }
        bool collapsed = false, interrupted = false;
        for (std::size_t k = 0; k < outputs_.size(); ++k) {
            RealizationOutput& out = outputs_[k];
            result_.realization_status.push_back(static_cast<std::int64_t>(out.status));
            collapsed |= out.status == RealizationStatus::collapsed;
            interrupted |= out.status == RealizationStatus::interrupted || out.status == RealizationStatus::not_run;
            result_.total_collisions += out.collisions;
            for (auto& snapshot : out.snapshots) result_.snapshots.push_back(std::move(snapshot));
            for (auto& collapse : out.collapse) result_.collapses.push_back(std::move(collapse));
            for (std::size_t h = 0; h < out.histogram_counts.size(); ++h)
                if (!out.histogram_counts[h].empty())
                    std::copy(out.histogram_counts[h].begin(), out.histogram_counts[h].end(),
                              result_.histograms[h].counts.begin() + static_cast<std::ptrdiff_t>(k * bins));
        }
        result_.status = interrupted ? "interrupted" : collapsed ? "collapsed" : "complete";
    }

    const SimulationParameters& parameters_;
    const InitialCondition* initial_override_;
    const std::atomic<bool>* stop_;
    EnsembleResult result_;
    std::vector<double> histogram_times_;
    std::vector<RealizationOutput> outputs_;
    std::vector<LiveStatus> live_;
    std::vector<std::atomic<bool>> finished_;
    std::exception_ptr failure_;  // the first worker exception, guarded by progress_mutex_
    std::atomic<std::int64_t> next_{0};
    std::atomic<std::int64_t> done_{0};
    int finished_workers_ = 0;
    std::mutex progress_mutex_;
    std::condition_variable progress_condition_;
};

}  // namespace

EnsembleResult run_ensemble(const SimulationParameters& parameters, const InitialCondition* initial_override,
                            const std::atomic<bool>* stop, const ProgressCallback& progress) {
    validate(parameters);
    if (initial_override) {
        validate(*initial_override);
        if (parameters.realizations != 1)
            throw InputError("--init gives one initial condition: realizations must be 1");
    }
    EnsembleRunner runner(parameters, initial_override, stop);
    return runner.run(progress);
}

std::string format_progress(const Progress& p) {
    const std::string eta = p.eta_seconds < 0 ? "--" : fmt::format("{:.0f} s", p.eta_seconds);
    return fmt::format("t = {:.4g}  realizations {}/{}  {:.1f}%  {:.3g} collisions/s  elapsed {:.0f} s  ETA {}",
                       p.latest_time, p.realizations_done, p.realizations, 100.0 * p.fraction_done,
                       p.collisions_per_second, p.elapsed_seconds, eta);
}

}  // namespace shockgas
