// SPDX-License-Identifier: GPL-3.0-or-later
// The event-driven ring engine.
//
// State per cluster (one slot per original particle; a slot dies when its
// cluster merges into its left neighbour):
//   velocity, mass, clock (time of its last velocity change: per-particle
//   clocks, i.e. delayed states), and gap, the distance to the next live
//   cluster, valid at time max(clock[i], clock[next]).
// Positions are never stored as absolute coordinates of size L, which would
// lose digits at large L and t; only gaps are stored, each updated from local
// quantities when one of its two ends changes velocity (see ARCHITECTURE.md).
// One cluster (the anchor) also carries an absolute position, used only to
// place the ring for output.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "shockgas/model/collision.hpp"
#include "shockgas/engines/engine.hpp"
#include "event_queue.hpp"

namespace shockgas {

struct ContactCluster;  // neighbour_collision.hpp

namespace detail {
template <class Engine>
void collide_neighbours(Engine& engine, std::int32_t i, double t, CollisionKind kind);
template <class Engine>
ContactCluster contact_cluster(const Engine& engine, std::int32_t i, double t);
}  // namespace detail

class ReferenceEventEngine final : public Engine {
public:
    ReferenceEventEngine(const InitialCondition& initial, const CollisionModel& model, const CollapseCriterion& collapse,
                LiveStatus* live = nullptr);

    bool advance_to(double t) override;
    double time() const override { return now_; }
    void clusters(ClusterState& out) const override;
    std::uint64_t collisions() const override { return collisions_; }
    std::int64_t cluster_count() const override { return alive_; }
    const std::optional<CollapseReport>& collapse() const override { return collapse_; }
    std::string name() const override { return "event"; }
    std::optional<EngineSnapshot> snapshot() const override;
    void restore(const EngineSnapshot& snapshot) override;
    static constexpr const char* snapshot_kind = "event";

    // Processes exactly one event if one is due at or before t_limit.
    // Exposed for tests that step through hand-solved cases.
    bool step(double t_limit);
    double next_event_time() const { return queue_.top_time(); }
    // Gaps between neighbouring clusters at the current time, in ring order
    // from the anchor. They sum to L and are never negative beyond rounding:
    // the invariants tests check.
    std::vector<double> gaps() const;
    // Memory the engine holds per particle: the cluster record plus the
    // queue's time, heap and heap-position entries.
    static constexpr std::size_t bytes_per_particle() {
        return sizeof(Cluster) + sizeof(double) + 2 * sizeof(std::int32_t);
    }

private:
    struct Cluster {
        double velocity;
        double gap;
        double clock;
        double mass;
        std::int32_t next;
        std::int32_t prev;
    };

    double gap_at(std::int32_t slot, double t) const;
    void reschedule(std::int32_t slot);
    void collide_pair(std::int32_t left, double t);

    // What detail::collide_neighbours (the collision step both event engines
    // share) needs: the global loop has no blocks, hence no cuts and no logs.
    template <class Engine>
    friend void detail::collide_neighbours(Engine& engine, std::int32_t i, double t, CollisionKind kind);
    std::vector<Cluster>& records() { return cluster_; }
    static constexpr bool left_is_cut(std::int32_t) { return false; }
    static constexpr bool right_is_cut(std::int32_t) { return false; }
    void unschedule(std::int32_t slot) { queue_.remove(slot); }
    void reschedule_collided(std::int32_t slot, std::int32_t left, std::int32_t right) {
        reschedule(slot);
        reschedule(left);  // never a cut (-1) here: the global loop has none
        reschedule(right);
    }
    static void log_left(double, std::int32_t, double) {}
    static void log_right(double, std::int32_t, std::int32_t, double, double) {}
    static void became_block_end(std::int32_t) {}
    // detail::contact_cluster (shared with the event engine) reads these.
    template <class Engine>
    friend ContactCluster detail::contact_cluster(const Engine& engine, std::int32_t i, double t);
    const std::vector<Cluster>& records() const { return cluster_; }
    void detect_collapse(std::int32_t left, double relative_speed, double t, const char* criterion,
                         const ContactCluster& cluster);
    // Where the model forbids collapse a stall is a numerical failure: throws
    // NumericalFailure naming it and what to change.
    [[noreturn]] void numerical_stall(double t, double relative_speed) const;
    void move_anchor_clock(std::int32_t slot, double t);

    std::vector<Cluster> cluster_;
    EventQueue queue_;
    CollisionModel model_;
    CollapseCriterion criterion_;
    LiveStatus* live_;
    double ring_length_;
    double time_unit_;       // L/N: the stall criterion's floor (CollapseCriterion)
    double frame_velocity_;  // velocities are relative to it (frame_velocity, state.hpp)
    double now_ = 0.0;
    std::int64_t particles_;
    std::int64_t alive_;
    std::uint64_t collisions_ = 0;
    std::int32_t anchor_ = 0;
    double anchor_position_ = 0.0;  // absolute position of the anchor at its clock
    std::optional<CollapseReport> collapse_;
    // Stall detection: events since time last advanced noticeably.
    double stall_reference_time_ = 0.0;
    std::uint64_t stall_events_ = 0;
    std::uint64_t stall_window_;
};

}  // namespace shockgas
