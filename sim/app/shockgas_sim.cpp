// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-sim: binds the command line to a shockgas::SimulationRequest, runs it
// (shockgas::run_simulation, sim/run) and shows the outcome, after the validity
// map's warning when it has one (shockgas/analysis/validity_warning.hpp).
#include <cstdio>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/analysis/validity_warning.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/cli/progress.hpp"
#include "shockgas/cli/signals.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/run/simulation.hpp"

namespace {

// What only the program does with a run: its progress line and its table.
struct Display {
    double progress_interval = 60.0;
    bool quiet = false;
    std::string validity_map;  // --validity-map: the map the warning reads ("": none)
};

// Every option, bound to the request's fields (their defaults are the request's).
void add_options(CLI::App& app, shockgas::SimulationRequest& request, Display& display) {
    app.set_config("--config", "", "read options from a TOML/INI parameter file (keys are the long option names)");
    app.add_option("-N,--particles", request.parameters.particles, "number of particles N (>= 2)")->capture_default_str();
    app.add_option("--ring-length", request.parameters.ring_length, "ring length L; 0 means L = N (unit spacing)")->capture_default_str();
    app.add_option("-r,--restitution", request.parameters.collision.restitution,
                   "restitution coefficient r = 1 - 2 eps in [0, 1]; 0 is the sticky gas")
        ->capture_default_str();
    app.add_option("-d,--threshold", request.parameters.collision.velocity_threshold,
                   "velocity threshold delta >= 0 (velocity units); below it the sub-threshold mechanism "
                   "applies; 0 is the pure inelastic gas, which stops at inelastic collapse")
        ->capture_default_str();
    app.add_option("--subthreshold", request.subthreshold, "sub-threshold mechanism: elastic (r = 1) or sticky (merge)")
        ->capture_default_str();
    app.add_option("-t,--t-max", request.parameters.t_max, "final time (units of spacing / velocity scale)")->capture_default_str();
    app.add_option("--samples-per-decade", request.parameters.samples_per_decade, "log-spaced samples per decade of t, from t = 1")
        ->capture_default_str();
    app.add_option("--sample-times", request.parameters.sample_times, "extra sample times, comma separated")->delimiter(',');
    app.add_option("--snapshot-times", request.parameters.snapshot_times,
                   "times at which to store every cluster's position, velocity and mass, comma separated")
        ->delimiter(',');
    app.add_option("--snapshot-interval", request.snapshot_interval,
                   "also store a snapshot every this much time (e.g. for world lines)");
    app.add_option("--histogram-times", request.parameters.histogram_times,
                   "times at which to store the mass-weighted velocity histogram, comma separated")
        ->delimiter(',');
    app.add_option("--histogram-bins", request.parameters.histogram_bins, "histogram bins")->capture_default_str();
    app.add_option("--histogram-range", request.parameters.histogram_range,
                   "histogram covers |v - V| t^(1/3) <= range (V the mean velocity)")
        ->capture_default_str();
    app.add_option("-R,--realizations", request.parameters.realizations, "independent realizations, 1 .. 2^31 - 1")
        ->check(shockgas::cli::realizations_in_range)
        ->capture_default_str();
    app.add_option("--first-realization", request.parameters.first_realization,
                   "index of the first realization (seed stream), to split an ensemble into parts")
        ->capture_default_str();
    // Checked as text (seed_in_range): CLI11 would otherwise wrap "-5"
    // silently to 2^64 - 5 and read 2^64 and beyond as 2^64 - 1.
    app.add_option("-s,--seed", request.parameters.seed, "random seed, 0 .. 2^63 - 1; realization k uses splitmix64(seed, k)")
        ->check(shockgas::cli::seed_in_range)
        ->capture_default_str();
    app.add_option("-j,--threads", request.parameters.threads, "threads for realizations; 0 means every core")->capture_default_str();
    app.add_option("--positions", request.positions,
                   "initial positions: lattice (x_i = i L/N, the paper's) or uniform (N i.i.d. uniform points on "
                   "the ring, sorted); drawn per realization from the seed")
        ->capture_default_str();
    app.add_option("--velocity-distribution", request.velocity_distribution,
                   "initial velocities, i.i.d.: uniform (on [-1, 1], the paper's) or gaussian (mean 0, the same "
                   "variance 1/3)")
        ->capture_default_str();
    app.add_option("--init", request.parameters.init_file,
                   "initial condition FILE.h5: datasets position, velocity, optional mass; root attribute "
                   "ring_length. It pins one exact start, so it needs -R 1 (every realization would be the same "
                   "run); for an ensemble use --positions / --velocity-distribution");
    app.add_option("--engine", request.parameters.engine,
                   "engine: event (event-driven, any r), reference (the plain global event loop that event reproduces bit "
                   "for bit: slower, for checks), exact (the sticky gas r = 0: clusters from the variational "
                   "principle, no event loop), passthrough (equal masses, delta > 0, elastic sub-threshold: "
                   "elastic collisions counted, not processed; pays late in long runs), hybrid (where passthrough "
                   "applies: event until at most 10% of the collisions are inelastic, then passthrough) or auto "
                   "(exact when r = 0, hybrid where passthrough applies, else event)")
        ->capture_default_str();
    app.add_option("--collapse-speed", request.parameters.collapse.collapse_speed,
                   "declare inelastic collapse at an inelastic collision slower than this with three or more "
                   "clusters in contact; at most delta when delta > 0 (no collapse can happen then)")
        ->capture_default_str();
    app.add_option("-o,--output", request.output, "output HDF5 file (written atomically)")->capture_default_str();
    app.add_option("--checkpoint-interval", request.checkpoint.interval_seconds,
                   "write a checkpoint every this many seconds of wall time (0: never); also on Ctrl-C")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--checkpoint", request.checkpoint_file, "checkpoint file (default: OUTPUT.checkpoint)");
    app.add_flag("--resume", request.checkpoint.resume,
                 "continue from the checkpoint if there is one of this run (same parameters and simulator: sources, compiler "
                 "and flags, recorded as simulator_sha256); "
                 "the output is bit-identical to an uninterrupted run. Without a checkpoint, start from t = 0; one of a "
                 "run with other parameters is refused, naming them");
    app.add_flag("--set-aside-other-runs", request.set_aside_other_runs,
                 "with --resume: a checkpoint of a run with other parameters is moved aside to "
                 "CHECKPOINT.from-other-run (and its .previous), and this run starts from t = 0, instead of being "
                 "refused; for scripts whose own record says which run a path holds (the figure pipeline passes it, "
                 "so that editing a run's parameters reruns it)")
        ->needs("--resume");
    app.add_option("--progress-interval", display.progress_interval,
                   "when stderr is not a terminal (a batch job's log), write a progress line every this many "
                   "seconds of wall time, and at each tenth of the run; 0: only at each tenth")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--max-memory", request.max_memory,
                   "memory the run may use, e.g. 8G or 500M (default: what the machine and any cgroup limit leave "
                   "free); fewer realizations run at once if all do not fit, and a run of which not even one fits "
                   "is refused");
    app.add_flag("-q,--quiet", display.quiet, "do not print the T(t) table");
    app.add_option("--validity-map", display.validity_map,
                   "the validity map of delta (a results file holding /validity_map; docs/validity.md) from which a "
                   "warning is printed before a run whose t_max lies past where its T leaves the sticky gas by 1 %; "
                   "'' checks none; default: $SHOCKGAS_VALIDITY_MAP if set, else this build tree's fig_validity "
                   "map, when there is one. The run is the same either way");
    app.set_version_flag("--version", "shockgas-sim " + shockgas::build_info().version);
    app.footer("Output schema: docs/cli-and-output.md (installed in share/doc/shockgas). Ctrl-C writes what has been computed, marked "
               "interrupted, and a checkpoint that --resume continues. The checkpoint is removed once the output "
               "is written.");
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
    shockgas::SimulationRequest request;
    Display display;
    CLI::App app{"shockgas-sim: event-driven simulation of a 1D inelastic gas on a ring (Ben-Naim, Chen, Doolen & "
                 "Redner, PRL 1999). Units: initial spacing 1, initial velocity scale 1."};
    add_options(app, request, display);
    // A config file's unknown key is an error, not silently ignored: a typo
    // (`restitutoin = 0.5`) would otherwise run with the default.
    app.allow_config_extras(CLI::config_extras_mode::error);
    // Every parse problem (bad value, unknown option or config key, missing
    // config file) is one line naming it, with the nearest option for a typo,
    // and exit status 2, like the validation errors of the run.
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-sim"); status >= 0) return status;

    return shockgas::cli::run("shockgas-sim", [&] {
        request.snapshot_interval_given = app.count("--snapshot-interval") > 0;
        request.particles_given = app.count("--particles") > 0;
        request.ring_length_given = app.count("--ring-length") > 0;
        const bool terminal = isatty(STDERR_FILENO) != 0;
        request.checkpoint.note = shockgas::cli::rank_note("shockgas-sim", session.rank(), session.ranks(), terminal);
        const bool map_given = app.count("--validity-map") > 0;
        const std::string warning = shockgas::analysis::validity_warning_for_run(
            map_given ? display.validity_map
                      : shockgas::analysis::default_validity_map({SHOCKGAS_PAPER_VALIDITY_MAP, SHOCKGAS_QUICK_VALIDITY_MAP}),
            map_given, request.parameters.collision.restitution, request.parameters.collision.velocity_threshold,
            request.subthreshold, request.parameters.t_max);
        // Printed once the run is known to start (its input checked), so that a
        // refused run still says one line.
        const auto before_run = [&] {
            if (!warning.empty() && session.is_root()) fmt::print(stderr, "shockgas-sim: warning: {}\n", warning);
            shockgas::cli::install_stop_handlers();
        };
        shockgas::SimulationHooks hooks{&shockgas::cli::stop_flag(), before_run,
                                        shockgas::cli::progress_printer("shockgas-sim", display.progress_interval)};
        const shockgas::SimulationOutcome outcome = shockgas::run_simulation(request, session, hooks);
        if (!outcome.nothing_to_do.empty()) fmt::print(stderr, "shockgas-sim: {}\n", outcome.nothing_to_do);
        if (!outcome.result) return outcome.exit_status;
        const auto& result = *outcome.result;
        if (terminal) fmt::print(stderr, "\n");  // past the progress line
        if (!display.quiet) print_table(result);
        fmt::print(stderr, "shockgas-sim: {} ({} engine, {} collisions, {:.2f} s wall, {:.2f} s CPU) -> {}\n",
                   result.status, result.engine, result.total_collisions, result.wall_seconds, result.cpu_seconds,
                   request.output);
        for (const auto& c : result.collapses)
            fmt::print(stderr, "shockgas-sim: realization {} collapsed at t = {:.6g} (cluster of {} particles, {})\n",
                       c.realization, c.report.time, c.report.cluster_mass, c.report.criterion);
        return outcome.exit_status;
    });
}
