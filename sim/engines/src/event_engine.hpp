// SPDX-License-Identifier: GPL-3.0-or-later
// The event engine (EventEngine, `--engine event`): exact time windows
// (ARCHITECTURE.md, "The event engines" and "The event engine's windows"; its
// speed: docs/engines.md).
//
// It produces BIT-IDENTICAL results to ReferenceEventEngine, the global-order reference
// loop, for the runs it supports (EventEngine::supports), and is chosen by
// make_engine only for those. Why it is faster: the reference takes events in
// global time order, so successive events land at random places on the ring
// and each touches cold memory. Here time advances in windows [T, T + W]. In
// 1D a pair can collide within the window only if its gap at T is at most
// W (|v|max left + |v|max right); the ring is cut at pairs whose gap exceeds
// 2 W |v|max (with a safety factor), and the blocks between cuts cannot
// interact within the window. Each block runs its own events to T + W with its
// own small heap while its particles sit in cache.
//
// Why the result is identical to the global loop:
//  * Inside a block the events are the global loop's events restricted to the
//    block, taken in the same (time, slot) order with the same arithmetic (the
//    same collision.hpp functions, the same gap and key formulas).
//  * A cut pair's gap and key depend on both blocks. The blocks never touch
//    them; each logs its boundary cluster's velocity changes (time, event slot,
//    new velocity, new end slot after a merge), and after both blocks ran the
//    logs are merged in global (time, slot) order and the gap and key updates
//    are replayed exactly as the global loop made them.
//  * Every key computed for a cut pair during the replay, and its key at the
//    cut, is checked to lie beyond T + W: then the global loop never took that
//    pair's event in the window. A violation (impossible with the safety
//    factor, short of a bug) throws instead of returning a wrong result.
//  * The bound needs |v|max never to grow. It holds when every collision forms
//    convex combinations of velocities: equal-mass collisions with r in [0, 1]
//    and merges. supports() refuses the rest (sticky sub-threshold with r > 0,
//    where a light cluster can rebound faster than either velocity, and
//    unequal masses with r > 0).
//  * Collapse detection is global: delta = 0 (r > 0) stops at the first slow
//    inelastic collision with three clusters in contact in global time order,
//    and the run then reports the whole ring at that instant. Blocks cannot
//    give that ring (the others have run on), so a window whose blocks meet a
//    slow inelastic collision (detail::collapse_candidate) is abandoned, the
//    engine goes back to a copy of the state taken at most rewind_period
//    windows earlier, runs the windows up to that one again (they are
//    deterministic, so they come out the same) and runs that one window as a
//    single block of the whole ring, which is the global loop itself; there
//    the candidate is judged as ReferenceEventEngine judges it. The copy is taken only
//    when collapse is possible (delta below --collapse-speed).
//    The stall detector (max(10^6, 10 N) consecutive events within
//    10^-12 max(L/N, t))
//    is bounded per window instead: each block counts its own densest run, and
//    if the bound cannot exclude a stall the engine throws rather than guess
//    (StallUndecidable; run_ensemble then reruns the realization with
//    ReferenceEventEngine).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "shockgas/model/collision.hpp"
#include "shockgas/engines/engine.hpp"
#include "quaternary_heap.hpp"

namespace shockgas {

struct ContactCluster;  // neighbour_collision.hpp

namespace detail {
template <class Engine>
void collide_neighbours(Engine& engine, std::int32_t i, double t, CollisionKind kind);
template <class Engine>
ContactCluster contact_cluster(const Engine& engine, std::int32_t i, double t);
}  // namespace detail

// Thrown by EventEngine::advance_to when its per-window bound cannot rule
// out the global stall detector firing: events crowd at one instant, as in an
// inelastic collapse regularized only by a tiny delta (seen at r = 1e-6,
// delta = 1e-12). Only the global loop can locate that stall, so the run must
// be redone with ReferenceEventEngine (make_fallback_engine names it).
struct StallUndecidable : EngineUndecided {
    using EngineUndecided::EngineUndecided;
};

class EventEngine final : public Engine {
public:
    EventEngine(const InitialCondition& initial, const CollisionModel& model, const CollapseCriterion& collapse,
                    LiveStatus* live = nullptr);

    // True when the window scheme reproduces ReferenceEventEngine exactly for this run:
    // |v|max cannot grow (r = 0; or equal masses with elastic sub-threshold
    // collisions or delta = 0, where there are none). Collapse detection
    // (delta below the collapse speed) is exact by the rewind described above.
    static bool supports(const InitialCondition& initial, const CollisionModel& model,
                         const CollapseCriterion& collapse);

    bool advance_to(double t) override;
    double time() const override { return now_; }
    void clusters(ClusterState& out) const override;
    std::uint64_t collisions() const override { return collisions_; }
    std::int64_t cluster_count() const override { return alive_; }
    const std::optional<CollapseReport>& collapse() const override { return collapse_; }
    // Same name as the reference: the two engines give the same output, so the
    // file's `engine` attribute need not say which one ran.
    std::string name() const override { return "event"; }
    // Checkpoints are taken between windows (advance_to returns only there),
    // where the per-window state is empty: the records, the clocks, the window
    // length and the stall-bound history are the whole state.
    std::optional<EngineSnapshot> snapshot() const override;
    void restore(const EngineSnapshot& snapshot) override;
    static constexpr const char* snapshot_kind = "fast_event";

    // Collisions at or above delta so far (classify: inelastic); what
    // HybridEngine's switch rule reads. Not in ReferenceEventEngine: only this engine
    // is handed over from.
    std::uint64_t inelastic_collisions() const { return inelastic_; }
    // The ring now, one particle per slot, positions unwrapped from the same
    // walk as clusters() (so a hand-over reports the same positions bit for
    // bit). Only while every particle is its own cluster (no merge happened).
    MidRunState mid_run_state() const;

    // Diagnostics for the benchmark.
    std::uint64_t windows() const { return windows_; }
    std::uint64_t blocks() const { return blocks_; }

    // The cluster record plus the heap position; the heap entries are
    // transient (pairs due in one window of one block).
    static constexpr std::size_t bytes_per_particle() { return sizeof(Node) + sizeof(std::int32_t); }

private:
    // One cache-friendly record per slot: everything an event reads or writes
    // about a cluster, including its pair's key (the reference keeps the key
    // in the queue's separate time array).
    struct Node {
        double velocity;
        double gap;    // to the next live cluster, valid at max(clock, next's clock)
        double clock;  // time of the last velocity change
        double mass;
        double key;    // scheduled collision time of (this, next); never if none
        std::int32_t next;
        std::int32_t prev;
    };
    // A cut pair's state at the start of a window.
    struct Cut {
        std::int32_t left;
        std::int32_t right;
        double gap;
        double left_velocity;
        double left_clock;
        double right_velocity;
        double right_clock;
    };
    // One velocity change of a boundary cluster: the event (time, slot) that
    // made it, the cluster now at the boundary, its new velocity and, after a
    // merge that moved the boundary to the left partner, their contact gap.
    struct BoundaryChange {
        double time;
        std::int32_t event_slot;
        std::int32_t end_slot;
        double velocity;
        double contact_gap;
    };
    // Windows whose events might join one stall run (see check_stall_bound).
    struct WindowRuns {
        double end;
        double stall_span;
        std::uint64_t run_events;  // sum over blocks of (densest run + 1)
    };

    double gap_at(std::int32_t slot, double t) const;
    double key_for(std::int32_t slot) const;
    double linked_key(std::int32_t slot) const;
    double rekey(std::int32_t slot);
    void reschedule(std::int32_t slot);
    bool cuttable(std::int32_t slot) const;
    void run_window(double window_end);
    void run_block(std::int32_t first, std::int32_t last);
    void collide_pair(std::int32_t i, double t);
    void replay_cut(const Cut& cut, const std::vector<BoundaryChange>& left_side,
                    const std::vector<BoundaryChange>& right_side);
    Cut snapshot_cut(std::int32_t left) const;
    void check_stall_bound(double window_end, std::uint64_t run_events);
    void save_rewind();
    void rewind();
    void move_anchor_clock(std::int32_t slot, double t);

    // What detail::collide_neighbours (the collision step both event engines
    // share) needs: the block's ends are cuts, whose changes are logged for
    // the replay instead of applied.
    template <class Engine>
    friend void detail::collide_neighbours(Engine& engine, std::int32_t i, double t, CollisionKind kind);
    std::vector<Node>& records() { return node_; }
    template <class Engine>
    friend ContactCluster detail::contact_cluster(const Engine& engine, std::int32_t i, double t);
    const std::vector<Node>& records() const { return node_; }
    bool left_is_cut(std::int32_t i) const { return i == block_first_; }
    bool right_is_cut(std::int32_t j) const { return j == block_last_; }
    void unschedule(std::int32_t slot) {
        heap_.remove(slot);
        node_[static_cast<std::size_t>(slot)].key = QuaternaryHeap::never;
    }
    // i is the heap's top; left and right (-1: a cut, not in the block) are
    // its neighbour pairs.
    void reschedule_collided(std::int32_t i, std::int32_t left, std::int32_t right);
    void log_left(double t, std::int32_t i, double velocity) { left_changes_.push_back({t, i, i, velocity, 0.0}); }
    void log_right(double t, std::int32_t i, std::int32_t end, double velocity, double contact_gap) {
        right_changes_.push_back({t, i, end, velocity, contact_gap});
    }
    void became_block_end(std::int32_t i) { block_last_ = i; }

    std::vector<Node> node_;
    QuaternaryHeap heap_;
    CollisionModel model_;
    CollapseCriterion criterion_;
    LiveStatus* live_;
    double ring_length_;
    double time_unit_;       // L/N: the stall span's floor (CollapseCriterion)
    double frame_velocity_;  // velocities are relative to it (frame_velocity, state.hpp)
    double now_ = 0.0;
    std::int64_t particles_;
    std::int64_t alive_;
    std::uint64_t collisions_ = 0;
    std::uint64_t inelastic_ = 0;
    std::int32_t anchor_ = 0;
    double anchor_position_ = 0.0;
    std::optional<CollapseReport> collapse_;

    // Collapse detection (delta below the collapse speed; see the header's
    // comment): the copy of the state between windows that a window meeting
    // a slow inelastic collision goes back to, and the window (by count) to
    // run as one block of the whole ring. rewound() is what a rewind restores
    // besides the records (the clock, the counters and the window history),
    // as one tuple of references.
    auto rewound() {
        return std::tie(now_, anchor_position_, window_length_, speed_bound_, window_start_, collisions_, inelastic_,
                        alive_, anchor_, windows_, blocks_, recent_windows_);
    }
    struct Rewind {
        std::vector<Node> nodes;
        std::tuple<double, double, double, double, double, std::uint64_t, std::uint64_t, std::int64_t, std::int32_t,
                   std::uint64_t, std::uint64_t, std::deque<WindowRuns>>
            values;
        std::uint64_t windows = 0;  // the window count it was taken at
    };
    static constexpr std::uint64_t no_window = ~std::uint64_t{0};
    bool collapse_possible_ = false;
    bool global_window_ = false;     // this window runs as one block of the whole ring
    bool candidate_seen_ = false;    // a block met a slow inelastic collision: abandon the window
    bool slow_pair_seen_ = false;    // the window run as the global loop met one (and it was no collapse)
    std::uint64_t global_window_index_ = no_window;
    Rewind rewind_;
    std::uint64_t stall_window_;

    // Window state.
    double window_length_;
    double window_start_ = 0.0;
    double window_end_ = 0.0;
    double cut_reach_ = 0.0;  // 2 |v|max W safety: the gap a cut pair must exceed
    std::uint64_t blocks_last_window_ = 0;
    double speed_bound_;  // |v|max at the start of the previous window: a bound for all later times
    std::int32_t block_first_ = -1;  // the current block's boundary clusters (-1: no cuts)
    std::int32_t block_last_ = -1;
    std::vector<BoundaryChange> left_changes_;   // current block: changes of block_first_
    std::vector<BoundaryChange> right_changes_;  // current block: changes at its right end
    std::vector<BoundaryChange> previous_right_changes_;
    std::vector<BoundaryChange> first_left_changes_;
    std::uint64_t window_events_ = 0;
    // Per-block densest run of events within the stall span (see check_stall_bound).
    double stall_span_ = 0.0;
    double run_reference_ = 0.0;
    std::uint64_t run_length_ = 0;
    std::uint64_t densest_run_ = 0;
    std::deque<WindowRuns> recent_windows_;
    std::uint64_t windows_ = 0;
    std::uint64_t blocks_ = 0;
};

}  // namespace shockgas
