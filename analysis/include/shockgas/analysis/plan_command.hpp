// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-plan as a library call: from the validity map (validity_map.hpp), the
// cheapest threshold delta and sub-threshold mechanism whose measured run at the
// requested r keeps one observable of the delta > 0 gas within a tolerance of
// the sticky gas up to t_max, with its cost. The program
// (analysis/app/shockgas_plan.cpp) binds its options to a PlanRequest and calls
// run_plan. It answers only from what the map measured: an r, a time, a ring
// smaller or an observable outside the map is refused, naming what is measured.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "shockgas/analysis/validity_map.hpp"

namespace shockgas::analysis {

struct PlanRequest {
    double t_max = 0.0;           // the time the user's run must reach
    std::int64_t particles = 0;   // the user's N
    double restitution = 0.0;     // r, one of the map's
    std::string observable;       // one of the map's observables
    std::string tolerance;        // a criterion: 3sigma, 1percent or 5percent
    std::string map_file;         // the results file whose /validity_map is read
};

// One measured run at the requested r, as the planner judges it.
struct PlanOption {
    std::string run;                   // the run's name in the map
    double velocity_threshold = 0.0;   // delta
    std::string subthreshold;          // elastic | sticky
    std::int64_t particles = 0;        // the N it was measured at
    double t_end = 0.0;
    double departure_time = 0.0;       // t* of the observable by the tolerance (NaN: never within, or not measured)
    bool measured = false;             // the run has a departure of this observable by this tolerance
    bool valid = false;                // measured, t_max <= t_end, and t* > t_max
    std::string why_not;               // when not valid: the reason in a few words
    double collisions_per_particle = 0.0;   // at t_max (NaN where the run's samples do not reach t_max)
    double cpu_seconds_per_realization = 0.0;  // at the user's N and t_max (NaN where not measurable)
};

struct Plan {
    std::string map_version;
    std::vector<PlanOption> options;  // every run at r (and N at most the user's), by delta then mechanism
    std::size_t best = 0;             // the index in options of the cheapest valid one
};

// The plan, or InputError (one line: what is refused, and what the map measured).
Plan make_plan(const ValidityMap& map, const PlanRequest& request);

// The plan as the program prints it: the answer first, then the table of every
// measured (delta, mechanism) at r with t* and cost, then the map's version.
std::string format_plan(const Plan& plan, const PlanRequest& request);

// Reads request.map_file (InputError when it is empty: how to make the map, or
// --map) and prints the plan to out.
void run_plan(const PlanRequest& request, std::FILE* out);

}  // namespace shockgas::analysis
