// SPDX-License-Identifier: GPL-3.0-or-later
// Homogeneous cooling of the disk and sphere gas (shockgas-spheres output):
// T(t) against Haff's law with Enskog's t0 (kinetic_theory.hpp), t0 fitted,
// and the start of clustering from the coarse-grained density field.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/analysis/results.hpp"

namespace shockgas::spheres {
struct SphereOutput;
struct SphereParameters;
}

namespace shockgas::analysis {

// The cells of a run's coarse-grained fields, field_cells^d: the length of one
// realization's row of /snapshots/<k>/density (cooling, clusters, late-decay).
std::size_t field_cell_count(const spheres::SphereParameters& parameters);

// The clustering index of one realization's density field: the variance of
// the particle count per cell over its mean, mean_count var(rho / rho_mean).
// 1 for particles placed independently (Poisson), below 1 for the hard-sphere
// fluid (its S(k -> 0)), growing as the gas clusters.
double clustering_index(const std::vector<double>& density, std::size_t first_cell, std::size_t cells,
                        double mean_count);

struct CoolingSummary {
    double haff_time = 0.0;          // t0 from Enskog theory
    Estimate fitted_haff_time;       // t0 from T^(-1/2) = (1 + t/t0) over t <= t0, jackknife sigma
    double largest_haff_deviation = 0.0;  // max |T / T_Haff - 1| of the ensemble mean over 0 < t <= t0
    Estimate final_clustering_index; // at the last snapshot, mean over realizations
};
CoolingSummary summarize_cooling(const spheres::SphereOutput& run);

// shockgas-analyze cooling: per input the summary (results file, a section
// each), the table T(t) with T_Haff (data, a block per input), the clustering
// index against t (clustering, a block per input), and realization 0's
// positions at the last snapshot of the first 2D input (picture).
void run_cooling(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                 const std::string& output, const std::string& data, const std::string& clustering,
                 const std::string& picture);

}  // namespace shockgas::analysis
