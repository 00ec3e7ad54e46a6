// SPDX-License-Identifier: GPL-3.0-or-later
// Checkpoint integrity: where a run's checkpoints live, how they are saved and
// loaded, and who may use them. The format itself (the output schema plus
// /checkpoint) is written and read in output.hpp, with the output schema.
//
// - Two generations: saving renames the current checkpoint to PATH.previous
//   before the new one takes its name, so a damaged file has a fallback.
// - Loading verifies every checksum (h5::File::open_read) and the layout
//   against the run; a damaged or truncated checkpoint never ends a run: the
//   older generation is used, or the run starts from t = 0, with one warning
//   line saying which. Either way the result equals an uninterrupted run's.
// - A lock (PATH.lock, flock) lets one process at a time use a checkpoint.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

using Note = std::function<void(const std::string&)>;

// PATH.previous: the older generation of the checkpoint at path.
std::string previous_checkpoint_path(const std::string& path);
// Both files of the checkpoint at path, newest first: path itself, then
// previous_checkpoint_path. Whatever reads, checks, moves or removes both
// files of a checkpoint walks these.
std::array<std::string, 2> checkpoint_generations(const std::string& path);

// Writes checkpoint to path atomically, keeping the one it replaces as the
// previous generation. Throws h5::Error naming path and the cause (full disk,
// file-size limit); the previous checkpoint is then kept untouched.
void save_checkpoint(const std::string& path, const Checkpoint& checkpoint);

// --resume's rule for a checkpoint that passed its checksums (a damaged one
// cannot be compared; it is passed over with a warning): it must belong to
// the run `run` (the whole run: every MPI rank's realizations), i.e. have the
// same physics_signature and, with check_realizations, hold realizations
// within run's. Otherwise throws InputError, before any work, naming `file`,
// every parameter that differs with both values (parameter_differences, as
// shockgas-merge says it; "t-max 500 vs 1000 in the checkpoint") and how to
// start anew: continuing would overwrite it and the end of the run remove it.
void check_checkpoint_of_run(const std::string& file, const Checkpoint& checkpoint, const SimulationParameters& run,
                             bool check_realizations = true);
// The same for every generation of `files` that can be read and was written
// by this code version: what a job about to gather from them checks first
// (shockgas-sim's rank 0, before the ranks start).
void check_resume_checkpoints(const std::vector<std::string>& files, const SimulationParameters& run);
// For --resume --set-aside-other-runs: every readable checkpoint among `files`
// (both generations) that belongs to a run with other parameters, by this
// simulator, is moved aside to '<file>.from-other-run' (and its '.previous'),
// instead of being refused, so that the run starts anew where its own record
// (the figure pipeline's parameter file) says it is another run; returns one
// note per file moved, naming what differed. Damaged files and other
// simulators' checkpoints are left to the loader, which says what it does.
std::vector<std::string> set_aside_other_runs(const std::vector<std::string>& files, const SimulationParameters& run);

// A run without --resume, before any work: throws InputError if a generation
// of `files` (the run's checkpoint path and every file a --resume of it would
// read or gather from) holds a checkpoint, whatever its run or code version:
// the run would redo what it holds, overwrite it and remove it at its end. The
// one line says how far it got, when it was saved, and --resume (when this run
// can continue it) or which files to remove to start anew. A lock held by a
// running process is refused as CheckpointLock refuses it. A damaged
// generation (as --resume passes over) does not refuse: returned, one warning
// line each, for the caller to print. Files that are not checkpoints are left
// to check_checkpoint_path.
std::vector<std::string> check_no_interrupted_run(const std::vector<std::string>& files,
                                                  const SimulationParameters& run);

// --resume, before any work: whether `output` already holds the finished
// result of the run `run`, so that there is nothing to continue and nothing to
// recompute: an output whose status is not interrupted (complete or
// collapsed), written by this code version, of the same run as --resume asks
// of a checkpoint (run_signature: physics, sampling, seed and realizations;
// and the engine, which `run` names resolved),
// while no generation of `checkpoints` (job_checkpoints: what the run would
// continue or gather from) exists. The output is read once, and only if it
// is a regular file; one that cannot be read (damaged, not an output) is
// none: the run replaces it, as without --resume.
bool is_finished_output_of_run(const std::string& output, const std::vector<std::string>& checkpoints,
                               const SimulationParameters& run);

// The newest usable checkpoint of the run with these parameters and sample
// times, from path or else its previous generation; nothing if there is none,
// or if it was written by another code version (noted). A damaged one is
// passed over with one warning line through note. One of another run
// (check_checkpoint_of_run against whole_run, default `parameters`) throws
// InputError; one of another block of the same run (realizations within
// whole_run, not these) gives nothing and sets *another_block: the caller
// gathers from it (gather_checkpoint).
std::optional<Checkpoint> load_checkpoint(const std::string& path, const SimulationParameters& parameters,
                                          const std::vector<double>& sample_times, const Note& note,
                                          const SimulationParameters* whole_run = nullptr,
                                          bool* another_block = nullptr);

// This run's realizations gathered from checkpoints of the same run cut into
// other blocks: an MPI job resumed with another number of ranks (each rank
// kept PATH.rank<k> of its own block), or one process resuming an MPI job and
// the reverse. Every candidate (and its previous generation) whose physics,
// sample times and code version match contributes the realizations of its
// block that fall in this one (parameters.first_realization and
// parameters.realizations); where candidates overlap, the record that got
// further wins. The checkpoint returned is this block's, as load_checkpoint
// gives it (realizations no candidate holds: not run, status 3), with the
// candidates' CPU and wall time shared out by the realizations taken.
// `sources` gets every file of this run that was read (the caller removes
// them once the output is written). Nothing if no candidate holds any of
// this block's realizations. A candidate of another run (other physics, or,
// when whole_run is given, realizations outside it) throws InputError
// (check_checkpoint_of_run): it would be removed with the others.
std::optional<Checkpoint> gather_checkpoint(const std::vector<std::string>& candidates,
                                            const SimulationParameters& parameters,
                                            const std::vector<double>& sample_times, const Note& note,
                                            std::vector<std::string>* sources = nullptr,
                                            const SimulationParameters* whole_run = nullptr);

// BASE.rank<k>: rank k's checkpoint when BASE is the run's checkpoint path
// and the job has more than one MPI rank.
std::string rank_checkpoint_path(const std::string& base, int rank);
// The checkpoints another job of the same run may have left, other than own:
// base (one process) and base.rank0, base.rank1, ... (MPI ranks) for as long
// as they (or their previous generations) exist.
std::vector<std::string> other_block_checkpoints(const std::string& base, const std::string& own);

// Every checkpoint file a job of `ranks` processes with checkpoint path `base`
// may continue from: its own first (base itself, or each rank's
// rank_checkpoint_path), then the other blocks' files that gathering takes
// (other_block_checkpoints), each once. What check_no_interrupted_run and,
// under MPI, check_resume_checkpoints look at before a run starts.
std::vector<std::string> job_checkpoints(const std::string& base, int ranks);
// After the output is written: removes the checkpoints a rank gathered from
// (gather_checkpoint's sources, either generation), except those of the
// current job's own ranks, which each rank removes itself.
void remove_gathered_checkpoints(const std::vector<std::string>& sources, const std::string& base, int ranks);

// Removes both generations (the output they served is safely written), each
// only if it is a shockgas checkpoint or an HDF5 file too damaged to tell:
// never another file that has the checkpoint's name. Returns those kept.
std::vector<std::string> remove_checkpoints(const std::string& path);

// Before a run uses the checkpoint at path: throws InputError if one of its
// files (either generation, the lock) is one of `others` ({role, path}, such
// as {"output", "run.h5"}; empty paths are skipped), or if a file already
// there is not a checkpoint (or lock): saving would overwrite it and the end
// of the run would remove it.
void check_checkpoint_path(const std::string& path, const std::vector<std::pair<std::string, std::string>>& others);

// An exclusive lock on the checkpoint at path, held while the object lives
// (flock on PATH.lock, released by the kernel if the process dies). Throws
// InputError if another live process holds it.
class CheckpointLock {
public:
    explicit CheckpointLock(const std::string& checkpoint_path);
    ~CheckpointLock();
    static std::string lock_path(const std::string& checkpoint_path) { return checkpoint_path + ".lock"; }
    CheckpointLock(const CheckpointLock&) = delete;
    CheckpointLock& operator=(const CheckpointLock&) = delete;

private:
    std::string lock_path_;
    int descriptor_ = -1;
};

}  // namespace shockgas
