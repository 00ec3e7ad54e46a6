// SPDX-License-Identifier: GPL-3.0-or-later
// The Burgers equation v_t + v v_x = nu v_xx on a periodic interval, from the
// initial velocity field of a particle run (docs/continuum.md: nu -> 0 gives the
// sticky gas; shocks <-> clusters, v = (x - q)/t between shocks, Eq. 7).
//
// Initial data: piecewise constant on M equal cells of width h = L/M. The
// particles of an InitialCondition (spacing L/N, cell of particle i centred on
// x_i) are placed on the grid by `grid_from_particles`: with M = k N each
// particle fills k cells with its own velocity (the particle field exactly);
// with M < N each cell gets the mean velocity of the particles in it
// (momentum conserved). Phi0(q) = int_0^q v0 is then piecewise linear.
//
// Both solutions use the Hopf-Lax form of the Lagrangian picture:
//   G_x(q) = (x - q)^2 / (2t) + Phi0(q),
// (a) inviscid: q*(x) = argmin_q G_x(q), v = (x - q*)/t            (Eq. 7);
// (b) viscous (Hopf-Cole): v = int (x-q)/t e^{-G_x/(2 nu)} dq / int e^{-G_x/(2 nu)} dq,
//     i.e. v = -2 nu d ln u/dx with u = int exp(-(x-q)^2/(4 nu t) - Phi0(q)/(2 nu)) dq,
//     done cell by cell in closed form (G_x is quadratic on each cell) and summed as a
//     ratio of log-sum-exps, so nothing overflows at nu = 1e-6.
// The mean velocity V is removed first (Phi0 is then periodic) and restored by
// Galilean invariance: v(x, t) = V + w(x - V t, t).
#pragma once

#include <cstdint>
#include <vector>

#include "shockgas/model/state.hpp"

namespace shockgas::burgers {

// Initial data on the periodic grid: cell c covers [c h, (c+1) h) shifted by
// origin (so that a particle's cell is centred on the particle).
struct Grid {
    double ring_length = 0.0;
    double origin = 0.0;             // left edge of cell 0
    std::vector<double> velocity;    // v0 per cell
    double cell_width() const { return ring_length / static_cast<double>(velocity.size()); }
};

// How far (a fraction of L) a particle may sit from its lattice site x_0 + i L/N
// and count as on it: rounding of positions written and read back, far below
// any spacing a start could mean.
constexpr double lattice_tolerance = 1e-9;

// The first particle of initial off the lattice of its start (x_i = x_0 + i L/N
// within lattice_tolerance L), or -1 when all are on it, as
// `shockgas-sim --positions lattice` places them.
std::int64_t first_off_lattice(const InitialCondition& initial);

// Particles (equally spaced, unit masses, as generate_initial_condition makes
// them) onto M cells; M a multiple or a divisor of N. Throws InputError otherwise
// (std::invalid_argument for no particles or no cells).
Grid grid_from_particles(const InitialCondition& initial, std::int64_t cells);

// A shock of the inviscid solution: Lagrangian interval [q_left, q_right]
// (the mass swept into it; one cluster of the sticky gas) located at x.
struct Shock {
    double position = 0.0;   // Eulerian, wrapped into [0, L)
    double q_left = 0.0;     // Lagrangian end points, unrolled
    double q_right = 0.0;
    double mass() const { return q_right - q_left; }  // initial density 1 per unit length
    double velocity = 0.0;   // (v_- + v_+)/2 = mean initial velocity over [q_left, q_right]
};

class Solver {
public:
    explicit Solver(Grid grid);

    // (a) Inviscid velocity at the points x (any real numbers; periodic), time t > 0.
    std::vector<double> inviscid(const std::vector<double>& x, double t) const;
    // Shocks at time t with mass >= min_mass (faces of the convex minorant of
    // Y(q) = q^2/2 + t Phi0(q) spanning more than one cell), sorted by position.
    std::vector<Shock> shocks(double t, double min_mass = 0.0) const;
    // Mass-weighted temperature sum_faces M V^2 / L in the centre-of-mass frame (the
    // sticky gas's T: each face of the minorant is one cluster, single cells included).
    double temperature(double t) const;
    // (b) Viscous velocity, nu > 0.
    std::vector<double> viscous(const std::vector<double>& x, double t, double nu) const;

    double mean_velocity() const { return mean_velocity_; }
    double ring_length() const { return grid_.ring_length; }
    std::size_t cells() const { return grid_.velocity.size(); }

private:
    Grid grid_;
    double mean_velocity_ = 0.0;
    std::vector<double> phi_;        // Phi0 at the cell edges 0..M (periodic: phi_[M] = phi_[0] = 0)
    double phi_min_ = 0.0, phi_max_ = 0.0;

    // Unrolled cell index c (any integer) -> its left edge, velocity, Phi0 at the left edge.
    double edge(std::int64_t c) const;
    double cell_velocity(std::int64_t c) const;
    double phi_at_edge(std::int64_t c) const;
    // Half-width of the window of q that can hold the minimiser of G_x (plus extra in G).
    double reach(double t, double extra) const;
    double face_slope(std::int64_t a, std::int64_t b, double t) const;
    std::vector<std::int64_t> lower_hull(double t) const;
};

// Velocities on n equally spaced points x_j = j L / n (lab frame).
std::vector<double> sample_points(double ring_length, std::int64_t points);

}  // namespace shockgas::burgers
