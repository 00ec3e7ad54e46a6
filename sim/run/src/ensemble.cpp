// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/run/ensemble.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <iterator>
#include <mutex>
#include <optional>
#include <thread>

#include <sys/resource.h>

#include <fmt/format.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/run/checkpoint.hpp"
#include "shockgas/model/observables.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"

namespace shockgas {

namespace {

constexpr double not_reached = std::numeric_limits<double>::quiet_NaN();
// Marks the engine states deposited when the user stopped the run: they go
// into the last checkpoint whatever checkpoint was requested before.
constexpr std::uint64_t final_epoch = std::numeric_limits<std::uint64_t>::max();

bool contains(const std::vector<double>& times, double t) {
    return std::find(times.begin(), times.end(), t) != times.end();
}

// Everything one realization produces, gathered by its worker and merged into
// the ensemble in realization order afterwards.
struct RealizationOutput {
    std::vector<SnapshotRecord> snapshots;
    std::vector<std::vector<double>> histogram_counts;  // one per histogram time; empty until reached
    std::vector<CollapseRecord> collapse;
    RealizationStatus status = RealizationStatus::not_run;
    std::uint64_t collisions = 0;
    std::int64_t samples_done = 0;  // sample times recorded
    double engine_switch_time = std::numeric_limits<double>::quiet_NaN();  // Engine::switch_time()
};

// A running realization's state, handed by its worker to the checkpoint
// writer: the engine state and everything recorded up to samples_done.
struct Deposit {
    std::uint64_t epoch = 0;
    std::optional<EngineSnapshot> engine;  // empty: the engine reruns from t = 0 instead
    RealizationOutput output;
    std::array<std::vector<double>, sample_tables.size()> rows;  // its rows of `sample_tables`
};

class EnsembleRunner {
public:
    EnsembleRunner(const SimulationParameters& parameters, const InitialCondition* initial_override,
                   const std::atomic<bool>* stop, const CheckpointOptions& checkpoint)
        : parameters_(with_engine_resolved(parameters, initial_override)),
          initial_override_(initial_override),
          stop_(stop),
          checkpoint_(checkpoint) {
        result_.times = sample_grid(parameters);
        result_.realizations = parameters.realizations;
        result_.engine = parameters_.engine;
        histogram_times_ = parameters.histogram_times;
        std::sort(histogram_times_.begin(), histogram_times_.end());
        histogram_times_.erase(std::unique(histogram_times_.begin(), histogram_times_.end()), histogram_times_.end());
        const std::size_t cells = static_cast<std::size_t>(parameters.realizations) * result_.times.size();
        for (const SampleTable table : sample_tables) (result_.*table).assign(cells, not_reached);
        const auto realizations = static_cast<std::size_t>(parameters.realizations);
        outputs_.resize(realizations);
        for (auto& out : outputs_) out.histogram_counts.assign(histogram_times_.size(), {});
        live_ = std::vector<LiveStatus>(realizations);
        started_ = std::vector<std::atomic<bool>>(realizations);
        finished_ = std::vector<std::atomic<bool>>(realizations);
        pause_ = std::vector<std::atomic<bool>>(realizations);
        deposits_.resize(realizations);
        resume_.resize(realizations);
        collisions_before_ = std::vector<std::atomic<std::uint64_t>>(realizations);
        for (std::size_t k = 0; k < realizations; ++k) {
            live_[k].stop = stop;
            live_[k].abort = &abort_;
            live_[k].pause = &pause_[k];
        }
        if (checkpoint_.resume && !checkpoint_.path.empty()) resume_from_checkpoint();
    }

    EnsembleResult run(const ProgressCallback& progress) {
        const auto wall_start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
        threads_ = std::clamp<int>(parameters_.threads > 0 ? parameters_.threads : static_cast<int>(hardware), 1,
                                   parameters_.realizations);
        const bool checkpoints = !checkpoint_.path.empty() && checkpoint_.interval_seconds > 0.0;
        // Wake at least once a second for progress, and in time for checkpoints.
        const auto tick = std::chrono::duration<double>(
            checkpoints ? std::min(1.0, checkpoint_.interval_seconds) : 1.0);
        auto last_checkpoint = wall_start;
        std::vector<std::thread> workers;
        for (int w = 0; w < threads_; ++w) workers.emplace_back([this] { work(); });
        for (;;) {
            std::unique_lock lock(progress_mutex_);
            const bool all_finished =
                progress_condition_.wait_for(lock, tick, [&] { return finished_workers_ == threads_; });
            if (all_finished) break;
            lock.unlock();
            if (progress) progress(snapshot_progress(wall_start));
            const auto now = std::chrono::steady_clock::now();
            if (checkpoints && std::chrono::duration<double>(now - last_checkpoint).count() >= checkpoint_.interval_seconds &&
                !halted()) {
                try {
                    take_checkpoint(wall_start, cpu_start);
                } catch (...) {
                    // A checkpoint that cannot be written (full disk, file-size
                    // limit) stops the run: the previous checkpoint is kept, so
                    // the run can be resumed once there is room.
                    std::lock_guard guard(progress_mutex_);
                    if (!failure_) failure_ = std::current_exception();
                    abort_.store(true);
                    next_.store(parameters_.realizations);
                }
                last_checkpoint = std::chrono::steady_clock::now();
            }
        }
        for (auto& worker : workers) worker.join();
        // A worker's exception (std::bad_alloc at huge N, an engine's internal
        // check) is rethrown here, on the caller's thread: escaping a
        // std::thread it would have aborted the process.
        if (failure_) std::rethrow_exception(failure_);
        // Stopped by the user: keep what the run reached, to resume it. Or ran
        // to its end as one block of a job that may yet end interrupted.
        if (!checkpoint_.path.empty() && ((stop_ && stop_->load()) || checkpoint_.checkpoint_when_done))
            write_checkpoint_now(final_epoch, wall_start, cpu_start);
        result_.wall_seconds = previous_wall_seconds_ + seconds_since(wall_start);
        result_.cpu_seconds = previous_cpu_seconds_ + cpu_seconds_since(cpu_start);
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        result_.peak_memory_bytes = 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux reports KiB
        if (progress) progress(snapshot_progress(wall_start));
        assemble(outputs_, result_);
        return std::move(result_);
    }

private:
    static double seconds_since(std::chrono::steady_clock::time_point start) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    static double cpu_seconds_since(std::clock_t start) {
        return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    }

    bool halted() const { return (stop_ && stop_->load()) || abort_.load(); }

    void work() {
        for (;;) {
            const std::int64_t k = next_.fetch_add(1);
            if (k >= parameters_.realizations || halted()) break;
            const auto index = static_cast<std::size_t>(k);
            if (finished_[index].load()) continue;  // done before the checkpoint we resumed from
            started_[index].store(true);
            try {
                run_realization_named(k);
            } catch (...) {
                std::lock_guard lock(progress_mutex_);
                if (!failure_) failure_ = std::current_exception();
                next_.store(parameters_.realizations);  // no further realizations
                break;
            }
            {
                std::lock_guard lock(progress_mutex_);
                finished_[index].store(true);
            }
            progress_condition_.notify_all();
        }
        {
            std::lock_guard lock(progress_mutex_);
            ++finished_workers_;
        }
        progress_condition_.notify_all();
    }

    void run_realization(std::int64_t k) {
        const auto index = static_cast<std::size_t>(k);
        const InitialCondition initial =
            initial_override_ ? *initial_override_
                              : generate_initial_condition(parameters_.particles, parameters_.effective_ring_length(),
                                                           parameters_.seed, parameters_.first_realization + k,
                                                           parameters_.initial_law);
        try {
            if (resume_[index]) {
                const EngineSnapshot snapshot = std::move(*resume_[index]);
                resume_[index].reset();
                const auto engine = restore_engine(snapshot, parameters_, initial, &live_[index]);
                collisions_before_[index].store(engine->collisions());  // done before the checkpoint
                run_samples(k, *engine);
            } else {
                run_samples(k, *make_engine(parameters_, initial, &live_[index]));
            }
        } catch (const EngineUndecided&) {
            // The engine cannot decide what comes next (an inelastic stall in
            // the event engine's windows): redo the realization with the
            // factory's fallback engine, which it matches bit for bit up to
            // that point and which decides it. Discard the partial rows and
            // records first.
            outputs_[index] = RealizationOutput{};
            outputs_[index].histogram_counts.assign(histogram_times_.size(), {});
            const std::size_t samples = result_.times.size();
            for (const SampleTable table : sample_tables)
                std::fill_n((result_.*table).begin() + static_cast<std::ptrdiff_t>(index * samples), samples,
                            not_reached);
            const auto engine = make_fallback_engine(parameters_, initial, &live_[index]);
            collisions_before_[index].store(0);  // from t = 0: all this process's
            run_samples(k, *engine);
        }
    }

    // run_realization, with a numerical failure (NumericalFailure: the run
    // cannot go on where the model can) naming the realization.
    void run_realization_named(std::int64_t k) {
        try {
            run_realization(k);
        } catch (const NumericalFailure& failure) {
            throw NumericalFailure(fmt::format("realization {}: {}", k, failure.what()));
        }
    }

    // Advances realization k from its next unrecorded sample time to t_max,
    // recording each sample; pauses for checkpoints when asked.
    void run_samples(std::int64_t k, Engine& engine) {
        const auto index = static_cast<std::size_t>(k);
        RealizationOutput& out = outputs_[index];
        const double particles = static_cast<double>(parameters_.particles);
        ClusterState state;
        const std::size_t samples = result_.times.size();
        out.status = RealizationStatus::complete;
        for (auto s = static_cast<std::size_t>(out.samples_done); s < samples;) {
            const double t = result_.times[s];
            if (!engine.advance_to(t)) {
                if (engine.collapse()) {
                    out.status = RealizationStatus::collapsed;
                    break;
                }
                const bool interrupted = halted();
                deposit(k, engine, interrupted);
                if (interrupted) {
                    out.status = RealizationStatus::interrupted;
                    break;
                }
                continue;  // paused for a checkpoint: go on to the same sample time
            }
            engine.clusters(state);
            const Moments moments = velocity_moments(state);
            const std::size_t cell = index * samples + s;
            result_.temperature[cell] = moments.temperature;
            result_.kinetic_energy[cell] = moments.kinetic_energy;
            result_.collisions_per_particle[cell] = static_cast<double>(engine.collisions()) / particles;
            result_.clusters[cell] = static_cast<double>(engine.cluster_count());
            if (contains(parameters_.snapshot_times, t)) out.snapshots.push_back({k, state});
            const auto h = std::find(histogram_times_.begin(), histogram_times_.end(), t);
            if (h != histogram_times_.end()) {
                const auto edges = histogram_edges(t, parameters_.histogram_bins, parameters_.histogram_range);
                accumulate_histogram(state, moments.frame_mean_velocity, edges,
                                     out.histogram_counts[static_cast<std::size_t>(h - histogram_times_.begin())]);
            }
            out.samples_done = static_cast<std::int64_t>(++s);
            out.collisions = engine.collisions();
            if (pause_[index].load(std::memory_order_relaxed)) deposit(k, engine, false);
        }
        if (const auto& report = engine.collapse()) {
            CollapseRecord record{k, *report, engine.collisions(), {}};
            engine.clusters(record.state);
            out.collapse.push_back(std::move(record));
        }
        out.collisions = engine.collisions();
        out.engine_switch_time = engine.switch_time();
        live_[index].collisions.store(out.collisions);
        live_[index].time.store(engine.time());
    }

    // Hands realization k's state to the checkpoint writer and clears its
    // pause request. Called by k's worker between two events.
    void deposit(std::int64_t k, const Engine& engine, bool final) {
        const auto index = static_cast<std::size_t>(k);
        if (checkpoint_.path.empty()) {
            pause_[index].store(false);
            return;
        }
        Deposit d;
        d.engine = engine.snapshot();
        d.output = outputs_[index];
        d.output.collisions = engine.collisions();
        const std::size_t samples = result_.times.size();
        for (std::size_t t = 0; t < sample_tables.size(); ++t) {
            const auto begin = (result_.*sample_tables[t]).begin() + static_cast<std::ptrdiff_t>(index * samples);
            d.rows[t].assign(begin, begin + static_cast<std::ptrdiff_t>(samples));
        }
        {
            std::lock_guard lock(progress_mutex_);
            d.epoch = final ? final_epoch : epoch_;
            deposits_[index] = std::move(d);
            pause_[index].store(false);
        }
        progress_condition_.notify_all();
    }

    // Asks every running realization for its state, waits until each has
    // answered (or finished), and writes the checkpoint.
    void take_checkpoint(std::chrono::steady_clock::time_point wall_start, std::clock_t cpu_start) {
        std::vector<std::size_t> asked;
        std::uint64_t epoch = 0;
        {
            std::lock_guard lock(progress_mutex_);
            epoch = ++epoch_;
            for (std::size_t k = 0; k < pause_.size(); ++k)
                if (started_[k].load() && !finished_[k].load()) {
                    pause_[k].store(true);
                    asked.push_back(k);
                }
        }
        {
            std::unique_lock lock(progress_mutex_);
            progress_condition_.wait(lock, [&] {
                if (finished_workers_ == threads_) return true;
                return std::all_of(asked.begin(), asked.end(),
                                   [&](std::size_t k) { return !pause_[k].load() || finished_[k].load(); });
            });
        }
        write_checkpoint_now(epoch, wall_start, cpu_start);
    }

    void write_checkpoint_now(std::uint64_t epoch, std::chrono::steady_clock::time_point wall_start,
                              std::clock_t cpu_start) {
        const auto write_start = std::chrono::steady_clock::now();
        Checkpoint checkpoint;
        checkpoint.parameters = parameters_;
        EnsembleResult& r = checkpoint.result;
        r.times = result_.times;
        r.realizations = result_.realizations;
        r.engine = result_.engine;
        const std::size_t samples = result_.times.size();
        for (const SampleTable table : sample_tables) (r.*table).assign((result_.*table).size(), not_reached);
        std::vector<RealizationOutput> outs(outputs_.size());
        checkpoint.samples_done.assign(outputs_.size(), 0);
        {
            std::lock_guard lock(progress_mutex_);
            for (std::size_t k = 0; k < outputs_.size(); ++k) {
                std::optional<Deposit>& d = deposits_[k];
                const bool fresh = d && d->engine && (d->epoch == epoch || d->epoch == final_epoch);
                const auto row = static_cast<std::ptrdiff_t>(k * samples);
                if (finished_[k].load() && outputs_[k].status != RealizationStatus::interrupted) {
                    outs[k] = outputs_[k];
                    for (const SampleTable table : sample_tables)
                        std::copy_n((result_.*table).begin() + row, samples, (r.*table).begin() + row);
                } else if (fresh) {
                    outs[k] = d->output;
                    outs[k].status = RealizationStatus::in_progress;
                    for (std::size_t t = 0; t < sample_tables.size(); ++t)
                        std::copy(d->rows[t].begin(), d->rows[t].end(), (r.*sample_tables[t]).begin() + row);
                    checkpoint.engines.emplace(static_cast<std::int64_t>(k), *d->engine);
                } else {
                    outs[k].status = RealizationStatus::not_run;
                }
                checkpoint.samples_done[k] = outs[k].samples_done;
                // A deposit serves one checkpoint: free its copy of the state.
                // Except a final one (the user stopped the run) taken by a
                // periodic checkpoint that was under way: the last checkpoint,
                // written after the workers end, needs it too, or it would
                // replace a good checkpoint by one with nothing in progress.
                if (epoch == final_epoch || !d || d->epoch != final_epoch) d.reset();
            }
        }
        assemble(outs, r);
        r.status = "checkpoint";
        r.wall_seconds = previous_wall_seconds_ + seconds_since(wall_start);
        r.cpu_seconds = previous_cpu_seconds_ + cpu_seconds_since(cpu_start);
        save_checkpoint(checkpoint_.path, checkpoint);
        if (checkpoint_.note)
            checkpoint_.note(fmt::format("checkpoint: {} realizations in progress, {} collisions -> {} ({:.2f} s)",
                                         checkpoint.engines.size(), r.total_collisions, checkpoint_.path,
                                         seconds_since(write_start)));
    }

    // Continues from the newest usable checkpoint of this run made by this
    // code (checkpoint.hpp verifies it and says why it passes one over).
    void resume_from_checkpoint() {
        // Notes of the first attempt are held back while other blocks may
        // still supply the realizations ("belongs to another run" would be
        // wrong then).
        std::vector<std::string> held;
        const Note hold = [&](const std::string& text) { held.push_back(text); };
        // The whole run, of which these parameters may be one rank's block.
        SimulationParameters run = parameters_;
        if (checkpoint_.run_realizations > 0) {
            run.first_realization = checkpoint_.run_first_realization;
            run.realizations = static_cast<int>(checkpoint_.run_realizations);
        }
        bool another_block = false;  // path holds another block of this run
        std::optional<Checkpoint> loaded = load_checkpoint(checkpoint_.path, parameters_, result_.times, hold, &run,
                                                           &another_block);
        bool gathered = false;
        if (!loaded && (another_block || !checkpoint_.other_blocks.empty())) {
            std::vector<std::string> candidates = checkpoint_.other_blocks;
            candidates.push_back(checkpoint_.path);
            loaded = gather_checkpoint(candidates, parameters_, result_.times, checkpoint_.note,
                                       checkpoint_.gathered_from, &run);
            gathered = loaded.has_value();
        }
        if (!gathered && checkpoint_.note)
            for (const auto& text : held) checkpoint_.note(text);
        if (!loaded) return;
        Checkpoint& checkpoint = *loaded;
        auto note = [&](const std::string& text) {
            if (checkpoint_.note) checkpoint_.note(text);
        };
        const EnsembleResult& r = checkpoint.result;
        const std::size_t samples = result_.times.size();
        const auto bins = static_cast<std::size_t>(parameters_.histogram_bins) + 2;
        const double resume_time = checkpoint_time(checkpoint);
        std::int64_t finished = 0;
        for (std::size_t k = 0; k < outputs_.size(); ++k) {
            const auto status = static_cast<RealizationStatus>(r.realization_status[k]);
            const bool done = status == RealizationStatus::complete || status == RealizationStatus::collapsed;
            const bool in_progress = status == RealizationStatus::in_progress &&
                                     checkpoint.engines.count(static_cast<std::int64_t>(k)) > 0;
            if (!done && !in_progress) continue;
            RealizationOutput& out = outputs_[k];
            out.status = status;
            out.samples_done = checkpoint.samples_done[k];
            out.engine_switch_time = r.engine_switch_time[k];
            const auto row = static_cast<std::ptrdiff_t>(k * samples);
            for (const SampleTable table : sample_tables)
                std::copy_n((r.*table).begin() + row, samples, (result_.*table).begin() + row);
            for (const auto& snapshot : r.snapshots)
                if (snapshot.realization == static_cast<std::int64_t>(k)) out.snapshots.push_back(snapshot);
            for (const auto& collapse : r.collapses)
                if (collapse.realization == static_cast<std::int64_t>(k)) out.collapse.push_back(collapse);
            // A histogram row exists once its time was sampled.
            const double reached = out.samples_done > 0 ? result_.times[static_cast<std::size_t>(out.samples_done) - 1]
                                                        : -1.0;
            for (std::size_t h = 0; h < histogram_times_.size(); ++h)
                if (histogram_times_[h] <= reached) {
                    const auto begin = r.histograms[h].counts.begin() + static_cast<std::ptrdiff_t>(k * bins);
                    out.histogram_counts[h].assign(begin, begin + static_cast<std::ptrdiff_t>(bins));
                }
            // Collisions are recorded per particle at each sample (exact below
            // 2^53 collisions); a collapse record keeps its own count.
            if (!out.collapse.empty())
                out.collisions = out.collapse.back().collisions;
            else if (out.samples_done > 0)
                out.collisions = static_cast<std::uint64_t>(std::llround(
                    r.collisions_per_particle[k * samples + static_cast<std::size_t>(out.samples_done) - 1] *
                    static_cast<double>(parameters_.particles)));
            if (done) {
                finished_[k].store(true);
                ++finished;
            } else {
                resume_[k] = std::move(checkpoint.engines.at(static_cast<std::int64_t>(k)));
                live_[k].collisions.store(out.collisions);
                collisions_before_[k].store(out.collisions);  // until the engine is restored
            }
        }
        previous_cpu_seconds_ = r.cpu_seconds;
        previous_wall_seconds_ = r.wall_seconds;
        std::size_t resumed = 0;
        for (const auto& state : resume_) resumed += state ? 1 : 0;
        note(fmt::format("resuming from '{}': {} realizations done, {} continue (the furthest from t = {:.6g}), {} "
                         "start anew",
                         checkpoint.source, finished, resumed, resume_time,
                         parameters_.realizations - finished - static_cast<std::int64_t>(resumed)));
    }

    static double checkpoint_time(const Checkpoint& checkpoint) {
        double t = 0.0;
        for (const auto& [k, snapshot] : checkpoint.engines) {
            const auto it = snapshot.reals.find("scalars");
            if (it != snapshot.reals.end() && !it->second.empty()) t = std::max(t, it->second.front());
        }
        return t;
    }

    // The facts of the moment; estimates are the caller's (cli::ProgressEstimator).
    Progress snapshot_progress(std::chrono::steady_clock::time_point start) const {
        Progress p;
        p.realizations = parameters_.realizations;
        p.t_max = parameters_.t_max;
        p.elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        p.realization.resize(live_.size());
        for (std::size_t k = 0; k < live_.size(); ++k) {
            RealizationProgress& r = p.realization[k];
            r.time = live_[k].time.load(std::memory_order_relaxed);
            r.collisions = live_[k].collisions.load(std::memory_order_relaxed);
            const std::uint64_t before = collisions_before_[k].load(std::memory_order_relaxed);
            p.collisions_this_process += r.collisions - std::min(r.collisions, before);
            // A realization stopped by a signal has finished running but is not done: the
            // last line of a stopped run must not read "1/1 100.0% ETA 0 s". (outputs_[k] is
            // written before finished_[k] is set, so it is complete once that reads true.)
            const bool finished = finished_[k].load();
            const bool done = finished && outputs_[k].status != RealizationStatus::interrupted;
            r.state = done                    ? RealizationProgress::State::finished
                      : started_[k].load() && !finished ? RealizationProgress::State::running
                                                       : RealizationProgress::State::waiting;
            p.realizations_done += done ? 1 : 0;
        }
        p.collisions_per_second =
            p.elapsed_seconds > 0 ? static_cast<double>(p.collisions_this_process) / p.elapsed_seconds : 0.0;
        return p;
    }

    // Joins per-realization outputs (moved from) into `into`, in realization
    // order: the final result and each checkpoint are assembled the same way.
    void assemble(std::vector<RealizationOutput>& outs, EnsembleResult& into) const {
        const auto bins = static_cast<std::size_t>(parameters_.histogram_bins) + 2;
        into.histograms.clear();
        for (const double t : histogram_times_) {
            HistogramRecord record;
            record.time = t;
            record.edges = histogram_edges(t, parameters_.histogram_bins, parameters_.histogram_range);
            record.counts.assign(static_cast<std::size_t>(parameters_.realizations) * bins, 0.0);
            into.histograms.push_back(std::move(record));
        }
        bool collapsed = false, interrupted = false;
        for (std::size_t k = 0; k < outs.size(); ++k) {
            RealizationOutput& out = outs[k];
            into.realization_status.push_back(static_cast<std::int64_t>(out.status));
            into.engine_switch_time.push_back(out.engine_switch_time);
            collapsed |= out.status == RealizationStatus::collapsed;
            interrupted |= out.status == RealizationStatus::interrupted || out.status == RealizationStatus::not_run;
            into.total_collisions += out.collisions;
            for (auto& snapshot : out.snapshots) into.snapshots.push_back(std::move(snapshot));
            for (auto& collapse : out.collapse) into.collapses.push_back(std::move(collapse));
            for (std::size_t h = 0; h < out.histogram_counts.size(); ++h)
                if (!out.histogram_counts[h].empty())
                    std::copy(out.histogram_counts[h].begin(), out.histogram_counts[h].end(),
                              into.histograms[h].counts.begin() + static_cast<std::ptrdiff_t>(k * bins));
        }
        into.status = interrupted ? "interrupted" : collapsed ? "collapsed" : "complete";
    }

    // A copy with "auto" resolved: checkpoints store, and --resume compares, the engine that runs.
    static SimulationParameters with_engine_resolved(SimulationParameters p, const InitialCondition* initial) {
        p.engine = resolve_engine_name(p, initial);
        return p;
    }
    const SimulationParameters parameters_;
    const InitialCondition* initial_override_;
    const std::atomic<bool>* stop_;
    CheckpointOptions checkpoint_;
    EnsembleResult result_;
    std::vector<double> histogram_times_;
    std::vector<RealizationOutput> outputs_;
    std::vector<LiveStatus> live_;
    std::vector<std::atomic<bool>> started_;
    std::vector<std::atomic<bool>> finished_;   // set under progress_mutex_
    std::vector<std::atomic<bool>> pause_;      // checkpoint requests, one per realization
    std::vector<std::optional<Deposit>> deposits_;             // guarded by progress_mutex_
    std::vector<std::optional<EngineSnapshot>> resume_;        // engine states loaded from a checkpoint
    std::vector<std::atomic<std::uint64_t>> collisions_before_;  // per realization: done before the checkpoint resumed from
    std::uint64_t epoch_ = 0;                                  // checkpoints requested; guarded by progress_mutex_
    double previous_cpu_seconds_ = 0.0;  // spent before the checkpoint we resumed from
    double previous_wall_seconds_ = 0.0;
    std::exception_ptr failure_;  // the first worker or checkpoint exception, guarded by progress_mutex_
    std::atomic<bool> abort_{false};  // raised on failure: every realization stops between two events
    std::atomic<std::int64_t> next_{0};
    int threads_ = 1;
    int finished_workers_ = 0;
    std::mutex progress_mutex_;
    std::condition_variable progress_condition_;
};

}  // namespace

EnsembleResult run_ensemble(const SimulationParameters& parameters, const InitialCondition* initial_override,
                            const std::atomic<bool>* stop, const ProgressCallback& progress,
                            const CheckpointOptions& checkpoint) {
    validate(parameters);
    if (initial_override) {
        validate(*initial_override);
        if (parameters.realizations != 1)
            throw InputError(fmt::format(
                "--init gives one fixed initial condition, so {} realizations would all be the same run: use -R 1, "
                "or draw an ensemble from an initial law (--positions, --velocity-distribution)",
                parameters.realizations));
        if (!parameters.initial_law.is_paper())
            throw InputError("--init gives the initial condition: --positions and --velocity-distribution do not apply");
    }
    EnsembleRunner runner(parameters, initial_override, stop, checkpoint);
    return runner.run(progress);
}

}  // namespace shockgas
