// SPDX-License-Identifier: GPL-3.0-or-later
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

#include "shockgas/model/parameters.hpp"
#include "shockgas/model/records.hpp"
#include "shockgas/model/state.hpp"
#include "shockgas/run/progress.hpp"

namespace shockgas {

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

}  // namespace shockgas
