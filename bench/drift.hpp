// SPDX-License-Identifier: GPL-3.0-or-later
// Long-run drift of the conserved and bounded quantities of one realization
// (the stability question: how far do total momentum, kinetic energy and the
// smallest gap move over the longest run one can afford, against what
// rounding alone can do). shockgas-drift (bench/shockgas_drift.cpp) is its command
// line; tests call run_drift directly. docs/testing-and-drift.md has the
// measurements.
//
// One realization of the paper's initial condition runs on the engine
// make_engine picks (or ReferenceEventEngine, the global-order reference loop), in
// chunks: advance_to successive times sized from the measured collision rate
// to about chunk_collisions. After every chunk the clusters are read through
// the public Engine interface and checked; a DriftRow is taken at every
// decade of the collision count (records_per_decade) and every record_every
// collisions. The columns:
//
//   momentum      total momentum sum m v (long double sum: its own rounding,
//                 ~N 2^-64 sum m|v|, is far below one ulp of the engine's values)
//   drift         relative drift |P - P0| / sum m |v0|
//   bound         the worst case rounding can reach (momentum_rounding_bound);
//                 exceeded means a real leak
//   energy_ratio  kinetic energy sum m v^2 / 2 over its initial value
//   max_rise      largest relative increase of E between two consecutive chunks
//                 so far; exact dynamics never increase E, rounding may by
//                 2^-52 |v|max^2 per collision (energy_rounding_bound)
//   min_gap       smallest gap between neighbouring clusters at this row, and
//   min_gap_run   the smallest over every chunk so far, in units of the mean
//                 spacing L/N, from ClusterState positions (no engine exposes
//                 its stored gaps through the Engine interface). Their
//                 resolution is gap_resolution: positions are walked from the
//                 anchor's absolute position, which is not wrapped and grows
//                 like |v| t, so a gap is known to about ulp(2L + |v|max0 t) + ulp(L).
//   order         1 while every gap so far was >= -resolution (ring order holds
//                 up to rounding; a pair out of order shows as a negative gap)
//   nonfinite     non-finite positions or velocities seen so far
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shockgas/model/parameters.hpp"

namespace shockgas::drift {

// Worst-case relative momentum drift after `collisions` equal-mass,
// non-merging collisions. Each collision computes v1' = v1 - h, v2' = v2 + h
// from one h (collision.hpp), so in exact arithmetic P is unchanged and only
// the two final roundings move it, each by at most u |v'| <= u |v|max0 (|v|max
// never grows: convex combinations, see event_engine.hpp). Hence
//   |P - P0| <= C * 2u * m |v|max0, relative to sum m |v0|.
double momentum_rounding_bound(double collisions, double mass, double max_speed0, double momentum_scale);

// |sum(gaps) - L| that rounding alone should stay within (the reference loop
// only). The engines store gaps, never L, and no collision moves mass across
// the ring, so the sum stays L but for rounding: each collision rewrites three
// gaps (the pair's own contact gap and its two neighbours'), each rounded to
// within 2^-53 of its value. Those errors have random signs, so the sum
// random-walks as sqrt(3 C) 2^-53 g for gaps g of about the mean spacing; the
// factor 20 covers gaps a few spacings wide and a 4-sigma excursion. It is not
// a worst case (that, 3 C 2^-53 g_max, grows too fast to tell anything apart).
// Measured at N = 1000, C = 10^7: 2.4e-13 L/N against a bound of 1.2e-11;
// setting the contact gap to 0 instead of keeping it gives 1.3e-9, because it
// drops c * (t rounded - t exact) ~ c ulp(t) at every collision.
double ring_length_rounding_bound(double collisions, double spacing);

// Worst-case energy increase over `collisions` collisions, relative to E: each
// rounded velocity v(1 + a), |a| <= u, changes m v^2 / 2 by at most m u v^2
// (1 + u), and exact collisions never add energy, so
//   E' - E <= C * 2u * m |v|max^2 (two velocities per collision),
// plus the long double measurement error of the two sums, 2 N 2^-64 E.
double energy_rounding_bound(double collisions, double mass, double max_speed, double energy, double particles);

struct DriftOptions {
    std::int64_t realization = 0;      // seed stream of the initial condition
    double target_collisions = 1e8;    // stop after this many
    double record_every = 1e8;         // a row every this many collisions (and at each decade)
    int records_per_decade = 1;        // log-spaced rows per decade of collisions
    double chunk_collisions = 1e6;     // collisions per advance_to call (the checks run after each)
    double inject_momentum_error = 0;  // testing the check only: the engine starts from v[0] + this
    bool stop_on_disorder = false;     // stop at the first chunk with a pair out of ring order
    bool reference = false;            // run ReferenceEventEngine and read its stored gaps
};

struct DriftRow {
    double collisions, time, clusters, momentum, drift, bound, energy_ratio, max_rise, min_gap, min_gap_run,
        gap_resolution, order, nonfinite, cpu_seconds, rate, collision_rate_in_time, stored_min_gap,
        ring_length_drift;
};
// The rows' column names (CSV header, HDF5 datasets), in DriftRow's order, and a row's values in that order.
const std::vector<std::string>& column_names();
std::vector<double> row_values(const DriftRow& row);

struct DriftStart {
    double momentum = 0, momentum_scale = 0, energy = 0, max_speed = 0;
};

struct DriftReport {
    std::string engine;              // the engine's name()
    double ring_length = 0, spacing = 0;
    DriftStart start;                // of the unperturbed initial condition
    std::vector<DriftRow> rows;      // never empty after run_drift
    std::string ended;               // why the run stopped
    double max_rise = 0;             // largest relative energy rise between chunks
    bool order_held = true, energy_within_bound = true;
    std::int64_t nonfinite = 0;
};

// What a caller hears while the run goes: the report's engine and start once,
// before the first chunk; each row as it is taken; and lines worth printing
// (an energy rise above the bound, the pairs out of order at a disorder).
struct DriftListener {
    std::function<void(const DriftReport&)> started;
    std::function<void(const DriftRow&)> row;
    std::function<void(const std::string&)> note;
};

// Runs the realization to options.target_collisions (or until it stops);
// InputError for invalid parameters.
DriftReport run_drift(const SimulationParameters& parameters, const DriftOptions& options,
                      const DriftListener& listener = {});

// The rounding bounds assume v' = v -+ h: InputError for a run with merges
// (r = 0 or sticky sub-threshold), which they cannot judge.
void require_checkable(const SimulationParameters& parameters);

// The reasons the run fails the rounding bounds (empty: it passes): an early
// end, momentum drift or an energy rise beyond its bound, broken ring order,
// non-finite values, and with options.reference the ring-length drift
// (require_checkable first).
std::vector<std::string> check_failures(const SimulationParameters& parameters, const DriftOptions& options,
                                        const DriftReport& report);

// The rows as CSV (a header of column_names, values to 17 digits), or as HDF5
// datasets with the run's parameters and provenance as attributes.
void write_csv(const std::string& path, const DriftReport& report);
void write_h5(const std::string& path, const SimulationParameters& parameters, const DriftOptions& options,
              const DriftReport& report);

// shockgas-drift as a library call: what its options ask for, with the
// program's defaults (bench/shockgas_drift.cpp binds its options to these
// fields).
struct DriftRequest {
    SimulationParameters parameters = [] {
        SimulationParameters p;
        p.particles = 1000;
        p.collision.restitution = 0.5;
        p.collision.velocity_threshold = 1e-2;
        p.engine = "event";
        return p;
    }();
    std::string subthreshold = "elastic";  // elastic | sticky
    DriftOptions options;
    std::string output;  // also write the rows here, FILE.csv or FILE.h5 (empty: nowhere)
    bool check = false;  // the rounding bounds as pass/fail (check_failures)
};

// Runs the request as shockgas-drift does: checks the parameters and the
// output, prints the run's header, a table row as each row is taken and the
// summary (drift_summary) on stdout, writes the rows to request.output, and
// with request.check prints each failure on stderr. Returns the exit status:
// 1 when a check fails, else 0. InputError for anything the user must change.
int run_drift_command(DriftRequest request);

// The last line of the table: why the run ended, its collisions, time, CPU
// and rate, the final momentum drift against its bound, the largest energy
// rise, the smallest gap, ring order and the non-finite count ("# " first).
std::string drift_summary(const DriftReport& report);

}  // namespace shockgas::drift
