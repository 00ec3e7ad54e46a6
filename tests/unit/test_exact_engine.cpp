// SPDX-License-Identifier: GPL-3.0-or-later
// The exact sticky-gas engine on cases solved by hand, on its symmetries, and
// on a 10^7-particle initial condition whose clusters are known exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <gtest/gtest.h>

#include "../test_support.hpp"

#include "shockgas/model/collision.hpp"
#include "shockgas/engines/engine.hpp"
#include "reference_event_engine.hpp"
#include "exact_engine.hpp"

namespace {

using shockgas::ClusterState;
using shockgas::CollisionModel;
using shockgas::ReferenceEventEngine;
using shockgas::ExactEngine;
using shockgas::InitialCondition;

constexpr double epsilon_machine = std::numeric_limits<double>::epsilon();
// Hand-solved positions and velocities below are dyadic numbers of order
// 1..10 that the engine computes in double-double and rounds once: 1 ulp of
// the largest magnitude bounds them.
constexpr double hand_solved_tolerance = 16.0 * epsilon_machine;

constexpr auto make = shockgas::testing::unit_masses;

ClusterState state_at(ExactEngine& engine, double t) {
    EXPECT_TRUE(engine.advance_to(t));
    ClusterState state;
    engine.clusters(state);
    return state;
}

TEST(ExactEngine, PairMergesAtItsContactTimeWithTheMergeRuleVelocity) {
    // x = (0, 1), v = (1/2, -1/2) on L = 4: contact at t = 1, x = 1/2. A pair
    // that touches exactly at t is merged (the event engine's convention).
    ExactEngine engine(make(4.0, {0.0, 1.0}, {0.5, -0.5}));
    EXPECT_EQ(engine.name(), "exact");
    auto before = state_at(engine, 1.0 - 0x1p-20);
    ASSERT_EQ(before.size(), 2u);
    EXPECT_EQ(engine.collisions(), 0u);
    auto at = state_at(engine, 1.0);
    ASSERT_EQ(at.size(), 1u);
    EXPECT_EQ(engine.collisions(), 1u);
    const auto merged = shockgas::merge(1.0, 0.5, 1.0, -0.5);
    EXPECT_EQ(at.mass[0], merged.mass);
    EXPECT_EQ(at.velocity[0], merged.velocity);
    EXPECT_NEAR(at.position[0], 0.5, hand_solved_tolerance);
    EXPECT_EQ(at.first_particle[0], 0);
}

TEST(ExactEngine, ClusterStraddlingTheSeamKeepsItsLeftmostParticle) {
    // L = 6, x = 0..5. Particles 4, 5, 0, 1 converge homologously on x = 6 = 0
    // (v = (6 - x)/4 for x = 4, 5, 6 = particle 0, 7 = particle 1) and meet at
    // t = 4; 2 and 3 rest. At t = 5: cluster {4, 5, 0, 1} of mass 4, velocity
    // (1/2 + 1/4 + 0 - 1/4)/4 = 1/8, at 0 + 1/8; it reaches x = 2 at t = 19.
    ExactEngine engine(make(6.0, {0, 1, 2, 3, 4, 5}, {0.0, -0.25, 0.0, 0.0, 0.5, 0.25}));
    const auto state = state_at(engine, 5.0);
    ASSERT_EQ(state.size(), 3u);
    EXPECT_EQ(state.first_particle, (std::vector<std::int64_t>{2, 3, 4}));
    EXPECT_EQ(state.mass, (std::vector<double>{1, 1, 4}));
    EXPECT_EQ(state.velocity[2], 0.125);
    EXPECT_NEAR(state.position[2], 0.125, hand_solved_tolerance);
    EXPECT_EQ(engine.collisions(), 3u);
}

TEST(ExactEngine, LoneClusterStartsAfterTheGapThatNeverClosed) {
    // L = 3, x = (0, 1, 2). Particles 0 and 1 merge at t = 1 at x = 1/2 with
    // v = 0. Particle 2 then closes either the seam gap (v2 = +1/2: it meets
    // the cluster at x = 3.5 at t = 3, so 2 is the left member and the lone
    // cluster's first particle) or the inner gap (v2 = -1/2, first particle 0).
    // The ring's state alone does not tell the two apart; the contact point
    // of the centre-of-mass construction does. Checked both when the engine
    // passes through t = 2 and when it jumps from 0 to t = 4 in one step.
    for (const double v2 : {0.5, -0.5}) {
        const std::int64_t expected_first = v2 > 0 ? 2 : 0;
        const auto initial = make(3.0, {0.0, 1.0, 2.0}, {0.5, -0.5, v2});
        ReferenceEventEngine event(initial, CollisionModel{0.0, 0.0, shockgas::Subthreshold::elastic}, {});
        ASSERT_TRUE(event.advance_to(4.0));
        ClusterState reference;
        event.clusters(reference);
        ASSERT_EQ(reference.first_particle, std::vector<std::int64_t>{expected_first});

        ExactEngine stepped(initial);
        EXPECT_EQ(state_at(stepped, 2.0).size(), 2u);
        ExactEngine jumped(initial);
        for (ExactEngine* engine : {&stepped, &jumped}) {
            const auto state = state_at(*engine, 4.0);
            ASSERT_EQ(state.size(), 1u) << "v2 = " << v2;
            EXPECT_EQ(state.first_particle[0], expected_first) << "v2 = " << v2;
            EXPECT_EQ(state.mass[0], 3.0);
            EXPECT_NEAR(state.velocity[0], v2 / 3.0, hand_solved_tolerance);
            EXPECT_NEAR(state.position[0], reference.position[0], hand_solved_tolerance);
            EXPECT_EQ(engine->collisions(), 2u);
        }
    }
}

TEST(ExactEngine, TouchingClustersWithEqualVelocitiesStaySeparate) {
    // Two particles at the same point moving together never collide in the
    // event engine (closing speed 0), so they are two clusters here too.
    ExactEngine engine(make(2.0, {0.5, 0.5}, {0.25, 0.25}));
    EXPECT_EQ(state_at(engine, 3.0).size(), 2u);
}

// Adding a velocity U to every particle (a drifting centre of mass) shifts
// each cluster by U t and its velocity by U and changes nothing else
// (Galilean invariance). U = 3/8 and t = 2^k keep v + U and U t exact.
TEST(ExactEngine, DriftingCentreOfMassShiftsClustersWithoutChangingThem) {
    const double drift = 0.375;
    const auto rest = shockgas::generate_initial_condition(2000, 2000.0, 11, 0);
    auto moving = rest;
    for (double& v : moving.velocity) v += drift;
    ExactEngine at_rest(rest), drifting(moving);
    for (double t = 1.0; t <= 0x1p24; t *= 4.0) {
        const auto a = state_at(at_rest, t);
        const auto b = state_at(drifting, t);
        ASSERT_EQ(a.first_particle, b.first_particle) << "t = " << t;
        ASSERT_EQ(a.mass, b.mass) << "t = " << t;
        for (std::size_t k = 0; k < a.size(); ++k) {
            // One rounding of each velocity (<= 1 ulp of 1.375).
            EXPECT_NEAR(b.velocity[k], a.velocity[k] + drift, 2.0 * epsilon_machine);
            // Positions: one rounding each, of numbers <= L (and U t is exact).
            const double shifted = shockgas::wrap_position(a.position[k] + std::fmod(drift * t, 2000.0), 2000.0);
            const double difference = std::abs(b.position[k] - shifted);
            EXPECT_LE(std::min(difference, 2000.0 - difference), 4.0 * 2000.0 * epsilon_machine) << "t = " << t;
        }
    }
    EXPECT_EQ(drifting.cluster_count(), 1);
}

// Clusters never split, so advancing through many times (PAV restarted from
// the clusters of the previous time) must give exactly the clusters of a
// fresh engine sent straight to each time (PAV from the particles).
TEST(ExactEngine, AdvancingInStepsEqualsOneJump) {
    const auto initial = shockgas::generate_initial_condition(5000, 5000.0, 3, 2);
    ExactEngine stepped(initial);
    for (double t = 0.5; t < 1e7; t *= 1.7) {
        const auto a = state_at(stepped, t);
        ExactEngine jumped(initial);
        const auto b = state_at(jumped, t);
        ASSERT_EQ(a.first_particle, b.first_particle) << "t = " << t;
        ASSERT_EQ(a.mass, b.mass) << "t = " << t;
        for (std::size_t k = 0; k < a.size(); ++k) {
            // Double-double sums in a different order: the one rounding to
            // double may differ by an ulp.
            EXPECT_NEAR(a.velocity[k], b.velocity[k], epsilon_machine);
            EXPECT_NEAR(a.position[k], b.position[k], 5000.0 * epsilon_machine);
        }
    }
    EXPECT_EQ(stepped.cluster_count(), 1);
}

// ---------------------------------------------------------------------------
// Precision at N = 10^7, t ~ 10^8. Groups of consecutive particles on the
// unit lattice (L = N) focus homologously onto their midpoint c:
//     v_i = U - (x_i - c) / T_g,   so   y_i(t) = c + U t + (x_i - c)(1 - t/T_g),
// and reach it all at once at t = T_g; neighbouring groups move apart, so no
// other collision ever happens. Before T_g a group is all singletons, after
// it one cluster of velocity U at c + U t. Focus times alternate between
// T_early = 2^26 and T_late = 2^27; U = 1/8 (nonzero total momentum, the
// clusters wrap the ring once or twice); group 0 straddles the seam. At
// t = T_late -+ 2^-3 neighbours in late groups are 2^-30 ~ 9e-10 apart or
// overlapping, at positions ~ 3 10^7 where a double's ulp is 3.7e-9: the
// contact is decided far below double resolution, and every number in the
// setup is dyadic, so the expected clusters, velocities and positions are
// exact.
class FocusingGroups {
public:
    static constexpr std::int64_t particles = 10'000'000;
    static constexpr double ring = static_cast<double>(particles);
    static constexpr double drift = 0.125;
    static constexpr double early = 0x1p26;
    static constexpr double late = 0x1p27;
    static constexpr std::int64_t seam_overlap = 7;  // group 0 starts at particle N - 7

    FocusingGroups() {
        // Group sizes 2..41 (group 0 has 22, so it straddles the seam); group
        // g covers unrolled indices [start_g, start_g + size_g) counted from
        // particle N - seam_overlap.
        std::int64_t start = particles - seam_overlap;
        for (std::int64_t g = 0; start < 2 * particles - seam_overlap; ++g) {
            const std::int64_t size = std::min<std::int64_t>(2 + (g * 13 + 20) % 40, 2 * particles - seam_overlap - start);
            group_start_.push_back(start);
            group_size_.push_back(size);
            start += size;
        }
    }

    InitialCondition initial() const {
        InitialCondition out;
        out.ring_length = ring;
        out.position.resize(static_cast<std::size_t>(particles));
        out.velocity.resize(static_cast<std::size_t>(particles));
        out.mass.assign(static_cast<std::size_t>(particles), 1.0);
        for (std::size_t g = 0; g < group_start_.size(); ++g)
            for (std::int64_t k = 0; k < group_size_[g]; ++k) {
                const std::int64_t unrolled = group_start_[g] + k;
                const auto i = static_cast<std::size_t>(unrolled % particles);
                out.position[i] = static_cast<double>(unrolled % particles);
                out.velocity[i] = velocity(g, unrolled);
            }
        return out;
    }

    std::size_t groups() const { return group_start_.size(); }
    std::int64_t start(std::size_t g) const { return group_start_[g]; }
    std::int64_t size(std::size_t g) const { return group_size_[g]; }
    double focus_time(std::size_t g) const { return g % 2 == 0 ? early : late; }
    // Midpoint of the group's unrolled positions (integer or half-integer).
    double centre(std::size_t g) const {
        return 0.5 * static_cast<double>(2 * group_start_[g] + group_size_[g] - 1);
    }
    double velocity(std::size_t g, std::int64_t unrolled) const {
        return drift - (static_cast<double>(unrolled) - centre(g)) / focus_time(g);
    }

private:
    std::vector<std::int64_t> group_start_, group_size_;
};

// The expected ring in the engine's order (by first particle), computed in
// long double (64-bit significand: x + t v needs at most 56 bits here, so it
// is exact) and rounded once. Generated in unrolled order from group 0, then
// rotated to start at particle 0.
ClusterState expected_state(const FocusingGroups& setup, double t) {
    static_assert(std::numeric_limits<long double>::digits >= 64, "exact expectations need x87 long double or wider");
    const auto wrap = [](long double x) {
        const long double ring = FocusingGroups::ring;
        return static_cast<double>(x - ring * std::floor(x / ring));
    };
    ClusterState out;
    out.time = t;
    const auto add = [&out](std::int64_t first, double mass, double velocity, double position) {
        out.first_particle.push_back(first % FocusingGroups::particles);
        out.mass.push_back(mass);
        out.velocity.push_back(velocity);
        out.position.push_back(position);
    };
    for (std::size_t g = 0; g < setup.groups(); ++g) {
        if (t > setup.focus_time(g)) {
            add(setup.start(g), static_cast<double>(setup.size(g)), FocusingGroups::drift,
                wrap(static_cast<long double>(setup.centre(g)) + static_cast<long double>(FocusingGroups::drift) * t));
        } else {
            for (std::int64_t k = 0; k < setup.size(g); ++k) {
                const std::int64_t unrolled = setup.start(g) + k;
                const double v = setup.velocity(g, unrolled);
                add(unrolled, 1.0, v, wrap(static_cast<long double>(unrolled) + static_cast<long double>(t) * v));
            }
        }
    }
    const auto zero = std::min_element(out.first_particle.begin(), out.first_particle.end()) - out.first_particle.begin();
    std::rotate(out.first_particle.begin(), out.first_particle.begin() + zero, out.first_particle.end());
    std::rotate(out.mass.begin(), out.mass.begin() + zero, out.mass.end());
    std::rotate(out.velocity.begin(), out.velocity.begin() + zero, out.velocity.end());
    std::rotate(out.position.begin(), out.position.begin() + zero, out.position.end());
    return out;
}

TEST(ExactEnginePrecision, FocusingGroupsAtTenMillionParticlesAndTimeOneHundredMillion) {
    const FocusingGroups setup;
    ExactEngine engine(setup.initial());
    const double just_before = FocusingGroups::late - 0x1p-3;  // late neighbours 2^-30 apart
    const double just_after = FocusingGroups::late + 0x1p-3;   // late neighbours 2^-30 overlapping
    for (const double t : {1e8, just_before, just_after}) {
        ClusterState state;
        ASSERT_TRUE(engine.advance_to(t));
        engine.clusters(state);
        const ClusterState expected = expected_state(setup, t);
        ASSERT_EQ(state.size(), expected.size()) << "t = " << t;
        ASSERT_EQ(state.first_particle, expected.first_particle) << "t = " << t;
        ASSERT_EQ(state.mass, expected.mass) << "t = " << t;
        EXPECT_EQ(state.velocity, expected.velocity) << "t = " << t;
        EXPECT_EQ(state.position, expected.position) << "t = " << t;
    }
    EXPECT_EQ(engine.cluster_count(), static_cast<std::int64_t>(setup.groups()));

    // The test discriminates: in plain double the separation of two late
    // neighbours at t = just_before, (x + t v)_{i+1} - (x + t v)_i, is lost.
    const std::size_t late_group = 1;
    const std::int64_t i = setup.start(late_group);
    const double y_left = static_cast<double>(i) + just_before * setup.velocity(late_group, i);
    const double y_right = static_cast<double>(i + 1) + just_before * setup.velocity(late_group, i + 1);
    EXPECT_NE(y_right - y_left, 0x1p-30);
}

}  // namespace
