// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-drift: long-run drift of total momentum, kinetic energy and the
// smallest gap of one realization against what rounding alone can do (the
// measurement and its columns: drift.hpp). This program binds its options
// to a shockgas::drift::DriftRequest and runs it (run_drift_command), which
// prints the rows as a table and writes them to CSV or HDF5.
//
// --check turns the two rounding bounds into pass/fail (exit status 1), and
// with --reference a third, on the ring length (ring_length_rounding_bound);
// the ctests `drift.check` (10^6 collisions) and `drift.ring_length` (10^7,
// --reference) run it.
//
// Example (the long run of docs/testing-and-drift.md, ~20 min of one core):
//   build/bin/shockgas-drift -N 1000 -r 0.5 -d 1e-2 --collisions 1e10 -o drift.h5
#include <string>

#include <CLI/CLI.hpp>

#include "drift.hpp"
#include "shockgas/cli/cli.hpp"

namespace {

// Every option, bound to the request's fields (their defaults are the request's).
void add_options(CLI::App& app, shockgas::drift::DriftRequest& request) {
    app.add_option("-N,--particles", request.parameters.particles, "number of particles N (>= 2)")
        ->capture_default_str();
    app.add_option("--ring-length", request.parameters.ring_length, "ring length L; 0 means L = N")
        ->capture_default_str();
    app.add_option("-r,--restitution", request.parameters.collision.restitution, "restitution r in [0, 1]")
        ->capture_default_str();
    app.add_option("-d,--threshold", request.parameters.collision.velocity_threshold, "velocity threshold delta")
        ->capture_default_str();
    app.add_option("--subthreshold", request.subthreshold, "sub-threshold mechanism: elastic or sticky")
        ->capture_default_str();
    app.add_option("-s,--seed", request.parameters.seed, "random seed, 0 .. 2^63 - 1")
        ->check(shockgas::cli::seed_in_range)
        ->capture_default_str();
    app.add_option("--realization", request.options.realization, "realization index (seed stream)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("-c,--collisions", request.options.target_collisions, "stop after this many collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--record-every", request.options.record_every,
                   "print a row every this many collisions (and at each decade)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--records-per-decade", request.options.records_per_decade,
                   "log-spaced rows per decade of collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--chunk", request.options.chunk_collisions,
                   "collisions per advance_to call (the checks run after each)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("-o,--output", request.output, "also write the rows to FILE.csv or FILE.h5 (with provenance)");
    app.add_flag("--check", request.check,
                 "exit 1 if the momentum drift or an energy rise exceeds its rounding bound, ring order breaks, a "
                 "value is non-finite or the run ends early (equal masses, no merges only)");
    app.add_option("--engine", request.parameters.engine,
                   "engine as for shockgas-sim: event (the event engine where it applies), passthrough, hybrid, auto")
        ->capture_default_str();
    app.add_flag(
        "--reference", request.options.reference,
        "run ReferenceEventEngine, the global-order loop the fast engine is bit-identical to (slower), and read its "
        "stored gaps: smallest stored gap and ring-length drift sum(gaps) - L per row");
    app.add_flag("--stop-on-disorder", request.options.stop_on_disorder,
                 "print every pair out of ring order at the first chunk that has one, and stop there");
    app.add_option("--inject-momentum-error", request.options.inject_momentum_error,
                   "testing the check only: the engine starts from v[0] + this while P0 is the unperturbed one");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "shockgas-drift: drift of total momentum, kinetic energy and the smallest gap over one long "
        "realization (engine chosen by make_engine). Units: initial spacing 1, velocity scale 1."};
    shockgas::drift::DriftRequest request;
    add_options(app, request);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-drift"); status >= 0) return status;
    return shockgas::cli::run("shockgas-drift", [&] { return shockgas::drift::run_drift_command(request); });
}
