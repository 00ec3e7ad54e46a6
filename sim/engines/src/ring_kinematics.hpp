// SPDX-License-Identifier: GPL-3.0-or-later
// The kinematics every event engine shares, written once so that the
// reference loop and the event engine do the same arithmetic (their
// results are compared bit for bit): the gap between neighbours at a later
// time, the contact time of an approaching pair, and the walk around the ring
// that turns gaps into positions. See ARCHITECTURE.md, "Gaps, not positions".
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "shockgas/model/state.hpp"

namespace shockgas {

// gap(t) = gap(tau) + (v_right - v_left)(t - tau), tau = max(clock_left, clock_right):
// the gap was last updated when either end last changed velocity.
inline double gap_at_time(double gap, double left_velocity, double right_velocity, double left_clock,
                          double right_clock, double t) {
    return gap + (right_velocity - left_velocity) * (t - std::max(left_clock, right_clock));
}

// An approaching pair (closing_speed = v_left - v_right > 0) meets at
// tau + gap / closing_speed; a pair whose gap is already <= 0, or a time that
// rounding put before `now` (or NaN), collides now.
inline double contact_time(double gap, double closing_speed, double left_clock, double right_clock, double now) {
    const double t = std::max(left_clock, right_clock) + gap / closing_speed;
    return t >= now ? t : now;
}

// The ring records of a start, for both event engines (same arithmetic, so
// their results can be compared bit for bit): each particle a cluster of its
// own with its velocity relative to the frame (frame_velocity, state.hpp) and
// mass, clock 0, the gap to its right neighbour (the last one's across the
// seam), linked in ring order. Records are any per-slot struct with velocity,
// gap, clock, mass, next and prev; other fields are left as they are.
template <class Record>
void link_ring(const InitialCondition& initial, double frame_velocity, std::vector<Record>& records) {
    const auto n = static_cast<std::int32_t>(initial.size());
    records.resize(static_cast<std::size_t>(n));
    for (std::int32_t i = 0; i < n; ++i) {
        const auto s = static_cast<std::size_t>(i);
        const double right = (i + 1 < n) ? initial.position[s + 1] : initial.position[0] + initial.ring_length;
        Record& r = records[s];
        r.velocity = initial.velocity[s] - frame_velocity;
        r.gap = right - initial.position[s];
        r.clock = 0.0;
        r.mass = initial.mass[s];
        r.next = (i + 1) % n;
        r.prev = (i + n - 1) % n;
    }
}

// Positions from gaps: the anchor's absolute position moved to `now`, then the
// gaps summed around the ring, in walk order from the anchor (unwrapped, so
// non-decreasing up to contact rounding). `first` is the walk index of the
// smallest live slot. Shared by walk_ring (output) and the hand-over of a
// mid-run state to another engine (EventEngine::mid_run_state), so both
// read the same positions bit for bit.
template <class Record, class GapAt>
std::size_t walk_positions(const std::vector<Record>& records, std::int32_t anchor, double anchor_position,
                           double now, std::int64_t alive, GapAt gap_at, std::vector<double>& walk_position,
                           std::vector<std::int32_t>& walk_slot) {
    const auto count = static_cast<std::size_t>(alive);
    walk_position.resize(count);
    walk_slot.resize(count);
    const Record& anchor_record = records[static_cast<std::size_t>(anchor)];
    double x = anchor_position + anchor_record.velocity * (now - anchor_record.clock);
    std::int32_t s = anchor;
    std::size_t first = 0;
    for (std::size_t k = 0; k < count; ++k) {
        walk_position[k] = x;
        walk_slot[k] = s;
        if (s < walk_slot[first]) first = k;
        x += gap_at(s, now);
        s = records[static_cast<std::size_t>(s)].next;
    }
    return first;
}

// Output in ring order from the smallest slot, positions wrapped into [0, L)
// and moved from the frame (velocity frame_velocity) into the lab; velocities
// relative to the frame (ClusterState). Records are any per-slot struct with
// velocity, clock, mass and next; gap_at(slot, t) gives the gap after slot.
template <class Record, class GapAt>
void walk_ring(const std::vector<Record>& records, std::int32_t anchor, double anchor_position, double now,
               std::int64_t alive, double ring_length, double frame_velocity, GapAt gap_at, ClusterState& out) {
    out.clear();
    out.time = now;
    out.frame_velocity = frame_velocity;
    const auto count = static_cast<std::size_t>(alive);
    std::vector<double> walk_position;
    std::vector<std::int32_t> walk_slot;
    const std::size_t first =
        walk_positions(records, anchor, anchor_position, now, alive, gap_at, walk_position, walk_slot);
    out.position.reserve(count);
    out.velocity.reserve(count);
    out.mass.reserve(count);
    out.first_particle.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t w = (first + k) % count;
        const Record& c = records[static_cast<std::size_t>(walk_slot[w])];
        out.position.push_back(wrap_position(walk_position[w], ring_length));
        out.velocity.push_back(c.velocity);
        out.mass.push_back(c.mass);
        out.first_particle.push_back(walk_slot[w]);
    }
    frame_to_lab_positions(out, ring_length);
}

}  // namespace shockgas
