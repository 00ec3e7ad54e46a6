// SPDX-License-Identifier: GPL-3.0-or-later
// The collision rule: the one place where velocities change.
//
// A pair (left, right) collides when left's velocity exceeds right's. What
// happens depends on the relative speed g = v_left - v_right > 0:
//   r = 0                      -> merge (the sticky gas: ballistic aggregation)
//   g <  delta, elastic        -> restitution 1
//   g <  delta, sticky         -> merge
//   otherwise                  -> restitution r
#pragma once

#include "shockgas/model/parameters.hpp"

namespace shockgas {

enum class CollisionKind { inelastic, elastic, merge };

inline CollisionKind classify(const CollisionModel& model, double relative_speed) {
    if (model.restitution == 0.0) return CollisionKind::merge;
    if (relative_speed < model.velocity_threshold)
        return model.subthreshold == Subthreshold::sticky ? CollisionKind::merge : CollisionKind::elastic;
    return CollisionKind::inelastic;
}

struct PostCollision {
    double left_velocity;
    double right_velocity;
};

// Two-body collision with restitution r for masses m1 (left), m2 (right):
//   v1' = v1 - (1 + r) m2/(m1 + m2) g,   v2' = v2 + (1 + r) m1/(m1 + m2) g,
// g = v1 - v2. For unit masses this is the paper's Eq. (1), v -> v - eps (v - u),
// in the exchanged-identity frame, with r = 1 - 2 eps. It conserves momentum and
// removes (1 - r^2) m1 m2 / (2 (m1 + m2)) g^2 of kinetic energy, i.e. eps (1 - eps) g^2
// for a unit-mass pair. For equal masses m2/(m1 + m2) is exactly 1/2, so the
// equal-mass case is computed with the same arithmetic as the general one.
inline PostCollision collide(double m1, double v1, double m2, double v2, double restitution) {
    const double g = v1 - v2;
    const double total = m1 + m2;
    const double kick = (1.0 + restitution) * g;
    return {v1 - kick * (m2 / total), v2 + kick * (m1 / total)};
}

// Perfectly inelastic merger: mass and momentum conserved,
//   M = m1 + m2,  V = (m1 v1 + m2 v2) / M.
struct MergedCluster {
    double mass;
    double velocity;
};

inline MergedCluster merge(double m1, double v1, double m2, double v2) {
    const double total = m1 + m2;
    return {total, (m1 * v1 + m2 * v2) / total};
}

}  // namespace shockgas
