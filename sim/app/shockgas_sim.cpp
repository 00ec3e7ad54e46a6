// shockgas-sim: parses arguments, runs the ensemble, writes the HDF5 file.
// Everything else lives in the shockgas_sim library.
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <algorithm>
#include <memory>
#include <optional>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/checkpoint.hpp"
#include "shockgas/checksum.hpp"
#include "shockgas/cli.hpp"
#include "shockgas/distributed.hpp"
#include "shockgas/engine.hpp"
#include "shockgas/ensemble.hpp"
#include "shockgas/h5.hpp"
#include "shockgas/memory.hpp"
#include "shockgas/output.hpp"
#include "shockgas/parameters.hpp"
#include "shockgas/provenance.hpp"

namespace {

std::atomic<bool> interrupt_requested{false};

extern "C" void on_interrupt(int) { interrupt_requested.store(true); }

// Which of stdout and stderr were terminals when the run began (isatty is not
// safe inside a signal handler).
bool stdout_terminal = false;
bool stderr_terminal = false;

// A hung-up terminal fails every later write (EIO), which would end the run
// with an error before its checkpoint: its streams go to /dev/null (open and
// dup2 are async-signal-safe), and the run stops as on SIGINT.
extern "C" void on_hangup(int) {
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
        if (stdout_terminal) dup2(null, STDOUT_FILENO);
        if (stderr_terminal) dup2(null, STDERR_FILENO);
        close(null);
    }
    interrupt_requested.store(true);
}


void print_table(const shockgas::EnsembleResult& result) {
    fmt::print("# {:>12} {:>14} {:>14} {:>14}\n", "t", "T(t)", "coll/particle", "clusters");
    const std::size_t samples = result.times.size();
    for (std::size_t s = 0; s < samples; ++s) {
        double temperature = 0, collisions = 0, clusters = 0;
        int reached = 0;
        for (std::int64_t k = 0; k < result.realizations; ++k) {
            const std::size_t cell = static_cast<std::size_t>(k) * samples + s;
            if (result.temperature[cell] != result.temperature[cell]) continue;  // NaN: not reached
            temperature += result.temperature[cell];
            collisions += result.collisions_per_particle[cell];
            clusters += result.clusters[cell];
            ++reached;
        }
        if (reached == 0) continue;
        fmt::print("  {:>12.6g} {:>14.6e} {:>14.6g} {:>14.6g}\n", result.times[s], temperature / reached,
                   collisions / reached, clusters / reached);
    }
}

}  // namespace

int main(int argc, char** argv) {
    // Under mpirun each rank runs a block of the realizations and rank 0
    // writes the joined file (distributed.hpp); otherwise one rank, no change.
    shockgas::DistributedSession session(argc, argv);
    shockgas::SimulationParameters p;
    std::string output = "shockgas.h5";
    std::string subthreshold = "elastic";
    bool quiet = false;

    CLI::App app{"shockgas-sim: event-driven simulation of a 1D inelastic gas on a ring (Ben-Naim, Chen, Doolen & "
                 "Redner, PRL 1999). Units: initial spacing 1, initial velocity scale 1."};
    app.set_config("--config", "", "read options from a TOML/INI parameter file (keys are the long option names)");
    app.add_option("-N,--particles", p.particles, "number of particles N (>= 2)")->capture_default_str();
    app.add_option("--ring-length", p.ring_length, "ring length L; 0 means L = N (unit spacing)")->capture_default_str();
    app.add_option("-r,--restitution", p.collision.restitution,
                   "restitution coefficient r = 1 - 2 eps in [0, 1]; 0 is the sticky gas")
        ->capture_default_str();
    app.add_option("-d,--threshold", p.collision.velocity_threshold,
                   "velocity threshold delta >= 0 (velocity units); below it the sub-threshold mechanism "
                   "applies; 0 is the pure inelastic gas, which stops at inelastic collapse")
        ->capture_default_str();
    app.add_option("--subthreshold", subthreshold, "sub-threshold mechanism: elastic (r = 1) or sticky (merge)")
        ->capture_default_str();
    app.add_option("-t,--t-max", p.t_max, "final time (units of spacing / velocity scale)")->capture_default_str();
    app.add_option("--samples-per-decade", p.samples_per_decade, "log-spaced samples per decade of t, from t = 1")
        ->capture_default_str();
    app.add_option("--sample-times", p.sample_times, "extra sample times, comma separated")->delimiter(',');
    app.add_option("--snapshot-times", p.snapshot_times,
                   "times at which to store every cluster's position, velocity and mass, comma separated")
        ->delimiter(',');
    double snapshot_interval = 0.0;
    app.add_option("--snapshot-interval", snapshot_interval,
                   "also store a snapshot every this much time (e.g. for world lines)");
    app.add_option("--histogram-times", p.histogram_times,
                   "times at which to store the mass-weighted velocity histogram, comma separated")
        ->delimiter(',');
    app.add_option("--histogram-bins", p.histogram_bins, "histogram bins")->capture_default_str();
    app.add_option("--histogram-range", p.histogram_range,
                   "histogram covers |v - V| t^(1/3) <= range (V the mean velocity)")
        ->capture_default_str();
    app.add_option("-R,--realizations", p.realizations, "independent realizations, 1 .. 2^31 - 1")
        ->check(shockgas::cli::realizations_in_range)
        ->capture_default_str();
    app.add_option("--first-realization", p.first_realization,
                   "index of the first realization (seed stream), to split an ensemble into parts")
        ->capture_default_str();
    // Checked as text (seed_in_range): CLI11 would otherwise wrap "-5"
    // silently to 2^64 - 5 and read 2^64 and beyond as 2^64 - 1.
    app.add_option("-s,--seed", p.seed, "random seed, 0 .. 2^63 - 1; realization k uses splitmix64(seed, k)")
        ->check(shockgas::cli::seed_in_range)
        ->capture_default_str();
    app.add_option("-j,--threads", p.threads, "threads for realizations; 0 means every core")->capture_default_str();
    std::string positions = "lattice", velocity_distribution = "uniform";
    app.add_option("--positions", positions,
                   "initial positions: lattice (x_i = i L/N, the paper's) or uniform (N i.i.d. uniform points on "
                   "the ring, sorted); drawn per realization from the seed")
        ->capture_default_str();
    app.add_option("--velocity-distribution", velocity_distribution,
                   "initial velocities, i.i.d.: uniform (on [-1, 1], the paper's) or gaussian (mean 0, the same "
                   "variance 1/3)")
        ->capture_default_str();
    app.add_option("--init", p.init_file,
                   "initial condition FILE.h5: datasets position, velocity, optional mass; root attribute "
                   "ring_length. It pins one exact start, so it needs -R 1 (every realization would be the same "
                   "run); for an ensemble use --positions / --velocity-distribution");
    app.add_option("--engine", p.engine,
                   "engine: event (event-driven, any r), exact (the sticky gas r = 0: clusters from the variational "
                   "principle, no event loop), passthrough (equal masses, delta > 0, elastic sub-threshold: "
                   "elastic collisions counted, not processed; pays late in long runs), hybrid (where passthrough "
                   "applies: event until at most 10% of the collisions are inelastic, then passthrough) or auto "
                   "(exact when r = 0, hybrid where passthrough applies, else event)")
        ->capture_default_str();
    app.add_option("--collapse-speed", p.collapse.collapse_speed,
                   "declare inelastic collapse at an inelastic collision slower than this with three or more "
                   "clusters in contact; at most delta when delta > 0 (no collapse can happen then)")
        ->capture_default_str();
    app.add_option("-o,--output", output, "output HDF5 file (written atomically)")->capture_default_str();
    shockgas::CheckpointOptions checkpoint;
    std::string checkpoint_file;
    app.add_option("--checkpoint-interval", checkpoint.interval_seconds,
                   "write a checkpoint every this many seconds of wall time (0: never); also on Ctrl-C")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--checkpoint", checkpoint_file, "checkpoint file (default: OUTPUT.checkpoint)");
    app.add_flag("--resume", checkpoint.resume,
                 "continue from the checkpoint if there is one of this run (same parameters and simulator: sources, compiler "
                 "and flags, recorded as simulator_sha256); "
                 "the output is bit-identical to an uninterrupted run. Without a checkpoint, start from t = 0; one of a "
                 "run with other parameters is refused, naming them");
    bool set_aside_other_runs = false;
    app.add_flag("--set-aside-other-runs", set_aside_other_runs,
                 "with --resume: a checkpoint of a run with other parameters is moved aside to "
                 "CHECKPOINT.from-other-run (and its .previous), and this run starts from t = 0, instead of being "
                 "refused; for scripts whose own record says which run a path holds (the figure pipeline passes it, "
                 "so that editing a run's parameters reruns it)")
        ->needs("--resume");
    double progress_interval = 60.0;
    app.add_option("--progress-interval", progress_interval,
                   "when stderr is not a terminal (a batch job's log), write a progress line every this many "
                   "seconds of wall time, and at each tenth of the run; 0: only at each tenth")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    std::string max_memory;
    app.add_option("--max-memory", max_memory,
                   "memory the run may use, e.g. 8G or 500M (default: what the machine and any cgroup limit leave "
                   "free); fewer realizations run at once if all do not fit, and a run of which not even one fits "
                   "is refused");
    app.add_flag("-q,--quiet", quiet, "do not print the T(t) table");
    app.set_version_flag("--version", "shockgas-sim " + shockgas::build_info().version);
    app.footer("Output schema: docs/cli-and-output.md (installed in share/doc/shockgas). Ctrl-C writes what has been computed, marked "
               "interrupted, and a checkpoint that --resume continues. The checkpoint is removed once the output "
               "is written.");

    // A config file's unknown key is an error, not silently ignored: a typo
    // (`restitutoin = 0.5`) would otherwise run with the default.
    app.allow_config_extras(CLI::config_extras_mode::error);

    // Every parse problem (bad value, unknown option or config key, missing
    // config file) is one line naming it, with the nearest option for a typo,
    // and exit status 2, like the validation errors below.
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-sim"); status >= 0) return status;

    return shockgas::cli::run("shockgas-sim", [&] {
        p.collision.subthreshold = shockgas::subthreshold_from_string(subthreshold);
        p.initial_law = {shockgas::position_law_from_string(positions),
                         shockgas::velocity_law_from_string(velocity_distribution)};
        if (app.count("--snapshot-interval") > 0) {
            const auto every = shockgas::evenly_spaced_times(snapshot_interval, p.t_max);
            p.snapshot_times.insert(p.snapshot_times.end(), every.begin(), every.end());
        }
        shockgas::InitialCondition initial;
        const std::string init_given = p.init_file;  // as the user wrote it, for messages
        if (!p.init_file.empty()) {
            initial = shockgas::read_initial_condition(p.init_file);
            if (app.count("--particles") > 0 && p.particles != initial.size())
                throw shockgas::InputError(fmt::format("--particles {} disagrees with the {} particles of '{}'",
                                                       p.particles, initial.size(), p.init_file));
            if (app.count("--ring-length") > 0 && p.ring_length != initial.ring_length)
                throw shockgas::InputError(fmt::format("--ring-length {} disagrees with the ring length {} of '{}'",
                                                       p.ring_length, initial.ring_length, p.init_file));
            p.particles = initial.size();
            p.ring_length = initial.ring_length;
            // Recorded so that a result names its start beyond doubt: where
            // it was (absolute) and what it held (SHA-256 of the file).
            p.init_file = std::filesystem::absolute(p.init_file).lexically_normal().string();
            p.init_file_sha256 = shockgas::file_sha256(p.init_file);
        }
        shockgas::validate(p);
        // The engine is part of what identifies a run: a checkpoint holds one engine's states, and merge
        // refuses parts of two. "auto" is resolved here (from the start's masses), so that --resume and
        // "already complete" compare the engine that runs, not the word asked for.
        p.engine = shockgas::resolve_engine_name(p, p.init_file.empty() ? nullptr : &initial);
        if (checkpoint_file.empty()) checkpoint_file = shockgas::checkpoint_path_for(output);
        const std::string base_checkpoint = checkpoint_file;
        const bool terminal = isatty(STDERR_FILENO) != 0;
        checkpoint.note = [&session, terminal](const std::string& text) {
            const std::string line = session.ranks() > 1
                                         ? fmt::format("shockgas-sim[rank {}]: {}", session.rank(), text)
                                         : fmt::format("shockgas-sim: {}", text);
            // On a terminal, overwrite the progress line rather than append to it.
            if (terminal)
                fmt::print(stderr, "\r{:<110}\n", line);
            else
                fmt::print(stderr, "{}\n", line);
        };
        bool already_written = false;  // rank 0's: --resume of a run whose output is already complete
        if (session.is_root()) {
            shockgas::h5::check_writable(output);
            shockgas::h5::check_not_an_input(output, {init_given});
            // An existing output is replaced (a rerun), but only if it is one:
            // a text file or another program's HDF5 file under that name was
            // silently replaced (CLI audit, 2026-11-27). An empty file, or an
            // HDF5 file too damaged to list (a killed write), may go.
            {
                const shockgas::h5::Probe found = shockgas::h5::probe(output);
                if (found.kind == shockgas::h5::Probe::Kind::not_hdf5 ||
                    (found.kind == shockgas::h5::Probe::Kind::hdf5 && !found.holds("timeseries")))
                    throw shockgas::InputError(fmt::format(
                        "'{}' exists and is not a shockgas-sim output ({}): it would be replaced; give -o another "
                        "path, or remove it",
                        output, found.kind == shockgas::h5::Probe::Kind::hdf5 ? "an HDF5 file without /timeseries"
                                                                              : "not an HDF5 file"));
            }
            // --resume of a run whose output is already its finished result,
            // by this build, with no checkpoint left: nothing to continue, and
            // recomputing it (hours, for a paper run) would only rewrite the
            // same datasets. Without --resume a rerun replaces the output.
            // The caller's record says this path is now this run: another run's
            // checkpoint there is moved aside, not refused (before anything reads it).
            if (set_aside_other_runs)
                for (const auto& moved :
                     shockgas::set_aside_other_runs(shockgas::job_checkpoints(base_checkpoint, session.ranks()), p))
                    checkpoint.note(moved);
            if (checkpoint.resume)
                already_written = shockgas::is_finished_output_of_run(
                    output, shockgas::job_checkpoints(base_checkpoint, session.ranks()), p);
            // Without --resume, a checkpoint that --resume would continue (this
            // path's, or any rank's or gathered file of it) is an interrupted
            // run's work: refused before any work, whatever the interval (with
            // checkpoints the run would overwrite and at its end remove it;
            // without, redo it). A damaged one is passed over with a warning.
            if (!checkpoint.resume)
                for (const auto& warning :
                     shockgas::check_no_interrupted_run(shockgas::job_checkpoints(base_checkpoint, session.ranks()), p))
                    checkpoint.note(warning);
            // --resume refuses a checkpoint of another run before any work.
            // Each rank checks the files it reads as it loads them; under MPI
            // rank 0 first checks them all (every rank's own and the ones
            // gathered from), so that the job ends here with one line rather
            // than in a rank that has started.
            if (checkpoint.resume && session.ranks() > 1)
                shockgas::check_resume_checkpoints(shockgas::job_checkpoints(base_checkpoint, session.ranks()), p);
        }
        const std::optional<shockgas::SimulationParameters> shared = session.share(p, already_written);
        if (!shared) {  // every rank leaves; rank 0 says why
            if (session.is_root())
                fmt::print(stderr,
                           "shockgas-sim: '{}' is already a complete output of this run; nothing to do (remove it, or "
                           "run without --resume, to recompute)\n",
                           output);
            return 0;
        }
        shockgas::SimulationParameters mine = *shared;
        checkpoint.run_first_realization = p.first_realization;
        checkpoint.run_realizations = p.realizations;
        // Under MPI a rank's block may end before another rank is stopped:
        // its last checkpoint then keeps the finished block for --resume
        // (removed below once the job is known complete).
        checkpoint.checkpoint_when_done = session.ranks() > 1;

        // Each MPI rank keeps its own checkpoint of its own block.
        if (session.ranks() > 1) checkpoint_file = shockgas::rank_checkpoint_path(base_checkpoint, session.rank());
        // Resumed with another number of ranks (or one process after an MPI
        // job, or the reverse): the block is gathered from the others' files.
        std::vector<std::string> gathered_from;
        if (checkpoint.resume) {
            checkpoint.other_blocks = shockgas::other_block_checkpoints(base_checkpoint, checkpoint_file);
            checkpoint.gathered_from = &gathered_from;
        }
        // Only checkpoints are removed (remove_checkpoints); a file that took a
        // checkpoint's name during the run is kept, and said so.
        const auto remove_own_checkpoints = [&] {
            for (const auto& kept : shockgas::remove_checkpoints(checkpoint.path))
                checkpoint.note(fmt::format("kept '{}': it is not a shockgas checkpoint", kept));
        };
        const auto remove_gathered = [&] {
            shockgas::remove_gathered_checkpoints(gathered_from, base_checkpoint, session.ranks());
        };
        if (checkpoint.interval_seconds > 0.0 || checkpoint.resume) {
            checkpoint.path = checkpoint_file;
            shockgas::h5::check_writable(checkpoint.path);
            // Saving renames over the checkpoint's files and the end of the
            // run removes them: none may be the output, the init file, or a
            // file that is not a checkpoint.
            shockgas::check_checkpoint_path(checkpoint.path, {{"output", output}, {"init file", init_given}});
        }

        // Memory: estimated before anything is allocated (memory.hpp).
        if (mine.realizations > 0) {
            const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
            const int threads = std::clamp(mine.threads > 0 ? mine.threads : hardware, 1, mine.realizations);
            std::string source = "--max-memory";
            const double budget = max_memory.empty() ? shockgas::available_memory_bytes(&source)
                                                     : shockgas::parse_memory_size(max_memory);
            if (budget >= 0.0) {
                const bool checkpoints = !checkpoint.path.empty() && checkpoint.interval_seconds > 0.0;
                const auto plan = shockgas::plan_memory(mine, threads, checkpoints, budget);
                if (plan.realizations_at_once == 0)
                    throw shockgas::InputError(shockgas::memory_refusal(mine, plan, budget, source));
                if (plan.realizations_at_once < threads) {
                    checkpoint.note(fmt::format("running realizations {} at a time instead of {}: each needs about {} "
                                                "and {} may be used in all ({})",
                                                plan.realizations_at_once, threads,
                                                shockgas::format_bytes(plan.per_realization_bytes),
                                                shockgas::format_bytes(budget), source));
                    mine.threads = plan.realizations_at_once;
                }
            }
        }

        // One process per checkpoint; then clear what killed runs left.
        std::unique_ptr<shockgas::CheckpointLock> lock;
        if (!checkpoint.path.empty()) lock = std::make_unique<shockgas::CheckpointLock>(checkpoint.path);
        std::vector<std::string> targets;
        if (session.is_root()) targets.push_back(output);
        if (!checkpoint.path.empty())
            for (const auto& generation : shockgas::checkpoint_generations(checkpoint.path))
                targets.push_back(generation);
        for (const auto& target : targets)
            for (const auto& stale : shockgas::h5::remove_stale_temporaries(target))
                checkpoint.note(fmt::format("removed '{}', left by a run that no longer exists", stale));

        // SIGHUP too (on_hangup): a closed terminal or a dropped ssh session
        // stops the run as Ctrl-C does, with its checkpoint and interrupted
        // output, instead of killing it with up to a checkpoint interval lost.
        stdout_terminal = isatty(STDOUT_FILENO) != 0;
        stderr_terminal = terminal;
        std::signal(SIGINT, on_interrupt);
        std::signal(SIGTERM, on_interrupt);
        std::signal(SIGHUP, on_hangup);
        shockgas::ProgressCallback progress;
        // On a terminal the progress line shows with --quiet too, which
        // silences only the T(t) table (docs/cli-and-output.md).
        if (terminal && session.is_root())
            progress = [](const shockgas::Progress& status) {
                fmt::print(stderr, "\r{:<110}", shockgas::format_progress(status));
                std::fflush(stderr);
            };
        // A log file gets whole lines, now and then (ProgressLog), even with
        // --quiet, which silences only the T(t) table on stdout.
        shockgas::ProgressLog log(progress_interval);
        if (!terminal && session.is_root())
            progress = [&log](const shockgas::Progress& status) {
                if (!log.due(status)) return;
                fmt::print(stderr, "shockgas-sim: progress: {}\n", shockgas::format_progress(status));
                std::fflush(stderr);
            };
        auto mine_result = mine.realizations == 0
                               ? shockgas::EnsembleResult{}  // an MPI rank beyond the realizations: idle
                               : shockgas::run_ensemble(mine, p.init_file.empty() ? nullptr : &initial,
                                                        &interrupt_requested, progress, checkpoint);
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
            return 0;
        }  // not rank 0: rank 0 writes the file and reports
        const auto& result = *joined;
        if (progress && terminal) fmt::print(stderr, "\n");
        shockgas::write_output(output, p, result);
        session.record_provenance(output);
        // The output is safely in place: the checkpoint has served its purpose.
        if (result.status != "interrupted" && !checkpoint.path.empty()) {
            remove_own_checkpoints();
            remove_gathered();
        }
        if (!quiet) print_table(result);
        fmt::print(stderr, "shockgas-sim: {} ({} engine, {} collisions, {:.2f} s wall, {:.2f} s CPU) -> {}\n",
                   result.status, result.engine, result.total_collisions, result.wall_seconds, result.cpu_seconds,
                   output);
        for (const auto& c : result.collapses)
            fmt::print(stderr, "shockgas-sim: realization {} collapsed at t = {:.6g} (cluster of {} particles, {})\n",
                       c.realization, c.report.time, c.report.cluster_mass, c.report.criterion);
        return result.status == "interrupted" ? 130 : 0;
    });
}
