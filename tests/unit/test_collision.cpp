// SPDX-License-Identifier: GPL-3.0-or-later
// The collision rule (sim/model/include/shockgas/model/collision.hpp), Eq. (1) of the paper.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "shockgas/model/collision.hpp"

namespace {

using shockgas::classify;
using shockgas::collide;
using shockgas::CollisionKind;
using shockgas::merge;

constexpr double epsilon_machine = std::numeric_limits<double>::epsilon();
// Momentum: each post-collision velocity is rounded once (plus one rounding
// of the kick), so the pair's momentum moves by at most a few ulp of the
// largest |m v| involved: 4 ulp is the bound for the three roundings.
constexpr double momentum_ulps = 4.0;
// Energy: the loss eps (1 - eps) g^2 is computed as a difference of kinetic
// energies of size ~v^2, so its relative error is ~ulp(v^2) / loss; with
// |v| <= 1 and g >= 0.01, eps >= 1e-3 that is below 1e-9.
constexpr double energy_loss_relative_tolerance = 1e-9;

TEST(Collision, Eq1ForUnitMasses) {
    // Eq. (1), v -> v - eps (v - u), in the exchanged-identity frame: the
    // particle arriving from the left with velocity v continues as the right
    // member of the pair, so the right member ends with v - eps (v - u) and
    // the left one with u - eps (u - v).
    const double r = 0.9, eps = (1 - r) / 2, v = 0.7, u = -0.4;
    const auto after = collide(1.0, v, 1.0, u, r);
    EXPECT_NEAR(after.right_velocity, v - eps * (v - u), 4 * epsilon_machine);
    EXPECT_NEAR(after.left_velocity, u - eps * (u - v), 4 * epsilon_machine);
}

TEST(Collision, ConservesMomentumAndRemovesEpsOneMinusEpsGSquared) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> velocity(-1.0, 1.0), restitution(0.0, 1.0);
    for (int trial = 0; trial < 100000; ++trial) {
        double v1 = velocity(rng), v2 = velocity(rng);
        if (v1 < v2) std::swap(v1, v2);
        const double g = v1 - v2;
        if (g < 0.01) continue;
        const double r = restitution(rng), eps = (1 - r) / 2;
        if (eps < 1e-3) continue;
        const auto after = collide(1.0, v1, 1.0, v2, r);
        const double scale = std::max(std::abs(v1), std::abs(v2));
        ASSERT_LE(std::abs((after.left_velocity + after.right_velocity) - (v1 + v2)),
                  momentum_ulps * epsilon_machine * scale);
        const double loss = 0.5 * (v1 * v1 + v2 * v2) -
                            0.5 * (after.left_velocity * after.left_velocity + after.right_velocity * after.right_velocity);
        ASSERT_NEAR(loss, eps * (1 - eps) * g * g, energy_loss_relative_tolerance * eps * (1 - eps) * g * g);
        // The pair separates afterwards, with relative speed r g.
        ASSERT_NEAR(after.right_velocity - after.left_velocity, r * g, 4 * epsilon_machine * scale);
    }
}

TEST(Collision, ElasticConservesEnergy) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> velocity(-1.0, 1.0), mass(0.1, 10.0);
    for (int trial = 0; trial < 10000; ++trial) {
        const double m1 = mass(rng), m2 = mass(rng), v1 = velocity(rng), v2 = velocity(rng);
        const auto after = collide(m1, v1, m2, v2, 1.0);
        const double before_energy = m1 * v1 * v1 + m2 * v2 * v2;
        const double after_energy = m1 * after.left_velocity * after.left_velocity +
                                    m2 * after.right_velocity * after.right_velocity;
        // Masses up to 100x apart amplify the velocity rounding by m/M: 1e-13.
        ASSERT_NEAR(after_energy, before_energy, 1e-13 * before_energy);
    }
}

TEST(Collision, UnequalMassesTwoBodyRule) {
    // m1 = 3, m2 = 1, v1 = 1, v2 = 0, r = 0.5: J = (1 + r) mu g = 1.5 * 0.75 = 1.125.
    const auto after = collide(3.0, 1.0, 1.0, 0.0, 0.5);
    EXPECT_DOUBLE_EQ(after.left_velocity, 1.0 - 1.125 / 3.0);
    EXPECT_DOUBLE_EQ(after.right_velocity, 1.125);
    EXPECT_NEAR(3.0 * after.left_velocity + after.right_velocity, 3.0, 4 * epsilon_machine * 3.0);
}

TEST(Collision, MergeConservesMassAndMomentum) {
    const auto merged = merge(3.0, 0.5, 5.0, -0.2);
    EXPECT_EQ(merged.mass, 8.0);
    EXPECT_NEAR(merged.mass * merged.velocity, 3.0 * 0.5 + 5.0 * -0.2, 2 * epsilon_machine);
}

TEST(Collision, ClassifiesThePaperMechanisms) {
    shockgas::CollisionModel model{0.9, 1e-2, shockgas::Subthreshold::elastic};
    EXPECT_EQ(classify(model, 0.5), CollisionKind::inelastic);
    EXPECT_EQ(classify(model, 1e-2), CollisionKind::inelastic);  // threshold is "g < delta"
    EXPECT_EQ(classify(model, 0.999e-2), CollisionKind::elastic);
    model.subthreshold = shockgas::Subthreshold::sticky;
    EXPECT_EQ(classify(model, 0.999e-2), CollisionKind::merge);
    model.restitution = 0.0;  // the sticky gas merges whatever the speed
    EXPECT_EQ(classify(model, 0.5), CollisionKind::merge);
    model = {0.5, 0.0, shockgas::Subthreshold::elastic};  // pure inelastic gas
    EXPECT_EQ(classify(model, 1e-300), CollisionKind::inelastic);
}

}  // namespace
