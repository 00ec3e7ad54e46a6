// SPDX-License-Identifier: GPL-3.0-or-later
// Clusters of the disk and sphere gas (shockgas-spheres output) from its
// coarse-grained density field: the connected regions of cells denser than a
// threshold, their masses, the largest one and the distribution of masses at
// each snapshot. An inelastic gas in d dimensions is predicted to form
// clusters up to a critical size N_c ~ eps^(-2d/(4-d)), eps = (1 - r)/2
// (Ben-Naim, Chen, Doolen & Redner, PRL 83, 4069 (1999), closing paragraph).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/analysis/results.hpp"

namespace shockgas::spheres {
struct SphereOutput;
}

namespace shockgas::analysis {

// One connected region of dense cells: its mass in particles (the sum over its
// cells of density x mean_count, the cells' particle counts) and its cells.
struct Cluster {
    double mass = 0.0;
    std::size_t cells = 0;
};

// The clusters of one realization's density field: cells_per_side^dimension
// relative densities (a cell's count over the mean count, as shockgas-spheres
// writes them), cell index sum_k i_k cells_per_side^k with x (k = 0) fastest,
// as sim/spheres/src/ensemble.cpp's coarse_fields numbers them. A cell belongs
// to a cluster when its density is at least `threshold` (relative: 2 is twice
// the mean); cells sharing a face (2d neighbours) are connected, across the
// periodic box's faces too. Clusters in the order of their first cell; none
// for a field with no cell at the threshold. Throws std::invalid_argument for
// a field whose size is not cells_per_side^dimension.
std::vector<Cluster> cluster_field(std::span<const double> density, int dimension, int cells_per_side,
                                   double mean_count, double threshold);

// Cluster masses binned logarithmically, bins_per_decade bins a decade on
// edges 10^(j / bins_per_decade), pooled over realizations.
inline constexpr int cluster_bins_per_decade = 5;

// The clusters at one snapshot, over the realizations whose field was recorded
// there (a collapsed realization's later rows are NaN and left out). Errors:
// delete-one-realization jackknife (fit.hpp); with no cluster at all every
// number is 0, not NaN.
struct ClusterSnapshot {
    double time = 0.0;
    std::size_t realizations = 0;
    Estimate clusters;            // number of clusters per realization
    Estimate mean_mass;           // mass-weighted mean sum m^2 / sum m, pooled over realizations
    Estimate largest_mass;        // the largest cluster's mass, mean over realizations
    Estimate clustered_fraction;  // sum m / N, mean over realizations
    std::vector<double> bin_edges;     // mass bin edges (bins + 1)
    std::vector<double> bin_clusters;  // clusters per bin, pooled over realizations
};

struct ClusterSummary {
    double threshold = 0.0;
    double mean_count = 0.0;              // N / field_cells^d: the particles of a cell at density 1
    Measured critical_size_scale;         // eps^(-2d/(4-d)) (Ben-Naim et al. 1999), n/a for r = 1
    std::vector<ClusterSnapshot> snapshots;  // snapshots no realization reached are left out
};
ClusterSummary summarize_clusters(const spheres::SphereOutput& run, double threshold);

// shockgas-analyze clusters: per input the summary (results file, a section
// per input and a subgroup per snapshot), the numbers against t (data, a block
// per input) and the mass distribution (distribution, a block per input and
// snapshot), and realization 0's density field of the first 2D input at each
// snapshot (maps: "x y density" at the cells' centres, a block per snapshot,
// for gnuplot's `with image`).
void run_clusters(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, double threshold, const std::string& data,
                  const std::string& distribution, const std::string& maps = "");

}  // namespace shockgas::analysis
