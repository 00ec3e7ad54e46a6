// SPDX-License-Identifier: GPL-3.0-or-later
// The start of a disk or sphere gas (docs/spheres.md, "The start"):
// non-overlapping positions at the packing fraction, taken to equilibrium by an
// elastic run, then fresh Maxwell velocities with zero momentum and T = 1.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "shockgas/spheres/engine.hpp"
#include "shockgas/spheres/parameters.hpp"

namespace shockgas::spheres {

// Realization k of seed s draws from std::mt19937_64 seeded with the ring's
// seed stream realization_seed(s, k) (state.hpp), with the project's portable
// uniform and Gaussian mappings, so a seed means the same start everywhere.
// k is the absolute realization (first_realization already added).
SphereState make_start(const SphereParameters& parameters, std::int64_t realization);

// The unmelted positions: random sequential insertion, or N sites of the
// ceil(N^(1/d))^d lattice chosen at random. Velocities Maxwell, T = 1.
SphereState place_particles(const SphereParameters& parameters, std::mt19937_64& random);

// Replaces the velocities by Maxwell ones (independent Gaussian components)
// shifted to zero total momentum and scaled so that T = sum |v|^2 / (d N) = 1
// exactly, in a fixed order of summation.
void draw_maxwell_velocities(SphereState& state, std::mt19937_64& random);

// Renumbers the particles in the order of the cells (side >= 1) they lie in,
// row by row: particles near in space are then near in memory, which the
// engine's neighbour searches reward (docs/spheres.md, "Speed").
void sort_by_cell(SphereState& state);

// Writes a start as text for other codes (docs/spheres.md, "Starts for other
// codes"): a first line "d N L", then one line per particle, its d coordinates
// and d velocity components, each with 17 significant digits so that the
// doubles read back exactly. Throws h5::Error-free InputError if unwritable.
void write_start_text(const SphereState& state, const std::string& path);

// V = sum v / N, component by component.
std::vector<double> mean_velocity(const std::vector<double>& velocities, int dimension);

// T = sum |v - V|^2 / (d N), V the mean velocity (per degree of freedom, m = k_B = 1).
double temperature(const std::vector<double>& velocities, int dimension);

}  // namespace shockgas::spheres
