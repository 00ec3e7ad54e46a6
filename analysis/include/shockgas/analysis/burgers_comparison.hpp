// SPDX-License-Identifier: GPL-3.0-or-later
// A particle run against the Burgers equation from the same start (Fig. 5; Burgers with
// nu -> 0 is the sticky gas: shocks <-> clusters, v = (x - q)/t between shocks, Eq. 7), and
// the convergence of the Burgers solution itself (nu -> 0, grid refinement; docs/continuum.md).
// shockgas-burgers prints and writes these.
#pragma once

#include <cstddef>
#include <vector>

#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/burgers.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::analysis {

// Positions of the Burgers shocks at t whose velocity drop mass/t (Rankine-Hugoniot:
// v_- - v_+ = (q_b - q_a)/t) is at least jump_fraction v_rms: the shock detector's rule
// (analysis/README.md, "Shocks").
std::vector<double> strong_burgers_shocks(const burgers::Solver& solver, double t, double jump_fraction);

struct BurgersComparison {
    // True when the snapshot's particles have merged (the sticky gas): its clusters are then the
    // shocks, a cluster of mass M counting where M/t >= jump_fraction v_rms, as a Burgers shock
    // of that mass would. Else the shocks are find_shocks' (the Fig. 5 detector).
    bool clusters_are_shocks = false;
    // Mass-weighted mean |v_i - v_Burgers(x_i)| over the snapshot's elements, in units of v_rms.
    // An element on a Burgers shock is compared with the shock's velocity (v_- + v_+)/2.
    double velocity_misfit = 0.0;
    std::size_t particle_shocks = 0;
    // From each particle shock to the nearest strong Burgers shock, around the ring.
    double median_distance = 0.0, max_distance = 0.0;
    double mean_separation = 0.0;   // L / (number of strong Burgers shocks, at least 1)
    std::size_t matched = 0;        // particle shocks within 0.1 mean_separation of a Burgers shock
    double median_distance_reverse = 0.0;  // from each Burgers shock to the nearest particle shock
};

// The snapshot (at solver's time `t`) against the Burgers solution from its start; strong_shocks:
// strong_burgers_shocks(solver, t, jump_fraction), which the caller has already; particles: the
// run's N (the tolerance for "on a shock" is 1e-6 of a spacing).
BurgersComparison compare_with_burgers(const Snapshot& snapshot, const burgers::Solver& solver, double t,
                                       double jump_fraction, const std::vector<double>& strong_shocks,
                                       std::int64_t particles);

// The Burgers solution's own convergence at t, on the points x where v_inviscid was sampled.
struct BurgersConvergence {
    struct ViscousLimit {
        double viscosity, mean_deviation;  // mean |v_nu - v_0| over the points
    };
    struct GridLevel {
        double cells_per_particle;
        bool skipped = false;  // a coarse level whose cells would not hold whole particles (N not a multiple)
        std::size_t strong_shocks = 0;
        double median_shift = 0.0, max_shift = 0.0;  // of the strong shocks against one cell per particle
        double mean_deviation = 0.0;                 // mean |v - v_exact| over the points
    };
    std::vector<ViscousLimit> viscous_limit;  // nu = 1 ... 1e-6 at the solver's grid
    std::vector<GridLevel> grid;              // 1/16 ... 4 cells per particle against one per particle
};
BurgersConvergence burgers_convergence(const InitialCondition& initial, const burgers::Solver& solver,
                                       const std::vector<double>& x, const std::vector<double>& v_inviscid, double t,
                                       double jump_fraction);

}  // namespace shockgas::analysis
