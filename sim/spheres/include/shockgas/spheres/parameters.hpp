// SPDX-License-Identifier: GPL-3.0-or-later
// Parameters of a gas of inelastic hard disks (d = 2) or spheres (d = 3) in a
// periodic box: the paper's collision rule with its threshold, applied to the
// normal relative velocity. One struct, validated in one place.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/model/parameters.hpp"

namespace shockgas::spheres {

// How the start's positions are made (docs/spheres.md, "The start").
//   insertion: random sequential insertion of non-overlapping spheres, then an
//              elastic run ("melting") that takes the positions to equilibrium;
//   lattice:   a simple cubic (square) lattice, then the same elastic run.
// Both then draw fresh Maxwell velocities, independent of the positions as in
// equilibrium, with zero total momentum and T = 1 exactly.
enum class StartMethod { insertion, lattice };
std::string to_string(StartMethod method);
StartMethod start_method_from_string(const std::string& name);  // throws InputError

// Random sequential insertion jams at phi = 0.547 (d = 2) and 0.384 (d = 3)
// (Feder 1980; Cooper 1988) and slows near it; it is offered below these.
double insertion_packing_limit(int dimension);
// The lattice holds spheres of diameter 1 at spacing >= 1: phi <= pi/4 (d = 2), pi/6 (d = 3).
double lattice_packing_limit(int dimension);

struct SphereParameters {
    int dimension = 3;
    std::int64_t particles = 1000;       // N, diameter sigma = 1, mass 1
    double packing_fraction = 0.1;       // phi = N v_d / L^d, v_d the volume of one sphere
    CollisionModel collision{0.9, 1e-2, Subthreshold::elastic};  // restitution, velocity_threshold
    // Inelastic collapse (delta = 0, r < 1): the run stops, reported as
    // collapsed, at the first inelastic collision slower than this.
    double collapse_speed = 1e-12;
    StartMethod start = StartMethod::insertion;
    double melt_collisions_per_particle = 20.0;  // the elastic run that equilibrates the start
    double t_max = 100.0;
    int samples_per_decade = 10;
    std::vector<double> sample_times;      // extra times, merged with the log grid
    std::vector<double> snapshot_times;    // positions and velocities of realization 0
    std::vector<double> histogram_times;   // velocity-component histograms, scaled by sqrt(T)
    int histogram_bins = 120;
    double histogram_range = 6.0;          // bins cover |v_k - V_k| / sqrt(T) <= range
    int field_cells = 32;                  // coarse-grained fields: field_cells^d cells at snapshots
    int realizations = 1;
    std::int64_t first_realization = 0;
    std::uint64_t seed = 1;
    int threads = 0;                       // 0: every hardware thread
};

// The volume of a sphere of diameter 1 in d dimensions: pi/4 (d = 2), pi/6 (d = 3).
double sphere_volume(int dimension);
// The box side L with N spheres at packing fraction phi: L^d = N v_d / phi.
double box_length(int dimension, std::int64_t particles, double packing_fraction);
// Cells of side >= 1 per box side; the engine needs at least 3.
int cells_per_side(double box_length);

// Throws InputError naming the first problem: dimension not 2 or 3, N < 2,
// phi out of (0, the start method's limit], a box of fewer than 3 cells a side
// (N too small for phi), r outside (0, 1], delta < 0 or not finite, a sticky
// sub-threshold rule (merging is the ring's; disks and spheres stay whole),
// t_max, the sampling and the histogram out of range.
void validate(const SphereParameters& parameters);

// The log-spaced sample grid from t = 0.01 to t_max (samples_per_decade per
// decade), with t = 0 first and the listed sample, snapshot and histogram times
// merged in, sorted, duplicates removed.
std::vector<double> sample_grid(const SphereParameters& parameters);

}  // namespace shockgas::spheres
