// SPDX-License-Identifier: GPL-3.0-or-later
// The event engine against conservation laws and theory at small N, fixed seeds.
#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "shockgas/run/ensemble.hpp"
#include "reference_event_engine.hpp"
#include "shockgas/model/observables.hpp"

namespace {

using namespace shockgas;

struct RunInvariants {
    double momentum_before, momentum_after, momentum_scale;
    double min_gap, gap_sum, energy_increase;
    double temperature_before, temperature_after;
    std::uint64_t collisions;
};

// Runs one realization to t_max, checking at 100 intermediate times that the
// kinetic energy never increases and that the gaps stay non-negative.
RunInvariants run_checked(const CollisionModel& model, std::int64_t particles, double t_max, std::uint64_t seed) {
    const auto initial = generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
    ReferenceEventEngine engine(initial, model, {});
    RunInvariants out{};
    CompensatedSum momentum, scale;
    for (std::size_t i = 0; i < initial.velocity.size(); ++i) {
        momentum.add(initial.velocity[i]);
        scale.add(std::abs(initial.velocity[i]));
    }
    out.momentum_before = momentum.value();
    out.momentum_scale = scale.value();
    out.temperature_before = velocity_moments(initial.velocity, initial.mass).temperature;
    out.min_gap = INFINITY;
    double previous_energy = velocity_moments(initial.velocity, initial.mass).kinetic_energy;
    ClusterState state;
    for (int k = 1; k <= 100; ++k) {
        EXPECT_TRUE(engine.advance_to(t_max * k / 100.0));
        engine.clusters(state);
        const auto moments = velocity_moments(state.velocity, state.mass);
        out.energy_increase = std::max(out.energy_increase, moments.kinetic_energy - previous_energy);
        previous_energy = moments.kinetic_energy;
        const auto gaps = engine.gaps();
        out.min_gap = std::min(out.min_gap, *std::min_element(gaps.begin(), gaps.end()));
        CompensatedSum total;
        for (double g : gaps) total.add(g);
        out.gap_sum = total.value();
    }
    CompensatedSum after;
    for (std::size_t i = 0; i < state.size(); ++i) after.add(state.mass[i] * state.velocity[i]);
    out.momentum_after = after.value();
    out.temperature_after = velocity_moments(state.velocity, state.mass).temperature;
    out.collisions = engine.collisions();
    return out;
}

// Momentum: every collision rounds two velocities (<= 2 ulp of |v| <= 1 each)
// and merges round once more; the errors are independent, so after C
// collisions the drift is ~ sqrt(C) * 2 * 2^-53. The bound below is 10x that
// random-walk estimate for C = 10^7 (sqrt(C) = 3.2e3): 10 * 3.2e3 * 2.2e-16 = 7e-12.
constexpr double momentum_drift_bound = 7e-12;
// Ring closure: the gaps are updated independently but must sum to L; each
// of the C gap updates adds ~ulp(gap) of error, random-walk again:
// 10 * sqrt(C) * ulp(1) relative to L = N for C = 10^7, as above.
constexpr double gap_sum_relative_bound = 7e-12;
// "The order of particles is never violated": a gap may go negative only by
// the rounding of one update, ~ulp of the spacing 1.
constexpr double negative_gap_bound = 1e-13;
// Kinetic energy never increases: between samples it can only appear to
// rise by rounding of the sum of N ~1 terms, 1e-12 relative for N = 10^4.
constexpr double energy_increase_bound = 1e-12;

TEST(PhysicsEvent, ConservationAndOrderWithElasticSubthreshold) {
    const auto run = run_checked({0.9, 1e-2, Subthreshold::elastic}, 10000, 1000.0, 11);
    EXPECT_GT(run.collisions, 1000000u);  // the run really collided a lot
    EXPECT_LE(std::abs(run.momentum_after - run.momentum_before), momentum_drift_bound * run.momentum_scale);
    EXPECT_NEAR(run.gap_sum, 10000.0, gap_sum_relative_bound * 10000.0);
    EXPECT_GE(run.min_gap, -negative_gap_bound);
    EXPECT_LE(run.energy_increase, energy_increase_bound);
}

TEST(PhysicsEvent, ConservationAndOrderWithStickySubthreshold) {
    const auto run = run_checked({0.5, 1e-2, Subthreshold::sticky}, 10000, 1000.0, 12);
    EXPECT_LE(std::abs(run.momentum_after - run.momentum_before), momentum_drift_bound * run.momentum_scale);
    EXPECT_NEAR(run.gap_sum, 10000.0, gap_sum_relative_bound * 10000.0);
    EXPECT_GE(run.min_gap, -negative_gap_bound);
    EXPECT_LE(run.energy_increase, energy_increase_bound);
}

TEST(PhysicsEvent, ElasticGasKeepsItsTemperature) {
    // r = 1: equal-mass elastic collisions exchange velocities, so T is
    // constant up to the rounding of v - (v - u) (1 ulp per collision).
    constexpr double elastic_temperature_tolerance = 1e-12;
    const auto run = run_checked({1.0, 0.0, Subthreshold::elastic}, 2000, 500.0, 13);
    EXPECT_GT(run.collisions, 100000u);
    EXPECT_NEAR(run.temperature_after, run.temperature_before, elastic_temperature_tolerance);
}

TEST(PhysicsEvent, PureInelasticGasStopsAtCollapseWithinSeconds) {
    SimulationParameters p;
    p.particles = 100000;
    p.collision = {0.5, 0.0, Subthreshold::elastic};
    p.t_max = 1e4;
    p.realizations = 2;
    const auto result = run_ensemble(p, nullptr);
    EXPECT_EQ(result.status, "collapsed");
    ASSERT_EQ(result.collapses.size(), 2u);
    for (const auto& c : result.collapses) {
        // eps = 1/4: t_stick ~ eps^(-3/2) = 8; the run must stop at a time of
        // that order, with a cluster of at least the three particles that
        // collapse needs, and not hang (the test's own timeout is 300 s; it
        // runs in well under a second).
        EXPECT_GT(c.report.time, 1.0);
        EXPECT_LT(c.report.time, 100.0);
        EXPECT_GE(c.report.cluster_mass, 3);
        EXPECT_FALSE(c.state.velocity.empty());
    }
    // Samples after the collapse are marked not reached (NaN), earlier ones are not.
    EXPECT_FALSE(std::isnan(result.temperature[0]));
    EXPECT_TRUE(std::isnan(result.temperature.back()));
}

// Haff's law for this collision rule (derivation in docs/haff-and-collapse.md).
// A collision of relative speed g removes eps (1 - eps) g^2 of kinetic energy
// (Eq. 1); with molecular chaos at unit density, collisions of relative speed g
// happen at rate |g|/2 per unit length, so per particle
//   dT/dt = -eps (1 - eps) <|g|^3>,  <|g|^3> = C T^(3/2),
//   T(t) = T0 / (1 + A eps (1 - eps) sqrt(T0) t)^2,  A = C / 2.
// For velocities uniform on [-1, 1], <|g|^3> = 4/5 and T0 = 1/3, so
// C = (4/5) 3^(3/2) and A = 6 sqrt(3) / 5 = 2.0785 while eps t << 1 (the shape
// of the distribution has not changed yet).
constexpr double haff_constant_uniform = 6.0 * 1.7320508075688772 / 5.0;
// Measured systematics at eps = 1e-3, t = 100 (docs/haff-and-collapse.md, table): the lattice
// start delays collisions by about half a crossing per pair (-0.2%), and the
// distribution's change of shape enters at O(eps t). 1% covers both, while the
// Gaussian-shape constant 4/sqrt(pi) = 2.257 (+8.6%) would fail.
constexpr double haff_relative_tolerance = 0.01;

// A of Haff's law measured at time t: N = 1e5 on the lattice from `law`'s
// velocities (seed 21), T0 the sample's own, T = T0 / (1 + A eps (1 - eps)
// sqrt(T0) t)^2 inverted for A. NaN if the run stops early.
double measured_haff_constant(double restitution, double t, const InitialLaw& law) {
    const double eps = (1 - restitution) / 2;
    const auto initial = generate_initial_condition(100000, 100000.0, 21, 0, law);
    const double t0 = velocity_moments(initial.velocity, initial.mass).temperature;
    ReferenceEventEngine engine(initial, {restitution, 0.0, Subthreshold::elastic}, {});
    if (!engine.advance_to(t)) return std::numeric_limits<double>::quiet_NaN();
    ClusterState state;
    engine.clusters(state);
    const double temperature = velocity_moments(state.velocity, state.mass).temperature;
    return (std::sqrt(t0 / temperature) - 1.0) / (eps * (1 - eps) * std::sqrt(t0) * t);
}

TEST(PhysicsEvent, EarlyCoolingFollowsHaffsLawWithDerivedConstant) {
    const double measured_a = measured_haff_constant(0.998, 100.0, {});
    EXPECT_NEAR(measured_a, haff_constant_uniform, haff_relative_tolerance * haff_constant_uniform);
}

// The same law from the Gaussian start of the same T0 = 1/3: g = v1 - v2 is
// normal with variance 2 T0, <|g|^3> = 8 T0^(3/2) / sqrt(pi), so C = 8/sqrt(pi)
// and A = 4/sqrt(pi) = 2.2568, the constant shockgas-analyze crossover
// --haff-constant derived uses for such runs. The Gaussian's tail changes
// shape faster than the uniform law: at eps t = 0.1 (the test above) A comes
// out 1.1% low, so this test takes eps t = 0.025, where it is 0.64% low here
// and 0.51-0.58% low with N = 4e5 and seeds 21, 22, 23: the shape change and
// the lattice start, with little noise. The same 1% covers that, and the uniform start's constant (-7.9%)
// would fail.
const double haff_constant_gaussian = 4.0 / std::sqrt(3.14159265358979323846);

TEST(PhysicsEvent, EarlyCoolingFromAGaussianStartFollowsHaffsLawWithItsConstant) {
    const double measured_a = measured_haff_constant(0.9995, 100.0, {PositionLaw::lattice, VelocityLaw::gaussian});
    EXPECT_NEAR(measured_a, haff_constant_gaussian, haff_relative_tolerance * haff_constant_gaussian);
}

}  // namespace
