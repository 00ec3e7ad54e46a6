// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/run/simulation.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/io/checksum.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/initial_condition.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/run/checkpoint.hpp"
#include "shockgas/run/memory_plan.hpp"

namespace shockgas {

SimulationOutcome run_simulation(SimulationRequest& request, DistributedSession& session,
                                 const SimulationHooks& hooks) {
    SimulationParameters& p = request.parameters;
    CheckpointOptions& checkpoint = request.checkpoint;
    const std::string& output = request.output;
    p.collision.subthreshold = subthreshold_from_string(request.subthreshold);
    p.initial_law = {position_law_from_string(request.positions),
                     velocity_law_from_string(request.velocity_distribution)};
    if (request.snapshot_interval_given) {
        const auto every = evenly_spaced_times(request.snapshot_interval, p.t_max);
        p.snapshot_times.insert(p.snapshot_times.end(), every.begin(), every.end());
    }
    InitialCondition initial;
    const std::string init_given = p.init_file;  // as the user wrote it, for messages
    if (!p.init_file.empty()) {
        initial = read_initial_condition(p.init_file);
        if (request.particles_given && p.particles != initial.size())
            throw InputError(fmt::format("--particles {} disagrees with the {} particles of '{}'", p.particles,
                                         initial.size(), p.init_file));
        if (request.ring_length_given && p.ring_length != initial.ring_length)
            throw InputError(fmt::format("--ring-length {} disagrees with the ring length {} of '{}'",
                                         p.ring_length, initial.ring_length, p.init_file));
        p.particles = initial.size();
        p.ring_length = initial.ring_length;
        // Recorded so that a result names its start beyond doubt: where
        // it was (absolute) and what it held (SHA-256 of the file).
        p.init_file = std::filesystem::absolute(p.init_file).lexically_normal().string();
        p.init_file_sha256 = file_sha256(p.init_file);
    }
    validate(p);
    if (!p.init_file.empty()) validate_travel(initial, p.t_max);
    // The engine is part of what identifies a run: a checkpoint holds one engine's states, and merge
    // refuses parts of two. "auto" is resolved here (from the start's masses), so that --resume and
    // "already complete" compare the engine that runs, not the word asked for.
    p.engine = resolve_engine_name(p, p.init_file.empty() ? nullptr : &initial);
    std::string checkpoint_file =
        request.checkpoint_file.empty() ? checkpoint_path_for(request.output) : request.checkpoint_file;
    const std::string base_checkpoint = checkpoint_file;
    bool already_written = false;  // rank 0's: --resume of a run whose output is already complete
    if (session.is_root()) {
        h5::check_writable(output);
        h5::check_not_an_input(output, {init_given});
        // An existing output is replaced (a rerun), but only if it is one:
        // a text file or another program's HDF5 file under that name was
        // silently replaced (CLI audit, 2026-11-27). An empty file, or an
        // HDF5 file too damaged to list (a killed write), may go.
        {
            const h5::Probe found = h5::probe(output);
            if (found.kind == h5::Probe::Kind::not_hdf5 ||
                (found.kind == h5::Probe::Kind::hdf5 && !found.holds("timeseries")))
                throw InputError(fmt::format(
                    "'{}' exists and is not a shockgas-sim output ({}): it would be replaced; give -o another "
                    "path, or remove it",
                    output, found.kind == h5::Probe::Kind::hdf5 ? "an HDF5 file without /timeseries"
                                                                          : "not an HDF5 file"));
        }
        // --resume of a run whose output is already its finished result,
        // by this build, with no checkpoint left: nothing to continue, and
        // recomputing it (hours, for a paper run) would only rewrite the
        // same datasets. Without --resume a rerun replaces the output.
        // The caller's record says this path is now this run: another run's
        // checkpoint there is moved aside, not refused (before anything reads it).
        if (request.set_aside_other_runs)
            for (const auto& moved :
                 set_aside_other_runs(job_checkpoints(base_checkpoint, session.ranks()), p))
                checkpoint.note(moved);
        if (checkpoint.resume)
            already_written = is_finished_output_of_run(
                output, job_checkpoints(base_checkpoint, session.ranks()), p);
        // Without --resume, a checkpoint that --resume would continue (this
        // path's, or any rank's or gathered file of it) is an interrupted
        // run's work: refused before any work, whatever the interval (with
        // checkpoints the run would overwrite and at its end remove it;
        // without, redo it). A damaged one is passed over with a warning.
        if (!checkpoint.resume)
            for (const auto& warning :
                 check_no_interrupted_run(job_checkpoints(base_checkpoint, session.ranks()), p))
                checkpoint.note(warning);
        // --resume refuses a checkpoint of another run before any work.
        // Each rank checks the files it reads as it loads them; under MPI
        // rank 0 first checks them all (every rank's own and the ones
        // gathered from), so that the job ends here with one line rather
        // than in a rank that has started.
        if (checkpoint.resume && session.ranks() > 1)
            check_resume_checkpoints(job_checkpoints(base_checkpoint, session.ranks()), p);
    }
    const std::optional<SimulationParameters> shared = session.share(p, already_written);
    if (!shared) {  // every rank leaves; rank 0 says why
        SimulationOutcome nothing;
        if (session.is_root())
            nothing.nothing_to_do = fmt::format("'{}' is already a complete output of this run; nothing to do (remove "
                                                "it, or run without --resume, to recompute)",
                                                output);
        return nothing;
    }
    SimulationParameters mine = *shared;
    checkpoint.run_first_realization = p.first_realization;
    checkpoint.run_realizations = p.realizations;
    // Under MPI a rank's block may end before another rank is stopped:
    // its last checkpoint then keeps the finished block for --resume
    // (removed below once the job is known complete).
    checkpoint.checkpoint_when_done = session.ranks() > 1;

    // Each MPI rank keeps its own checkpoint of its own block.
    if (session.ranks() > 1) checkpoint_file = rank_checkpoint_path(base_checkpoint, session.rank());
    // Resumed with another number of ranks (or one process after an MPI
    // job, or the reverse): the block is gathered from the others' files.
    std::vector<std::string> gathered_from;
    if (checkpoint.resume) {
        checkpoint.other_blocks = other_block_checkpoints(base_checkpoint, checkpoint_file);
        checkpoint.gathered_from = &gathered_from;
    }
    // Only checkpoints are removed (remove_checkpoints); a file that took a
    // checkpoint's name during the run is kept, and said so.
    const auto remove_own_checkpoints = [&] {
        for (const auto& kept : remove_checkpoints(checkpoint.path))
            checkpoint.note(fmt::format("kept '{}': it is not a shockgas checkpoint", kept));
    };
    const auto remove_gathered = [&] {
        remove_gathered_checkpoints(gathered_from, base_checkpoint, session.ranks());
    };
    if (checkpoint.interval_seconds > 0.0 || checkpoint.resume) {
        checkpoint.path = checkpoint_file;
        h5::check_writable(checkpoint.path);
        // Saving renames over the checkpoint's files and the end of the
        // run removes them: none may be the output, the init file, or a
        // file that is not a checkpoint.
        check_checkpoint_path(checkpoint.path, {{"output", output}, {"init file", init_given}});
    }

    // Memory: estimated before anything is allocated (memory.hpp).
    if (mine.realizations > 0) {
        const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        const int threads = std::clamp(mine.threads > 0 ? mine.threads : hardware, 1, mine.realizations);
        std::string source = "--max-memory";
        const double budget = request.max_memory.empty() ? available_memory_bytes(&source)
                                                         : parse_memory_size(request.max_memory);
        if (budget >= 0.0) {
            const bool checkpoints = !checkpoint.path.empty() && checkpoint.interval_seconds > 0.0;
            const auto plan = plan_memory(mine, threads, checkpoints, budget);
            if (plan.realizations_at_once == 0)
                throw InputError(memory_refusal(mine, plan, budget, source));
            if (plan.realizations_at_once < threads) {
                checkpoint.note(fmt::format("running realizations {} at a time instead of {}: each needs about {} "
                                            "and {} may be used in all ({})",
                                            plan.realizations_at_once, threads,
                                            format_bytes(plan.per_realization_bytes),
                                            format_bytes(budget), source));
                mine.threads = plan.realizations_at_once;
            }
        }
    }

    // One process per checkpoint; then clear what killed runs left.
    std::unique_ptr<CheckpointLock> lock;
    if (!checkpoint.path.empty()) lock = std::make_unique<CheckpointLock>(checkpoint.path);
    std::vector<std::string> targets;
    if (session.is_root()) targets.push_back(output);
    if (!checkpoint.path.empty())
        for (const auto& generation : checkpoint_generations(checkpoint.path))
            targets.push_back(generation);
    for (const auto& target : targets)
        for (const auto& stale : h5::remove_stale_temporaries(target))
            checkpoint.note(fmt::format("removed '{}', left by a run that no longer exists", stale));

    if (hooks.before_run) hooks.before_run();
    auto mine_result = mine.realizations == 0
                           ? EnsembleResult{}  // an MPI rank beyond the realizations: idle
                           : run_ensemble(mine, p.init_file.empty() ? nullptr : &initial, hooks.stop,
                                          session.is_root() ? hooks.progress : ProgressCallback{}, checkpoint);
    const auto joined = session.reduce(mine, std::move(mine_result));
    if (!joined) {
        // Only a job that ran to its end lets a rank drop its checkpoint:
        // one whose own block finished keeps it when another rank was
        // stopped (or the joining failed), so that --resume does not run
        // the finished block again.
        if (session.job_complete() && !checkpoint.path.empty()) {
            remove_own_checkpoints();
            remove_gathered();
        }
        return {};
    }  // not rank 0: rank 0 writes the file and reports
    SimulationOutcome outcome;
    outcome.result = std::move(*joined);
    const EnsembleResult& result = *outcome.result;
    write_output(output, p, result);
    session.record_provenance(output);
    // The output is safely in place: the checkpoint has served its purpose.
    if (result.status != "interrupted" && !checkpoint.path.empty()) {
        remove_own_checkpoints();
        remove_gathered();
    }
    outcome.exit_status = result.status == "interrupted" ? 130 : 0;
    return outcome;
}

}  // namespace shockgas
