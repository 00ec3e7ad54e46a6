// SPDX-License-Identifier: GPL-3.0-or-later
// The validity map's observables on hand-built rings whose answers are known:
// the cluster rule, the kurtosis, the gap fraction, the structure function,
// the fragmentation rate, the departure rule and the fit of t* against delta.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "shockgas/analysis/validity.hpp"

namespace shockgas::analysis {
namespace {

// Doubles computed from a handful of exact inputs: equal up to rounding.
constexpr double rounding = 1e-12;
// nu of the sticky gas's cluster density, which scales the cluster rule's cut.
constexpr double nu = sticky_gas_cluster_prefactor;

// A ring of unit-mass particles at the given positions (ring order), velocities v.
ClusterState ring(double time, std::vector<double> position, std::vector<double> velocity) {
    ClusterState state;
    state.time = time;
    state.position = std::move(position);
    state.velocity = std::move(velocity);
    state.mass.assign(state.position.size(), 1.0);
    for (std::size_t i = 0; i < state.position.size(); ++i) state.first_particle.push_back(static_cast<std::int64_t>(i));
    return state;
}

TEST(Validity, ClustersAreRunsOfGapsBelowTheCut) {
    // t = nu^(3/2) makes the sticky gas's cluster spacing t^(2/3)/nu exactly 1
    // unit (L = N): the cut is cluster_gap_fraction = 0.1.
    const double t = std::pow(nu, 1.5);
    ValidityRule rule;
    // Ten particles on a ring of 10: the last, at 9.95, lies 0.05 before 0 (+10) and joins
    // {0, 0.05, 0.09}; then {3}, {6, 6.01}, {7}, {8}, {8.5}: six clusters.
    const ClusterState state =
        ring(t, {0.0, 0.05, 0.09, 3.0, 6.0, 6.01, 7.0, 8.0, 8.5, 9.95}, std::vector<double>(10, 0.0));
    const auto starts = cluster_starts(state, 10.0, 10, rule);
    EXPECT_EQ(starts, (std::vector<std::size_t>{3, 4, 6, 7, 8, 9}));
    const SnapshotObservables o = snapshot_observables(state, 10.0, 10, rule);
    // 6 clusters of 10 particles, times t^(2/3) / nu = 1.
    EXPECT_NEAR(o.cluster_density, 0.6, rounding);
}

TEST(Validity, OneClusterRingHasOneStart) {
    const ClusterState state = ring(1.0, {0.0, 1e-6, 2e-6}, {0.0, 0.0, 0.0});
    EXPECT_EQ(cluster_starts(state, 1e-5, 3, ValidityRule{}), (std::vector<std::size_t>{0}));
}

TEST(Validity, KurtosisOfTwoVelocitiesIsOne) {
    // Half the mass at +u, half at -u: <u^4> / <u^2>^2 = 1, whatever the mean.
    const ClusterState state = ring(1.0, {0.0, 2.0, 4.0, 6.0}, {1.5, -0.5, 1.5, -0.5});
    EXPECT_NEAR(snapshot_observables(state, 8.0, 4, ValidityRule{}).kurtosis, 1.0, rounding);
}

TEST(Validity, StructureFunctionOfPointClustersIsTheirMassSquared) {
    // All the mass at one point: |sum m e^(ikx)|^2 / N = N at every k, scaled by t^(-2/3).
    ClusterState state;
    state.time = 8.0;
    state.position = {3.0};
    state.velocity = {0.0};
    state.mass = {100.0};
    state.first_particle = {0};
    const SnapshotObservables o = snapshot_observables(state, 100.0, 100, ValidityRule{});
    EXPECT_NEAR(o.structure_function, 100.0 / 4.0, 1e-9);
}

TEST(Validity, SmallGapFractionCountsShortEmptyGaps) {
    const double t = std::pow(nu, 1.5);  // cut 0.1 (as above)
    // Four single-particle clusters on a ring of 40, gaps 1, 13, 13, 13: mean 10, short < 1 (fraction 0.1):
    // none; the gap of 1 is just at the threshold, so it does not count; with 0.5 it would.
    const ClusterState state = ring(t, {0.0, 1.0, 14.0, 27.0}, {0.0, 0.0, 0.0, 0.0});
    EXPECT_NEAR(snapshot_observables(state, 40.0, 4, ValidityRule{}).small_gap_fraction, 0.0, rounding);
    ValidityRule wider;
    wider.small_gap_fraction = 0.2;  // short < 2: the gap of 1
    EXPECT_NEAR(snapshot_observables(state, 40.0, 4, wider).small_gap_fraction, 0.25, rounding);
}

TEST(Validity, FragmentationCountsClustersWhoseParticlesPart) {
    const double t = std::pow(nu, 1.5);
    // Earlier: {0,1,2} {3} {4,5}; later (time e t, so per unit ln t is per cluster):
    // {0,1} {2,3} {4,5}: the first cluster split, the others did not.
    const ClusterState earlier =
        ring(t, {0.0, 0.01, 0.02, 3.0, 6.0, 6.01}, std::vector<double>(6, 0.0));
    // At time e t the cut is 0.1 e^(2/3) = 0.195.
    const ClusterState later =
        ring(t * std::numbers::e, {0.0, 0.01, 1.5, 1.51, 6.0, 6.01}, std::vector<double>(6, 0.0));
    EXPECT_NEAR(fragmentation_rate(earlier, later, 9.0, 6, ValidityRule{}), 1.0 / 3.0, rounding);
    // Clusters that merge do not fragment.
    EXPECT_NEAR(fragmentation_rate(later, ring(t * 10.0, {0.0, 0.0, 0.0, 0.0, 6.0, 6.0}, std::vector<double>(6, 0.0)),
                                   9.0, 6, ValidityRule{}),
                0.0, rounding);
}

TEST(Validity, FragmentationFollowsAClusterAcrossTheRingsEnd) {
    const double t = std::pow(nu, 1.5);
    // Earlier: particles 4, 5, 0 form one cluster across x = 0; later, 5 and 0 part.
    const ClusterState earlier = ring(t, {0.0, 2.0, 2.5, 5.0, 8.98, 8.99}, std::vector<double>(6, 0.0));
    const ClusterState later = ring(t * std::numbers::e, {0.5, 2.0, 2.5, 5.0, 8.98, 8.99}, std::vector<double>(6, 0.0));
    // Earlier clusters: {4,5,0}, {1}, {2}, {3}: one of four split.
    EXPECT_NEAR(fragmentation_rate(earlier, later, 9.0, 6, ValidityRule{}), 0.25, rounding);
}

// An observable history of R realizations: a constant value, plus `step` from t >= t_step.
ObservableHistory history(const std::string& name, const std::vector<double>& times, std::size_t realizations,
                          double value, double step, double t_step, double noise) {
    ObservableHistory h;
    h.observable = name;
    h.values.time = times;
    h.values.realizations = realizations;
    for (std::size_t r = 0; r < realizations; ++r)
        for (const double t : times)
            h.values.temperature.push_back(value + (t >= t_step ? step : 0.0) +
                                           noise * (static_cast<double>(r % 3) - 1.0));
    return h;
}

TEST(Validity, DepartureIsWhereTheFinalStretchOutsideBegins) {
    const std::vector<double> times = {1, 10, 100, 1000, 10000};
    const auto reference = history("kurtosis", times, 6, 1.0, 0.0, 0.0, 0.001);
    // The run joins the reference at t = 10 (outside at t = 1), leaves it at 1000 by 10 %.
    auto run = history("kurtosis", times, 6, 1.0, 0.1, 1000.0, 0.001);
    run.values.temperature[0] += 0.5;  // realization 0 at t = 1: outside at first
    for (std::size_t r = 1; r < 6; ++r) run.values.temperature[r * times.size()] += 0.5;
    const ValidityDeparture d = departure(run, reference, "5percent", ValidityRule{});
    EXPECT_EQ(d.departure_time, 1000.0);
    // Every replica departs at the same sample: sigma is the grid's, ln(10)/sqrt(12) relative.
    EXPECT_NEAR(d.departure_sigma / d.departure_time, std::log(10.0) / std::sqrt(12.0), 1e-9);
    // A run that never left: +inf; one that was never inside: NaN.
    EXPECT_TRUE(std::isinf(departure(reference, reference, "1percent", ValidityRule{}).departure_time));
    const auto outside = history("kurtosis", times, 6, 2.0, 0.0, 0.0, 0.001);
    EXPECT_TRUE(std::isnan(departure(outside, reference, "1percent", ValidityRule{}).departure_time));
}

TEST(Validity, FitRecoversMuAndNamesThePrediction) {
    // t* = 2 delta^-3 exactly, 10 % sigma: mu = 3 with a small sigma.
    std::vector<ValidityRun> runs;
    for (const double delta : {0.1, 0.03, 0.01}) {
        ValidityRun run;
        run.velocity_threshold = delta;
        run.subthreshold = "elastic";
        run.restitution = 0.9;
        const double t = 2.0 * std::pow(delta, -3.0);
        run.departures.push_back({"temperature", "1percent", t, 0.1 * t, ""});
        runs.push_back(run);
    }
    std::vector<const ValidityRun*> pointers;
    for (const auto& run : runs) pointers.push_back(&run);
    const ValidityFit fit = fit_departures(pointers, "temperature", "1percent");
    EXPECT_NEAR(fit.mu, 3.0, 1e-9);
    EXPECT_NEAR(fit.log_amplitude, std::log(2.0), 1e-9);
    EXPECT_EQ(fit.follows, "delta^-3");
    EXPECT_EQ(fit.points, 3);
    // Too few departures: n/a with the reason.
    const ValidityFit none = fit_departures(pointers, "kurtosis", "3sigma");
    EXPECT_TRUE(std::isnan(none.mu));
    EXPECT_NE(none.follows.find("n/a"), std::string::npos);
}

}  // namespace
}  // namespace shockgas::analysis
