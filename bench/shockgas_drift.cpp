// shockgas-drift: long-run drift of total momentum, kinetic energy and the
// smallest gap of one realization against what rounding alone can do (the
// measurement and its columns: drift.hpp). This program parses the
// options, prints the rows as a table and writes them to CSV or HDF5.
//
// --check turns the two rounding bounds into pass/fail (exit status 1), and
// with --reference a third, on the ring length (ring_length_rounding_bound);
// the ctests `drift.check` (10^6 collisions) and `drift.ring_length` (10^7,
// --reference) run it.
//
// Example (the long run of docs/testing-and-drift.md, ~20 min of one core):
//   build/bin/shockgas-drift -N 1000 -r 0.5 -d 1e-2 --collisions 1e10 -o drift.h5
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "drift.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"

namespace {

void print_header() {
    fmt::print("# {:>10} {:>10} {:>6} {:>9} {:>9} {:>10} {:>9} {:>9} {:>9} {:>8} {:>5} {:>3} {:>8} {:>8} {:>8}\n",
               "collisions", "t", "clust", "dP/S0", "bound", "E/E0", "rise", "gap", "gap_min", "res", "order",
               "bad", "cpu_s", "coll/s", "dC/dt");
    std::fflush(stdout);
}

void print_row(const shockgas::drift::DriftRow& r) {
    fmt::print("  {:>10.4g} {:>10.4g} {:>6} {:>9.2e} {:>9.2e} {:>10.4e} {:>9.2e} {:>9.2e} {:>9.2e} {:>8.1e} {:>5} "
               "{:>3} {:>8.1f} {:>8.3g} {:>8.3g}\n",
               r.collisions, r.time, static_cast<std::int64_t>(r.clusters), r.drift, r.bound, r.energy_ratio,
               r.max_rise, r.min_gap, r.min_gap_run, r.gap_resolution, static_cast<int>(r.order),
               static_cast<std::int64_t>(r.nonfinite), r.cpu_seconds, r.rate, r.collision_rate_in_time);
    if (!std::isnan(r.stored_min_gap))
        fmt::print("#   stored gaps: smallest {:.3e} L/N, sum(gaps) - L = {:.3e}\n", r.stored_min_gap,
                   r.ring_length_drift);
    std::fflush(stdout);
}

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    shockgas::SimulationParameters p;
    p.particles = 1000;
    p.collision.restitution = 0.5;
    p.collision.velocity_threshold = 1e-2;
    p.engine = "event";
    std::string subthreshold = "elastic";
    shockgas::drift::DriftOptions o;
    std::string output;
    bool check = false;

    CLI::App app{"shockgas-drift: drift of total momentum, kinetic energy and the smallest gap over one long "
                 "realization (engine chosen by make_engine). Units: initial spacing 1, velocity scale 1."};
    app.add_option("-N,--particles", p.particles, "number of particles N (>= 2)")->capture_default_str();
    app.add_option("--ring-length", p.ring_length, "ring length L; 0 means L = N")->capture_default_str();
    app.add_option("-r,--restitution", p.collision.restitution, "restitution r in [0, 1]")->capture_default_str();
    app.add_option("-d,--threshold", p.collision.velocity_threshold, "velocity threshold delta")
        ->capture_default_str();
    app.add_option("--subthreshold", subthreshold, "sub-threshold mechanism: elastic or sticky")
        ->capture_default_str();
    app.add_option("-s,--seed", p.seed, "random seed, 0 .. 2^63 - 1")->check(shockgas::cli::seed_in_range)->capture_default_str();
    app.add_option("--realization", o.realization, "realization index (seed stream)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("-c,--collisions", o.target_collisions, "stop after this many collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--record-every", o.record_every, "print a row every this many collisions (and at each decade)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--records-per-decade", o.records_per_decade, "log-spaced rows per decade of collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--chunk", o.chunk_collisions, "collisions per advance_to call (the checks run after each)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("-o,--output", output, "also write the rows to FILE.csv or FILE.h5 (with provenance)");
    app.add_flag("--check", check,
                 "exit 1 if the momentum drift or an energy rise exceeds its rounding bound, ring order breaks, a "
                 "value is non-finite or the run ends early (equal masses, no merges only)");
    app.add_option("--engine", p.engine,
                   "engine as for shockgas-sim: event (the event engine where it applies), passthrough, hybrid, auto")
        ->capture_default_str();
    app.add_flag("--reference", o.reference,
                 "run ReferenceEventEngine, the global-order loop the fast engine is bit-identical to (slower), and read its "
                 "stored gaps: smallest stored gap and ring-length drift sum(gaps) - L per row");
    app.add_flag("--stop-on-disorder", o.stop_on_disorder,
                 "print every pair out of ring order at the first chunk that has one, and stop there");
    app.add_option("--inject-momentum-error", o.inject_momentum_error,
                   "testing the check only: the engine starts from v[0] + this while P0 is the unperturbed one");

    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-drift"); status >= 0) return status;

    return shockgas::cli::run("shockgas-drift", [&] {
        p.collision.subthreshold = shockgas::subthreshold_from_string(subthreshold);
        shockgas::validate(p);
        if (!output.empty() && !ends_with(output, ".csv") && !ends_with(output, ".h5"))
            throw shockgas::InputError("--output must end in .csv or .h5, got '" + output + "'");
        if (!output.empty()) shockgas::h5::check_writable(output);
        if (check) shockgas::drift::require_checkable(p);

        shockgas::drift::DriftListener listener;
        listener.started = [&](const shockgas::drift::DriftReport& report) {
            fmt::print("# shockgas-drift: N = {}, L = {}, r = {}, delta = {}, {} sub-threshold, seed {}, realization "
                       "{}; engine {} ({})\n",
                       p.particles, report.ring_length, p.collision.restitution, p.collision.velocity_threshold,
                       subthreshold, p.seed, o.realization, report.engine,
                       o.reference ? "ReferenceEventEngine, --reference" : "make_engine");
            fmt::print("# P0 = {:.17g}, S0 = sum m|v0| = {:.17g}, E0 = {:.17g}, |v|max0 = {:.17g}\n",
                       report.start.momentum, report.start.momentum_scale, report.start.energy,
                       report.start.max_speed);
            fmt::print("# dP/S0 = |P - P0| / S0; gaps in units of L/N; rise = largest (E_k - E_(k-1))/E_(k-1) "
                       "between chunks of ~{:.0e} collisions\n",
                       o.chunk_collisions);
            print_header();
        };
        listener.row = print_row;
        listener.note = [](const std::string& line) { fmt::print("# {}\n", line); };
        const auto report = shockgas::drift::run_drift(p, o, listener);

        const auto& last = report.rows.back();
        fmt::print("# {}: {} collisions, t = {:.6g}, {:.1f} s CPU, {:.3g} collisions/s; final dP/S0 = {:.3e} "
                   "(bound {:.3e}); max energy rise {:.3e}; smallest gap {:.3e} L/N; ring order {}; non-finite {}\n",
                   report.ended, last.collisions, last.time, last.cpu_seconds, last.rate, last.drift, last.bound,
                   report.max_rise, last.min_gap_run, report.order_held ? "held" : "BROKEN", report.nonfinite);
        if (ends_with(output, ".csv")) shockgas::drift::write_csv(output, report);
        if (ends_with(output, ".h5")) shockgas::drift::write_h5(output, p, o, report);

        if (!check) return 0;
        const auto failures = shockgas::drift::check_failures(p, o, report);
        for (const auto& why : failures) fmt::print(stderr, "shockgas-drift: check failed: {}\n", why);
        return failures.empty() ? 0 : 1;
    });
}
