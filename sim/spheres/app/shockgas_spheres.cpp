// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-spheres: inelastic hard disks (--dimension 2) or spheres (3) in a
// periodic box with the paper's threshold rule (docs/spheres.md). Binds the
// command line to a shockgas::spheres::SphereJob and runs it (run_spheres_job:
// the ensemble over MPI ranks under `mpirun -np K`, or in this process); the
// physics is in sim/spheres.
#include <unistd.h>

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/cli/progress.hpp"
#include "shockgas/cli/signals.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/ranks/ranks.hpp"
#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/job.hpp"
#include "shockgas/spheres/start.hpp"

namespace {

void add_options(CLI::App& app, shockgas::spheres::SphereParameters& p, shockgas::spheres::SphereRunOptions& run,
                 std::string& start, std::string& output, std::string& export_start, double& progress_interval) {
    app.set_version_flag("--version", "shockgas-spheres " + shockgas::build_info().version);
    app.add_option("--dimension,-D", p.dimension, "2 (disks) or 3 (spheres)")->capture_default_str();
    app.add_option("--particles,-N", p.particles, "number of particles, diameter 1, mass 1")->capture_default_str();
    app.add_option("--packing-fraction,--phi", p.packing_fraction, "phi = N v_d / L^d")->capture_default_str();
    app.add_option("--restitution,-r", p.collision.restitution,
                   "r = 1 - 2 eps, applied to the normal relative velocity g_n >= threshold")
        ->capture_default_str();
    app.add_option("--threshold,-d", p.collision.velocity_threshold,
                   "delta: collisions with g_n below it are elastic (0: the pure inelastic gas, which may collapse)")
        ->capture_default_str();
    app.add_option("--collapse-speed", p.collapse_speed,
                   "where delta is below it, an inelastic collision slower than this ends the run as collapsed")
        ->capture_default_str();
    app.add_option("--start", start,
                   "insertion (random sequential insertion) or lattice; both then melt in an elastic run")
        ->capture_default_str();
    app.add_option("--melt", p.melt_collisions_per_particle,
                   "collisions per particle of the elastic run that takes the start to equilibrium")
        ->capture_default_str();
    app.add_option("--t-max,-t", p.t_max, "end time (time unit: diameter / thermal speed at T = 1)")
        ->capture_default_str();
    app.add_option("--samples-per-decade", p.samples_per_decade, "log-spaced samples from t = 0.01")
        ->capture_default_str();
    app.add_option("--sample-times", p.sample_times, "extra sample times, comma separated")->delimiter(',');
    app.add_option("--snapshot-times", p.snapshot_times,
                   "times of snapshots (realization 0's particles, every realization's coarse fields)")
        ->delimiter(',');
    app.add_option("--histogram-times", p.histogram_times, "times of velocity histograms (scaled by sqrt T)")
        ->delimiter(',');
    app.add_option("--histogram-bins", p.histogram_bins, "bins of each histogram")->capture_default_str();
    app.add_option("--histogram-range", p.histogram_range, "histograms cover |u| / sqrt(T) <= this")
        ->capture_default_str();
    app.add_option("--field-cells", p.field_cells, "coarse-grained fields: this many cells a side")
        ->capture_default_str();
    app.add_option("--realizations,-R", p.realizations, "independent realizations")
        ->check(shockgas::cli::realizations_in_range)
        ->capture_default_str();
    app.add_option("--first-realization", p.first_realization,
                   "seed stream of the first realization (to split an ensemble into parts)")
        ->capture_default_str();
    app.add_option("--seed,-s", p.seed, "random seed, 0 .. 2^63 - 1")
        ->check(shockgas::cli::seed_in_range)
        ->capture_default_str();
    app.add_option("-j,--threads", p.threads,
                   "realizations run at once; 0 means every core (the result does not depend on it)")
        ->capture_default_str();
    app.add_option("--progress-interval", progress_interval,
                   "when stderr is not a terminal, write a progress line every this many wall seconds")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--checkpoint", run.checkpoint,
                   "checkpoint file (default OUTPUT.checkpoint); kept until the output is written")
        ->capture_default_str();
    app.add_option("--checkpoint-interval", run.checkpoint_interval_seconds,
                   "wall seconds between checkpoints of each realization")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_flag("--resume", run.resume, "continue from the checkpoint, bit for bit as an uninterrupted run");
    app.add_option("--export-start", export_start,
                   "write the start of realization --first-realization to this text file (d N L, then x and v of "
                   "each particle) for other codes, and stop");
    app.add_option("--output,-o", output, "output HDF5 file");
    app.footer("Output schema: docs/spheres.md. Ctrl-C (or SIGTERM, SIGHUP) saves a checkpoint that --resume "
               "continues, and exits with status 130.");
}

}  // namespace

int main(int argc, char** argv) {
    // First of all: MPI_Init may take arguments of its own from argv.
    shockgas::ranks::Session session(argc, argv);
    CLI::App app{"Inelastic hard disks (d = 2) or spheres (d = 3) in a periodic box, with the paper's "
                 "threshold rule on the normal relative velocity (docs/spheres.md)"};
    shockgas::spheres::SphereJob job;
    std::string start = "insertion", export_start;
    double progress_interval = 60.0;
    add_options(app, job.parameters, job.run, start, job.output, export_start, progress_interval);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-spheres"); status >= 0) return status;
    return shockgas::cli::run("shockgas-spheres", [&] {
        auto& parameters = job.parameters;
        parameters.start = shockgas::spheres::start_method_from_string(start);
        shockgas::spheres::validate(parameters);
        if (!export_start.empty()) {
            shockgas::spheres::write_start_text(
                shockgas::spheres::make_start(parameters, parameters.first_realization), export_start);
            return 0;
        }
        if (job.output.empty()) throw shockgas::InputError("--output is required");
        if (session.is_root()) shockgas::h5::check_writable(job.output);
        if (job.run.checkpoint.empty()) job.run.checkpoint = job.output + ".checkpoint";
        shockgas::h5::check_not_an_input(job.output, {job.run.checkpoint});
        job.run.stop = &shockgas::cli::stop_flag();
        job.run.note = shockgas::cli::rank_note("shockgas-spheres", session.rank(), session.ranks(),
                                                          isatty(STDERR_FILENO) != 0);
        shockgas::cli::install_stop_handlers();
        const auto outcome = shockgas::spheres::run_spheres_job(
            job, session, shockgas::cli::progress_printer("shockgas-spheres", progress_interval));
        if (outcome.interrupted) {
            if (session.is_root())
                fmt::print(stderr, "\nshockgas-spheres: interrupted; the checkpoint {}{} continues it with --resume{}\n",
                           job.run.checkpoint, session.ranks() > 1 ? ".rank<k>" : "",
                           session.ranks() > 1 ? fmt::format(" on {} ranks", session.ranks()) : "");
            return 130;
        }
        if (!outcome.wrote_output) return 0;  // another rank than 0: rank 0 wrote the file
        const auto& result = outcome.result;
        fmt::print("{}D, N = {}, phi = {}: {} collisions ({:.4g} per particle per realization) in {:.3g} CPU-s "
                   "({:.3g} of them making the starts); T(t_max) = {:.6g} in realization 0; {}\n",
                   parameters.dimension, parameters.particles, parameters.packing_fraction,
                   result.counts.collisions(),
                   2.0 * static_cast<double>(result.counts.collisions()) /
                       (static_cast<double>(parameters.particles) * parameters.realizations),
                   result.cpu_seconds, result.start_seconds, result.temperature[result.time.size() - 1],
                   job.output);
        return 0;
    });
}
