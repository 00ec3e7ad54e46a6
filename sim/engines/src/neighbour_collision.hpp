// SPDX-License-Identifier: GPL-3.0-or-later
// The collision of neighbouring clusters i and next(i) at time t, written once
// for the two event engines: ReferenceEventEngine (the global-order reference loop) and
// EventEngine (its windowed twin, bit-identical to it). Both call this after
// their own bookkeeping (collapse and stall detection in the reference loop,
// the per-block stall bound in the windowed one), so the statements that change
// gaps, velocities, masses and links are the same statements in both, and the
// results stay bit-identical by construction.
//
// The engine provides, as members this function may call (it is a friend):
//   records()                         the per-slot records (velocity, gap, clock, mass, next, prev)
//   gap_at(slot, t), move_anchor_clock(slot, t)
//   reschedule(slot), reschedule_collided(i, left, right) (left/right -1: a cut), unschedule(slot)
//   left_is_cut(i), right_is_cut(j)   the event engine's block ends; false in the reference loop
//   log_left(t, i, v), log_right(t, i, end, v, contact_gap), became_block_end(i)
//                                     the event engine's boundary logs; no-ops in the reference loop
//   collisions_, alive_, anchor_, anchor_position_, ring_length_
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "shockgas/model/collision.hpp"
#include "shockgas/engines/engine.hpp"

namespace shockgas {

// The clusters in contact around a colliding pair (detail::contact_cluster):
// how many, and their mass. Three or more make a collapse (McNamara & Young 1992).
struct ContactCluster {
    std::int64_t members = 0;
    double mass = 0.0;
};

}  // namespace shockgas

namespace shockgas::detail {


// Two clusters count as one collapsing cluster when their gap at the moment
// of collapse is below this fraction of the mean spacing L/N. In a collapse
// the gaps shrink geometrically to zero, far below this; between ordinary
// neighbours they are of order the spacing (see ARCHITECTURE.md, "Collapse").
inline constexpr double collapse_contact_fraction = 1e-6;

// The run of clusters in contact (gap below collapse_contact_fraction L/N)
// around the pair (i, next i) at time t, for both event engines. The engine
// provides records() (next, prev, mass), gap_at(slot, t), alive_,
// ring_length_ and particles_.
template <class Engine>
ContactCluster contact_cluster(const Engine& engine, std::int32_t i, double t) {
    const auto& records = engine.records();
    const double contact = collapse_contact_fraction * engine.ring_length_ / static_cast<double>(engine.particles_);
    double mass = records[static_cast<std::size_t>(i)].mass;
    std::int64_t members = 1;
    for (std::int32_t s = i; members < engine.alive_ && engine.gap_at(s, t) <= contact; ++members) {
        s = records[static_cast<std::size_t>(s)].next;
        mass += records[static_cast<std::size_t>(s)].mass;
    }
    for (std::int32_t s = records[static_cast<std::size_t>(i)].prev;
         members < engine.alive_ && engine.gap_at(s, t) <= contact; ++members) {
        mass += records[static_cast<std::size_t>(s)].mass;
        s = records[static_cast<std::size_t>(s)].prev;
    }
    return {members, mass};
}

// A slow inelastic collision (relative speed below --collapse-speed) is a
// candidate collapse; it is one when three or more clusters are in contact.
// Two alone separate after each collision (McNamara & Young 1992): a slow pair
// with no third cluster in contact is a cooled gas, not a collapse (a ring of
// N = 2 ... 8 at delta = 0 reaches g < 1e-12 by Haff cooling alone near
// t ~ 1e12 and would be reported collapsed there; every collapse the figures record
// has 10 or more).
inline bool collapse_candidate(const CollapseCriterion& criterion, CollisionKind kind, double relative_speed) {
    return kind == CollisionKind::inelastic && relative_speed < criterion.collapse_speed;
}
inline constexpr std::int64_t collapse_min_members = 3;

// Whether the model forbids inelastic collapse (infinitely many collisions
// in finite time): with delta > 0 every inelastic collision removes at least
// eps (1 - eps) delta^2 of a finite energy, so there are finitely many, and
// between them the elastic ones are crossings of straight world lines, finitely
// many in finite time; with r = 0 every collision merges two clusters. A
// stall there is a numerical failure, never a collapse.
inline bool collapse_forbidden(const CollisionModel& model) {
    return model.restitution == 0.0 || model.velocity_threshold > 0.0;
}

// The one line a numerical stall throws (NumericalFailure): `events`
// collisions from t = since to t advanced time by less than the stall span
// where the model forbids collapse; relative_speed is the last one's.
inline std::string stall_message(const CollisionModel& model, const CollapseCriterion& criterion,
                                 std::uint64_t events, double since, double t, double relative_speed) {
    return fmt::format(
        "numerical failure: {} collisions between t = {:.17g} and t = {:.17g} advanced time by less than {:.3g} "
        "max(L/N, t): collisions crowd at one instant beyond what double precision resolves (the last at relative "
        "speed {:.3g}). With {} the model forbids collapse, so this is no physical event and the run cannot go on. "
        "Change: a larger delta or r, so that relative speeds within a cluster (down to r delta = {:.3g}) stay far "
        "above the rounding of velocities and positions, or a t_max before t = {:.6g}",
        events, since, t, criterion.stall_time_fraction, relative_speed,
        model.restitution == 0.0 ? std::string("r = 0") : fmt::format("delta = {:.3g} > 0", model.velocity_threshold),
        model.restitution * model.velocity_threshold, since);
}

// The report of a collapse found at pair (i, next i) at time t.
inline CollapseReport collapse_report(std::int32_t i, double relative_speed, double t, const char* criterion,
                                      const ContactCluster& cluster) {
    return CollapseReport{t, i, static_cast<std::int64_t>(std::llround(cluster.mass)), relative_speed, criterion};
}

template <class Engine>
void collide_neighbours(Engine& engine, std::int32_t i, double t, CollisionKind kind) {
    auto& records = engine.records();
    auto& a = records[static_cast<std::size_t>(i)];
    const std::int32_t j = a.next;
    const std::int32_t p = a.prev;
    auto& b = records[static_cast<std::size_t>(j)];
    const bool left_is_cut = engine.left_is_cut(i);   // pair (p, i) belongs to no block
    const bool right_is_cut = engine.right_is_cut(j);  // pair (j, next j) belongs to no block

    // Bring the two neighbouring gaps to time t before the velocities change.
    // On a ring of two clusters the left gap of i is the right gap of j.
    if (!left_is_cut) records[static_cast<std::size_t>(p)].gap = engine.gap_at(p, t);
    if (j != p && !right_is_cut) b.gap = engine.gap_at(j, t);
    // The pair is in contact at t, up to the rounding of t itself: keep the
    // gap the arithmetic leaves, |g| ~ c ulp(t), rather than setting it to 0.
    // Zeroing dropped that residual at every collision, so the gaps summed to
    // L only up to a random walk of them (-7e-6 L after 1e9 collisions at
    // N = 1000; docs/testing-and-drift.md, "Long-run drift"); kept, they sum
    // to L up to the rounding of the gap updates.
    const double contact_gap = engine.gap_at(i, t);
    a.gap = contact_gap;
    engine.move_anchor_clock(i, t);
    engine.move_anchor_clock(j, t);
    ++engine.collisions_;

    if (kind == CollisionKind::merge) {
        const MergedCluster merged = merge(a.mass, a.velocity, b.mass, b.velocity);
        a.velocity = merged.velocity;
        a.mass = merged.mass;
        a.clock = t;
        a.gap = contact_gap + b.gap;  // the merged cluster sits where i was
        const std::int32_t k = b.next;
        a.next = k;
        if (right_is_cut) {
            // i is now the left end of the cut; k's prev is set by the cut's
            // replay, which adds the contact gap to the cut's gap as above.
            engine.became_block_end(i);
            engine.log_right(t, i, i, a.velocity, contact_gap);
        } else {
            records[static_cast<std::size_t>(k)].prev = i;
        }
        if (left_is_cut) engine.log_left(t, i, a.velocity);
        engine.unschedule(j);
        --engine.alive_;
        if (engine.anchor_ == j) {
            engine.anchor_ = i;
            engine.anchor_position_ -= contact_gap;  // i's position: j's, moved to t above, less the contact gap
        }
        if (engine.alive_ == 1) {
            a.next = a.prev = i;
            a.gap = engine.ring_length_;
            engine.unschedule(i);
            return;
        }
        if (!left_is_cut) engine.reschedule(p);
        if (right_is_cut)
            engine.unschedule(i);  // (i, k) is now the cut pair: its key comes from the replay
        else
            engine.reschedule(i);
        return;
    }

    const double restitution = kind == CollisionKind::elastic ? 1.0 : engine.model_.restitution;
    const PostCollision after = collide(a.mass, a.velocity, b.mass, b.velocity, restitution);
    a.velocity = after.left_velocity;
    b.velocity = after.right_velocity;
    a.clock = t;
    b.clock = t;
    if (left_is_cut) engine.log_left(t, i, a.velocity);
    if (right_is_cut) engine.log_right(t, i, j, b.velocity, 0.0);
    // The pair (i, j) and its neighbours (p, i), (j, next j), except those
    // that are cuts. The order of the updates does not matter: queues order
    // by (time, slot), which is unique.
    engine.reschedule_collided(i, left_is_cut ? -1 : p, right_is_cut ? -1 : j);
}

}  // namespace shockgas::detail
