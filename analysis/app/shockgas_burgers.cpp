// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-burgers: the Burgers velocity profile from the initial condition of
// a particle run, for Fig. 5 (docs/continuum.md: Burgers with nu -> 0 is the sticky
// gas; shocks <-> clusters, v = (x - q)/t between shocks, Eq. 7).
//
//   shockgas-burgers --run RUN.h5 [--realization k] [--time t] [--cells-per-particle k]
//                    [--viscosity nu1,nu2,...] [--points P] --output profile.dat
//                    [--summary vars.gp] [--study study.dat]
//   shockgas-burgers --particles N [--ring-length L] --seed S --time t ...   (the same initial
//                    condition shockgas-sim draws) or --init FILE.h5 (none of these with --run: a
//                    run's start is its own)
// The profile is built on the lattice of the particles' start (burgers.hpp): a run's or an
// init file's particles must be equally spaced, as shockgas-sim --positions lattice places them.
//
// Every text output begins with '#' lines naming this program's version, the date and the
// start (seed, realization and law, or the run or init file).
// profile.dat: block 0 "x v_inviscid v_nu..." on P equally spaced points; block 1 the
// inviscid shocks "position mass velocity jump/v_rms". With --run and a snapshot at t,
// the shocks found in the particles (shockgas::analysis::find_shocks, the Fig. 5 detector)
// are matched to the Burgers shocks with the same jump criterion (drop >= v_rms), and the
// distances are printed and written to --summary as gnuplot variables.
// --study: nu -> 0 and grid-refinement convergence tables (docs/continuum.md).
// The program binds the command line to a shockgas::analysis::BurgersRequest and runs it
// (run_burgers, shockgas/analysis/burgers_command.hpp).
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "shockgas/analysis/burgers_command.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/io/provenance.hpp"

namespace {

// Every option, bound to the request's fields (their defaults are the request's); returns the
// options that exclude others, for cli::parse to name with their reason.
std::vector<shockgas::cli::Exclusion> add_options(CLI::App& app, shockgas::analysis::BurgersRequest& request) {
    app.set_version_flag("--version", "shockgas-burgers " + shockgas::build_info().version);
    auto* run_option =
        app.add_option("--run", request.run_path,
                       "shockgas-sim output: N, L, seed (or init_file) and the snapshot time; its start must be "
                       "equally spaced (--positions lattice, the default)")
            ->check(CLI::ExistingFile);
    auto* init_option = app.add_option("--init", request.init_path,
                                       "initial condition file (as shockgas-sim --init) of equally spaced particles")
                            ->check(CLI::ExistingFile);
    auto* particles_option = app.add_option("-N,--particles", request.particles,
                                            "particles (with --seed: shockgas-sim's initial condition)");
    auto* ring_length_option = app.add_option("-L,--ring-length", request.ring_length, "ring length (default N)");
    auto* seed_option = app.add_option("-s,--seed", request.seed, "seed (as shockgas-sim)")
                            ->check(shockgas::cli::seed_in_range)
                            ->capture_default_str();
    // --run takes the start from the run itself (its N, L, seed and initial law, or its init file
    // checked against the run's init_file_sha256): -N, -L and -s beside it would be ignored, and an
    // --init would replace that start unchecked, comparing the run's particles with another start's
    // profile.
    auto run_supplies = shockgas::cli::exclude(
        run_option, {init_option, particles_option, ring_length_option, seed_option},
        "--run takes the initial condition from the run (its N, L, seed and law, or its init file)");
    auto* realization_option =
        app.add_option("--realization", request.realization, "realization")->capture_default_str();
    // --init's file is the start itself (its N, L and velocities): -N, -L, -s and --realization
    // beside it would be ignored.
    auto init_supplies =
        shockgas::cli::exclude(init_option, {particles_option, ring_length_option, seed_option, realization_option},
                               "--init's file is the initial condition itself (its N, L and velocities)");
    app.add_option("-t,--time", request.time, "time (default: the run's first snapshot time)");
    app.add_option("--cells-per-particle", request.cells_per_particle, "grid cells per particle")
        ->capture_default_str();
    app.add_option("--viscosity", request.viscosities, "viscous profiles (Hopf-Cole) at these nu")->delimiter(',');
    app.add_option("--points", request.points, "output points (default: 4 per particle)");
    app.add_option("--jump-fraction", request.jump_fraction, "a counted shock drops v by >= this x v_rms")
        ->capture_default_str();
    app.add_option("-o,--output", request.output, "profile data file")->required();
    app.add_option("--summary", request.summary, "gnuplot variables: shock counts and particle-vs-Burgers distances");
    app.add_option("--study", request.study, "convergence tables (nu -> 0, grid refinement)");
    return {std::move(run_supplies), std::move(init_supplies)};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-burgers: inviscid and viscous Burgers profiles from a particle run's initial condition"};
    shockgas::analysis::BurgersRequest request;
    const auto exclusions = add_options(app, request);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-burgers", exclusions); status >= 0)
        return status;
    return shockgas::cli::run("shockgas-burgers", [&] {
        shockgas::analysis::run_burgers(request);
        return 0;
    });
}
