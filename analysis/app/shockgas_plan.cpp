// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-plan: from the validity map of the threshold delta, the cheapest
// (delta, sub-threshold mechanism) whose measured run keeps an observable
// within a tolerance of the sticky gas to t_max, with its cost. Binds the
// command line to a shockgas::analysis::PlanRequest and runs it
// (shockgas::analysis::run_plan, shockgas/analysis/plan_command.hpp).
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "shockgas/analysis/plan_command.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/io/provenance.hpp"

namespace {

void add_options(CLI::App& app, shockgas::analysis::PlanRequest& request) {
    app.set_version_flag("--version", "shockgas-plan " + shockgas::build_info().version);
    app.add_option("-t,--t-max", request.t_max,
                   "the time your run must reach, in units of initial spacing / initial velocity scale; within the "
                   "times the map measured")
        ->required();
    app.add_option("-N,--particles", request.particles,
                   "your number of particles N (a count; the ring's length is N initial spacings); at least the "
                   "map's N at that r")
        ->required();
    app.add_option("-r,--restitution", request.restitution,
                   "restitution coefficient r (dimensionless), one the map measured (e.g. 0.5 or 0.9)")
        ->required();
    app.add_option("--observable", request.observable,
                   "what must stay as in the sticky gas: temperature, kurtosis, cluster_density, small_gap_fraction, "
                   "structure_function or fragmentation_rate (the map lists its own)")
        ->required();
    app.add_option("--tolerance", request.tolerance,
                   "how close: 3sigma (within 3 jackknife sigma of the sticky gas), 1percent or 5percent "
                   "(within a relative band of 1 % or 5 %, left only when beyond it by 2 sigma; for the "
                   "fragmentation rate an absolute rate)")
        ->required();
    app.add_option("--map", request.map_file,
                   "a results file whose /validity_map holds the map (shockgas-analyze validity); default: "
                   "$SHOCKGAS_VALIDITY_MAP if set, else this build tree's fig_validity map (paper, else quick)");
    app.footer("Prints the cheapest measured choice, its cost (collisions per particle by t_max, from the run's "
               "own; CPU seconds per realization, from the run's CPU time per particle-collision), and a table of "
               "every measured (delta, mechanism) at r. Refuses (exit status 2) what the map did not measure "
               "rather than extrapolate. The map: docs/validity.md; its layout: docs/cli-and-output.md.");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-plan: the cheapest threshold delta that keeps an observable of the inelastic gas as in "
                 "the sticky gas to t_max, from the measured validity map"};
    shockgas::analysis::PlanRequest request;
    add_options(app, request);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-plan"); status >= 0) return status;
    return shockgas::cli::run("shockgas-plan", [&] {
        if (app.count("--map") == 0)
            request.map_file =
                shockgas::analysis::default_validity_map({SHOCKGAS_PAPER_VALIDITY_MAP, SHOCKGAS_QUICK_VALIDITY_MAP});
        shockgas::analysis::run_plan(request, stdout);
        return 0;
    });
}
