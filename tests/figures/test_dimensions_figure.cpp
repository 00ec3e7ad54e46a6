// SPDX-License-Identifier: GPL-3.0-or-later
// fig_2d, fig_3d, fig_2d_clusters and fig_3d_clusters at the quick tier, through the real pipeline
// (the fixture figures.build built them): the paper's d-dimensional prediction
// as far as these sizes carry it (docs/dimensions.md). Each tolerance says what
// it was set from; the quick tier's measured values are in docs/dimensions.md.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/clusters.hpp"
#include "shockgas/analysis/late_decay.hpp"
#include "shockgas/spheres/ensemble.hpp"

namespace shockgas::analysis {
namespace {

const std::string pipeline = std::string(SHOCKGAS_PIPELINE_DIR);  // build/paper_targets/quick

spheres::SphereOutput run(const std::string& figure, const std::string& name) {
    return spheres::read_spheres_output(pipeline + "/" + figure + "/" + name + ".h5");
}

// In 2D Burgers (d/2) and ballistic aggregation (2d/(d+2)) both give theta = 1.
// The quick runs measure 1.08-1.12 with jackknife sigma 0.02-0.05 and window
// sigma 0.06-0.11: 0.25 is about twice the largest combined error, and still
// tells 1 from Haff's 2 and from a gas that stopped cooling (0).
constexpr double theta_2d_tolerance = 0.25;
// The late decay is slower than Haff's t^-2 by far more than its errors: theta
// below 2 by at least this many combined sigma (measured: 2D > 8, 3D > 6).
constexpr double slower_than_haff_sigmas = 5.0;
// tau_c ~ eps^x: predicted x = -2 in 2D, measured -1.58 +- 0.10 (3 eps). The
// test asks for the sign and the size of a crossover that moves with eps as a
// power between -1 and -3, not for the prediction, which the quick tier misses.
constexpr double crossover_exponent_low = -3.0, crossover_exponent_high = -1.0;
// The 3D gas leaves Maxwell during the crossover: the kurtosis peaks at 3.19,
// 3.27, 3.41 (eps = 0.25, 0.3, 0.4). Its statistical error at one sample is
// about sqrt(96 / n) = 0.013 for n = 6e5 velocity components; 3.1 is 7 of them
// above Maxwell's 3 and below the smallest peak.
constexpr double crossover_kurtosis = 3.1;
// The plateau of the local exponent (local_plateau): in 2D 0.97, 1.00, 0.99 with
// jackknife sigma 0.09, 0.04, 0.04 (eps = 0.1, 0.15, 0.2), on the 1 of both
// theories within 3 sigma. In 3D 1.18, 1.19, 1.25 +- 0.02 at N = 5e4, at 0.7-1.8
// t_N: below Burgers' 3/2 by more than 5 sigma (what it means at this N:
// docs/dimensions.md).
constexpr double plateau_sigmas = 3.0;
constexpr double below_burgers_sigmas = 5.0;
// In Haff's regime (t = 10, tau = 18) the 3D velocity distribution has
// overpopulated tails, as the homogeneous cooling state's (van Noije & Ernst,
// Granular Matter 1, 57 (1998)): the tail fit's gamma is 1.71, 1.60, 1.45
// (eps = 0.25, 0.3, 0.4) with sigma 0.03, 10-18 sigma below a Gaussian's 2.
// sigma is the Poisson Delta chi2 = 1 width, which leaves out the particles'
// correlations (fit_pooled_tail): hence 5 of them, not 3.
constexpr double overpopulated_tail_sigmas = 5.0;
// The 2D gas clusters: the share of particles in cells at twice the mean
// density grows from 1-3 % at t = 100 to 67-72 % at t = 4e4 (quick runs).
constexpr double early_clustered_fraction = 0.1, late_clustered_fraction = 0.5;
// The 3D gas clusters too, past the paper's critical size scale eps^-6 (4096,
// 1372, 244 particles at eps = 0.25, 0.3, 0.4): the largest cluster at t = 3000
// (about 4 t_N) holds 15 555 +- 1573, 17 396 +- 1845, 17 660 +- 1358 particles
// (the mean over 4 realizations and its standard error). The test asks for the
// largest above the scale by 5 of its sigma (measured: 7.3, 8.7, 12.8), so a
// growth that stopped at N_c, as the paper's picture has it, fails it.
constexpr double past_critical_size_sigmas = 5.0;

double combined_sigma(const LateDecaySummary& s) {
    return std::hypot(s.late.theta.sigma, s.theta_window_sigma.value);
}

TEST(DimensionsFigure, TwoDimensionalLateDecayIsOneOverT) {
    std::vector<CrossoverPoint> points;
    for (const char* name : {"e0.1", "e0.15", "e0.2"}) {
        const auto summary = summarize_late_decay(run("fig_2d", name), LateDecayRule{});
        ASSERT_FALSE(std::isnan(summary.late.theta.value)) << name << ": " << summary.late.theta.note;
        EXPECT_NEAR(summary.late.theta.value, 1.0, theta_2d_tolerance) << name;
        EXPECT_LT(summary.late.theta.value, 2.0 - slower_than_haff_sigmas * combined_sigma(summary)) << name;
        ASSERT_FALSE(std::isnan(summary.plateau.theta.value)) << name << ": " << summary.plateau.theta.note;
        EXPECT_NEAR(summary.plateau.theta.value, 1.0, plateau_sigmas * summary.plateau.theta.sigma) << name;
        points.push_back({summary.eps, summary.crossover_collisions});
    }
    const LinearFit crossover = fit_crossover_exponent(points);
    EXPECT_GT(crossover.slope, crossover_exponent_low);
    EXPECT_LT(crossover.slope, crossover_exponent_high);
}

TEST(DimensionsFigure, ThreeDimensionalGasIsSlowerThanHaffAndLeavesMaxwell) {
    for (const char* name : {"e0.25", "e0.3", "e0.4"}) {
        const auto summary = summarize_late_decay(run("fig_3d", name), LateDecayRule{});
        EXPECT_GT(*std::max_element(summary.kurtosis.begin(), summary.kurtosis.end()), crossover_kurtosis) << name;
        ASSERT_FALSE(std::isnan(summary.plateau.theta.value)) << name << ": " << summary.plateau.theta.note;
        EXPECT_LT(summary.plateau.theta.value, 1.5 - below_burgers_sigmas * summary.plateau.theta.sigma) << name;
        if (std::string(name) != "e0.4") {
            // N = 5e4 leaves no decade between 3 t_pred and 0.3 t_N at these eps: said, not fitted.
            EXPECT_TRUE(std::isnan(summary.late.theta.value)) << name;
            EXPECT_NE(summary.late.theta.note.find("window empty"), std::string::npos) << name;
            continue;
        }
        ASSERT_FALSE(std::isnan(summary.late.theta.value)) << summary.late.theta.note;
        EXPECT_LT(summary.late.theta.value, 2.0 - slower_than_haff_sigmas * combined_sigma(summary));
    }
}

TEST(DimensionsFigure, ThreeDimensionalTailsAreOverpopulatedInHaffsRegime) {
    for (const char* name : {"e0.25", "e0.3", "e0.4"}) {
        const auto summary = summarize_late_decay(run("fig_3d", name), LateDecayRule{});
        ASSERT_FALSE(summary.tails.empty()) << name << ": the run has no --histogram-times";
        const TailSample& haff = summary.tails.front();
        EXPECT_LT(haff.time, summary.haff_time * 10.0) << name << ": the first histogram is in Haff's regime";
        ASSERT_FALSE(std::isnan(haff.gamma.value)) << name << ": " << haff.gamma.note;
        EXPECT_LT(haff.gamma.value, 2.0 - overpopulated_tail_sigmas * haff.gamma.sigma) << name;
    }
}

TEST(DimensionsFigure, TwoDimensionalGasClusters) {
    for (const char* name : {"e0.1", "e0.15", "e0.2"}) {
        const ClusterSummary summary = summarize_clusters(run("fig_2d", name), 2.0);
        ASSERT_GE(summary.snapshots.size(), 2u) << name;
        EXPECT_LT(summary.snapshots.front().clustered_fraction.value, early_clustered_fraction) << name;
        EXPECT_GT(summary.snapshots.back().clustered_fraction.value, late_clustered_fraction) << name;
    }
}

TEST(DimensionsFigure, ThreeDimensionalClustersOutgrowTheCriticalSize) {
    for (const char* name : {"e0.25", "e0.3", "e0.4"}) {
        const ClusterSummary summary = summarize_clusters(run("fig_3d", name), 2.0);
        ASSERT_GE(summary.snapshots.size(), 2u) << name;
        ASSERT_TRUE(summary.critical_size_scale.known()) << name;
        const Estimate& largest = summary.snapshots.back().largest_mass;
        EXPECT_GT(largest.value, summary.critical_size_scale.value + past_critical_size_sigmas * largest.sigma)
            << name << ": largest cluster " << largest.value << " +- " << largest.sigma << " against eps^-6 = "
            << summary.critical_size_scale.value;
    }
}

}  // namespace
}  // namespace shockgas::analysis
