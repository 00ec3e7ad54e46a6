// The ensemble driver: runs R independent realizations (in parallel on
// `threads` threads), samples every realization at the same times, and
// collects snapshots, histograms and collapse reports. Realization k always
// uses the same seed stream and writes only its own row, so the result is
// bit-identical for any thread count.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shockgas/engine.hpp"
#include "shockgas/parameters.hpp"
#include "shockgas/state.hpp"

namespace shockgas {

// in_progress appears only in checkpoints: a realization whose engine state
// the checkpoint holds.
enum class RealizationStatus : std::int64_t { complete = 0, collapsed = 1, interrupted = 2, not_run = 3, in_progress = 4 };

struct SnapshotRecord {
    std::int64_t realization = 0;
    ClusterState state;
};

struct HistogramRecord {
    double time = 0.0;
    std::vector<double> edges;   // bins + 1 edges of v - V (velocity units)
    std::vector<double> counts;  // R x (bins + 2): underflow, bins, overflow; mass-weighted
};

struct CollapseRecord {
    std::int64_t realization = 0;
    CollapseReport report;
    std::uint64_t collisions = 0;
    ClusterState state;  // the ring at the moment of collapse
};

struct EnsembleResult {
    std::vector<double> times;  // K sample times
    std::int64_t realizations = 0;
    // R x K, row-major; NaN where a realization did not reach the time.
    std::vector<double> temperature;
    std::vector<double> collisions_per_particle;
    std::vector<double> clusters;
    std::vector<double> kinetic_energy;
    std::vector<SnapshotRecord> snapshots;    // ordered by (realization, time)
    std::vector<HistogramRecord> histograms;  // ordered by time
    std::vector<CollapseRecord> collapses;    // ordered by realization
    std::vector<std::int64_t> realization_status;
    // R: Engine::switch_time() of each realization when it stopped (NaN for
    // engines that never switch, +infinity for a hybrid that had not).
    std::vector<double> engine_switch_time;
    std::string status;  // complete | interrupted | collapsed
    std::string engine;
    std::uint64_t total_collisions = 0;
    double cpu_seconds = 0.0;
    double wall_seconds = 0.0;
    double peak_memory_bytes = 0.0;  // resident set high-water mark of the process
};

// The R x K tables of EnsembleResult, for code that copies or joins rows.
using SampleTable = std::vector<double> EnsembleResult::*;
inline constexpr std::array<SampleTable, 4> sample_tables = {
    &EnsembleResult::temperature, &EnsembleResult::collisions_per_particle, &EnsembleResult::clusters,
    &EnsembleResult::kinetic_energy};

// Room for `realizations` realizations in r: the sample tables and histogram
// rows of the new ones are NaN and zero, their status not_run, their hand-over
// time NaN (what a realization that never ran records). Existing rows stay.
void grow_realizations(EnsembleResult& r, std::int64_t realizations);

// Realization j of `from` becomes realization k of `to` (which must have room
// for it, grow_realizations), replacing whatever `to` held for k: its rows of
// the sample tables and histograms, its status and hand-over time, and its
// snapshots and collapse records, renumbered and kept in the order
// EnsembleResult promises. If `to` has no histograms yet it takes `from`'s
// times and edges. The one way realizations move between results: joining
// parts (merge_outputs) and gathering a block from other blocks'
// checkpoints (gather_checkpoint).
void copy_realization(const EnsembleResult& from, std::int64_t j, EnsembleResult& to, std::int64_t k);

// What the driver reports while running, about once a second.
struct Progress {
    double fraction_done = 0.0;    // estimated share of the work done, in [0, 1]
    double latest_time = 0.0;      // simulated time of the most advanced running realization
    double collisions_per_second = 0.0;
    double elapsed_seconds = 0.0;
    double eta_seconds = 0.0;      // negative when not yet estimable
    std::int64_t realizations_done = 0;
    std::int64_t realizations = 0;
};
using ProgressCallback = std::function<void(const Progress&)>;

// Checkpoints, so that a run survives being killed. Every interval_seconds
// of wall time the driver asks each running realization to pause between two
// events, copies its engine state (Engine::snapshot) and lets it go on at
// once, then writes the finished realizations, the partial ones and their
// engine states to `path` (temporary file, then rename: a kill during the
// write leaves the previous checkpoint). A run stopped through `stop` writes
// one last checkpoint. With resume, a checkpoint of the same run at `path`
// (same run_signature and code version) is loaded and the run continues from
// it; the result is bit-identical to an uninterrupted run, because pausing
// changes nothing (the engines return between events and go on from exactly
// that state) and a snapshot holds the whole engine state. A checkpoint of a
// different code version is ignored, with a note; one of a run with other
// parameters is refused (InputError, before any work: check_checkpoint_of_run
// in checkpoint.hpp). The caller removes the checkpoint once the output is
// safely written.
struct CheckpointOptions {
    std::string path;                // empty: no checkpoints
    double interval_seconds = 300.0; // wall time between checkpoints
    bool resume = false;
    std::function<void(const std::string&)> note;  // one-line messages: written, resumed, ignored
    // With resume, when path holds no checkpoint of this very block: other
    // checkpoints of the same run, cut into other blocks (the ranks of an MPI
    // job with another number of ranks, or one process's), from which this
    // block's realizations are gathered (gather_checkpoint, checkpoint.hpp).
    std::vector<std::string> other_blocks;
    // Filled with the files gathered from, so that the caller can remove them
    // once the output is safely written.
    std::vector<std::string>* gathered_from = nullptr;
    // The whole run's realizations [run_first_realization, + run_realizations)
    // when the parameters given to run_ensemble are one MPI rank's block of it;
    // run_realizations 0: that block is the whole run. A checkpoint with
    // realizations outside the whole run belongs to another run.
    std::int64_t run_first_realization = 0;
    std::int64_t run_realizations = 0;
    // Write a last checkpoint when the block runs to its end, too (with path
    // set). An MPI rank whose block ends before another rank is stopped cannot
    // yet tell whether the job will end interrupted; this checkpoint keeps its
    // finished realizations for --resume, and is removed once rank 0 reports
    // the job complete (DistributedSession::job_complete).
    bool checkpoint_when_done = false;
};

// Runs the ensemble. initial_override, when non-null, replaces the generated
// initial condition (the --init file; then realizations must be 1).
// stop may be raised from a signal handler: the run ends within milliseconds
// and the result is marked interrupted.
EnsembleResult run_ensemble(const SimulationParameters& parameters, const InitialCondition* initial_override,
                            const std::atomic<bool>* stop = nullptr, const ProgressCallback& progress = {},
                            const CheckpointOptions& checkpoint = {});

// One line of progress for a terminal: time, rate, ETA.
std::string format_progress(const Progress& progress);

// When a log (stderr not a terminal: a batch job's log file) gets a progress
// line: every interval_seconds of wall time, at each tenth of the work done,
// and once at the end, so a log shows a live job without filling up. The
// driver reports about once a second; due() picks the reports to print.
class ProgressLog {
public:
    explicit ProgressLog(double interval_seconds) : interval_seconds_(interval_seconds) {}
    bool due(const Progress& progress);

private:
    double interval_seconds_;
    double last_line_seconds_ = 0.0;
    int last_tenth_ = 0;
};

}  // namespace shockgas
