// SPDX-License-Identifier: GPL-3.0-or-later
#include "event_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "shockgas/model/collision.hpp"
#include "snapshot_io.hpp"
#include "ring_kinematics.hpp"
#include "neighbour_collision.hpp"

namespace shockgas {

namespace {
constexpr double never = QuaternaryHeap::never;
// Cut only where the gap exceeds this multiple of the largest distance the two
// ends can close in the window, 2 W |v|max. The margin absorbs the rounding of
// the key computation (relative 1e-15); every cut key is checked anyway.
constexpr double cut_safety = 1.25;
// Fewest clusters between cuts, and events per live cluster per window that
// the window length aims at. Small blocks keep each heap a few entries deep,
// which beats the per-block overhead (snapshot, heapify, replay) down to ~8
// clusters; short windows make more pairs cuttable, which beats the O(N) scan
// per window down to ~0.3 events per cluster. The rate is flat near (8, 0.3)
// (within the noise from (4, 0.3) to (12, 0.4)) and falls off at (48, 0.75),
// (16, 0.5) and (2, 0.15) (docs/measurements.md, "Measurements behind
// constants in the code"); what makes the engine fast is few instructions per
// event and per scanned cluster: the scan loads due pairs straight into the
// heap with the cut test inlined, collide_pair and the reschedules are
// inlined, and the taken pair is re-keyed at the heap's top.
constexpr std::int64_t min_block_clusters = 8;
constexpr double target_events_per_cluster = 0.3;
// Beyond this mean block size (clusters) a block's heap and records no longer
// sit in L2, so the window is shortened to make more cuts.
constexpr double max_mean_block_clusters = 4096.0;
constexpr double first_window = 0.05;
// Where collapse is possible, the state is copied every this many windows
// (and at each advance_to), so a window that meets a slow inelastic collision
// goes back at most this far.
constexpr std::uint64_t rewind_period = 16;
}  // namespace

bool EventEngine::supports(const InitialCondition& initial, const CollisionModel& model,
                               const CollapseCriterion& /*collapse: detected exactly, see the header*/) {
    if (initial.size() < 2) return false;
    if (model.restitution == 0.0) return true;  // merges only: V = (m1 v1 + m2 v2)/(m1 + m2) is convex for any masses
    // Merged clusters then collide with r > 0 (sticky sub-threshold; at delta = 0 no collision is below it).
    if (model.subthreshold == Subthreshold::sticky && model.velocity_threshold > 0.0) return false;
    const double mass = initial.mass.front();
    return std::all_of(initial.mass.begin(), initial.mass.end(), [mass](double m) { return m == mass; });
}

EventEngine::EventEngine(const InitialCondition& initial, const CollisionModel& model,
                                 const CollapseCriterion& collapse, LiveStatus* live)
    : heap_(static_cast<std::int32_t>(initial.size())),
      model_(model),
      criterion_(collapse),
      live_(live),
      ring_length_(initial.ring_length),
      time_unit_(time_unit(initial)),
      frame_velocity_(frame_velocity(initial.velocity, initial.mass)),
      particles_(initial.size()),
      alive_(initial.size()),
      stall_window_(std::max<std::uint64_t>(collapse.stall_events_min, 10 * static_cast<std::uint64_t>(initial.size()))) {
    validate(initial);
    if (!supports(initial, model, collapse))
        throw std::logic_error("EventEngine: run not supported, use ReferenceEventEngine (see supports())");
    collapse_possible_ = shockgas::collapse_possible(model, collapse);
    const auto n = static_cast<std::int32_t>(initial.size());
    link_ring(initial, frame_velocity_, node_);  // the same initial state and arithmetic as ReferenceEventEngine's
    anchor_position_ = initial.position[0];
    for (std::int32_t i = 0; i < n; ++i) node_[static_cast<std::size_t>(i)].key = key_for(i);
    speed_bound_ = 0.0;
    for (const Node& c : node_) speed_bound_ = std::max(speed_bound_, std::abs(c.velocity));
    // The first window, first_window in units of the mean spacing L/N over the
    // speed scale max(1, |v|max) (|v| in the frame; 1 the velocity unit): a
    // dense or fast start (--ring-length << N, or an --init file with large
    // velocities) would otherwise put billions of events into one window, and
    // the stop flag and the progress line are looked at only between windows.
    // For the paper's start (L = N, |v| < 1) this is first_window itself;
    // later windows adapt (advance_to).
    window_length_ = first_window * time_unit_ / std::max(1.0, speed_bound_);
}

double EventEngine::gap_at(std::int32_t slot, double t) const {
    const Node& left = node_[static_cast<std::size_t>(slot)];
    const Node& right = node_[static_cast<std::size_t>(left.next)];
    return gap_at_time(left.gap, left.velocity, right.velocity, left.clock, right.clock, t);
}

// The key ReferenceEventEngine::reschedule would give pair (slot, next) at now_.
double EventEngine::key_for(std::int32_t slot) const {
    const Node& left = node_[static_cast<std::size_t>(slot)];
    if (left.next == slot) return never;
    const Node& right = node_[static_cast<std::size_t>(left.next)];
    const double closing_speed = left.velocity - right.velocity;
    if (!(closing_speed > 0.0)) return never;
    return contact_time(left.gap, closing_speed, left.clock, right.clock, now_);
}

// key_for when at least two clusters live (so next != slot), as during every
// collision's reschedules.
[[gnu::always_inline]] inline double EventEngine::linked_key(std::int32_t slot) const {
    const Node& left = node_[static_cast<std::size_t>(slot)];
    const Node& right = node_[static_cast<std::size_t>(left.next)];
    const double closing_speed = left.velocity - right.velocity;
    if (!(closing_speed > 0.0)) return never;
    return contact_time(left.gap, closing_speed, left.clock, right.clock, now_);
}

// The pair's new key at now_, recorded in its node; the caller updates the
// heap. Called only while two or more clusters live.
[[gnu::always_inline]] inline double EventEngine::rekey(std::int32_t slot) {
    const double key = linked_key(slot);
    node_[static_cast<std::size_t>(slot)].key = key;
    return key;
}

// Within a block: record the key, and keep the pair in the block's heap only
// if it is due in this window.
[[gnu::always_inline]] inline void EventEngine::reschedule(std::int32_t slot) {
    const double key = rekey(slot);
    if (key <= window_end_)
        heap_.schedule(slot, key);
    else
        heap_.remove(slot);
}

// After a collision of pair i (the heap's top): i's new key, and its
// neighbour pairs' (left, right; -1: a cut), each kept in the heap only if
// due in this window.
void EventEngine::reschedule_collided(std::int32_t i, std::int32_t left, std::int32_t right) {
    const auto new_key = [this](std::int32_t slot) { return slot < 0 ? never : rekey(slot); };
    const double key = new_key(i);
    if (key <= window_end_) {  // not the usual case: the collided pair diverges
        heap_.replace_top(key);
        if (left >= 0) reschedule(left);
        if (right >= 0) reschedule(right);
        return;
    }
    // On a ring of two clusters both neighbour pairs are one.
    heap_.pop_top_and_schedule(left, new_key(left), right == left ? -1 : right, new_key(right), window_end_);
}

void EventEngine::move_anchor_clock(std::int32_t slot, double t) {
    if (slot != anchor_) return;
    const Node& c = node_[static_cast<std::size_t>(slot)];
    anchor_position_ += c.velocity * (t - c.clock);
}

// A pair can be a cut when its gap at the window start exceeds the closing
// bound and its event is not due in the window.
bool EventEngine::cuttable(std::int32_t slot) const {
    const Node& c = node_[static_cast<std::size_t>(slot)];
    if (c.next == slot || !(c.key > window_end_)) return false;
    return gap_at(slot, window_start_) > cut_reach_;
}

EventEngine::Cut EventEngine::snapshot_cut(std::int32_t left) const {
    const Node& l = node_[static_cast<std::size_t>(left)];
    const Node& r = node_[static_cast<std::size_t>(l.next)];
    return {left, l.next, l.gap, l.velocity, l.clock, r.velocity, r.clock};
}

bool EventEngine::advance_to(double t) {
    if (collapse_) return false;
    // A copy to go back to within this call (whose window ends are clipped
    // at t, so the windows run again come out the same).
    if (collapse_possible_) save_rewind();
    for (;;) {
        if (collapse_possible_ && windows_ - rewind_.windows >= rewind_period) save_rewind();
        const double end = std::min(now_ + window_length_, t);
        const double start = now_;
        global_window_ = windows_ == global_window_index_;
        const bool forced_global = global_window_;
        slow_pair_seen_ = false;
        run_window(end);
        if (candidate_seen_) {
            // A block met a slow inelastic collision: run this window again
            // as the global loop, from the copy (header comment).
            candidate_seen_ = false;
            global_window_index_ = windows_;
            rewind();
            continue;
        }
        const bool ran_global = global_window_;  // also a ring with no cut, which is one block anyway
        if (collapse_) {
            if (live_ != nullptr) {
                live_->time.store(now_, std::memory_order_relaxed);
                live_->collisions.store(collisions_, std::memory_order_relaxed);
            }
            return false;
        }
        now_ = end;
        ++windows_;
        // Adapt W: about target_events_per_cluster events per cluster per
        // window, fewer if blocks grew too large to stay in cache. Changes are
        // bounded per window so that one quiet window does not blow W up.
        if (end < t || window_events_ > 0) {
            const double clusters = static_cast<double>(alive_);
            const double blocks = std::max<double>(1.0, static_cast<double>(blocks_last_window_));
            double factor = 2.0;
            if (window_events_ > 0)
                factor = std::clamp(target_events_per_cluster * clusters / static_cast<double>(window_events_), 0.5, 2.0);
            // (Not after a window made one block on purpose to judge a slow pair.)
            if (!forced_global && clusters / blocks > max_mean_block_clusters) factor = std::min(factor, 0.7);
            if (end - start >= 0.5 * window_length_) window_length_ *= factor;
        }
        if (ran_global && collapse_possible_) {
            // A later rewind must not go back past a window run as the global
            // loop: run normally, that window would be abandoned again. While
            // slow pairs go on, the next window runs as the global loop at once.
            global_window_index_ = slow_pair_seen_ ? windows_ : no_window;
            save_rewind();
        }
        if (live_ != nullptr) {
            live_->time.store(now_, std::memory_order_relaxed);
            live_->collisions.store(collisions_, std::memory_order_relaxed);
            if (live_->halt_requested()) return false;
        }
        if (!(now_ < t)) break;
    }
    now_ = std::max(now_, t);
    return true;
}

void EventEngine::run_window(double window_end) {
    window_start_ = now_;
    window_end_ = window_end;
    // A window run as the global loop has no cut: no gap exceeds an infinite reach.
    cut_reach_ = global_window_ ? never : 2.0 * speed_bound_ * (window_end_ - window_start_) * cut_safety;
    window_events_ = 0;
    blocks_last_window_ = 0;
    stall_span_ = criterion_.stall_time_fraction * std::max(time_unit_, window_end);
    std::uint64_t run_events = 0;
    double next_speed_bound = 0.0;

    // The first cut, searched from the anchor.
    std::int32_t first_cut = -1;
    {
        std::int32_t s = anchor_;
        for (std::int64_t k = 0; k < alive_; ++k) {
            if (cuttable(s)) {
                first_cut = s;
                break;
            }
            s = node_[static_cast<std::size_t>(s)].next;
        }
    }

    // Scan one block from `first`: load its due pairs into the (empty) heap,
    // track |v|max, stop at a cut at least min_block_clusters on, or at `stop`
    // (inclusive). cuttable() inlined: with the slot's record at hand, and
    // next != slot because more than one cluster lives whenever a block ends
    // anywhere but at `stop`.
    auto scan_block = [&](std::int32_t first, std::int32_t stop) {
        const Node* nodes = node_.data();
        const double end = window_end_;
        const double start = window_start_;
        const double reach = cut_reach_;
        double speed = next_speed_bound;
        std::int32_t s = first;
        // The first min_block_clusters - 1 clusters cannot end the block at a cut.
        for (std::int64_t count = 1; count < min_block_clusters; ++count) {
            const Node& c = nodes[s];
            speed = std::max(speed, std::abs(c.velocity));
            if (c.key <= end) heap_.append_unordered(s, c.key);
            if (s == stop) {
                next_speed_bound = speed;
                return s;
            }
            s = c.next;
        }
        for (;;) {
            const Node& c = nodes[s];
            speed = std::max(speed, std::abs(c.velocity));
            const bool due = c.key <= end;
            if (due) heap_.append_unordered(s, c.key);
            if (s == stop) break;
            const std::int32_t next = c.next;
            if (!due) {
                const Node& r = nodes[next];
                if (gap_at_time(c.gap, c.velocity, r.velocity, c.clock, r.clock, start) > reach) break;
            }
            s = next;
        }
        next_speed_bound = speed;
        return s;
    };

    auto run_scanned = [&](std::int32_t first, std::int32_t last) {
        heap_.heapify();
        run_block(first, last);
        run_events += densest_run_ + 1;
        ++blocks_last_window_;
    };

    std::int32_t whole_ring_last = -1;
    if (first_cut >= 0) {
        const Cut first = snapshot_cut(first_cut);
        const std::int32_t last = scan_block(first.right, first_cut);
        if (last != first_cut) {
            // At least two cuts: independent blocks.
            Cut left_cut = first;
            std::int32_t block_first = first.right;
            std::int32_t block_last = last;
            for (std::uint64_t index = 0;; ++index) {
                const bool final_block = block_last == first_cut;
                const Cut right_cut = final_block ? first : snapshot_cut(block_last);
                run_scanned(block_first, block_last);
                if (candidate_seen_) return;  // abandoned: the state goes back to the copy
                if (index == 0)
                    first_left_changes_.swap(left_changes_);
                else
                    replay_cut(left_cut, previous_right_changes_, left_changes_);
                previous_right_changes_.swap(right_changes_);
                if (final_block) break;
                left_cut = right_cut;
                block_first = right_cut.right;
                block_last = scan_block(block_first, first_cut);
            }
            replay_cut(first, previous_right_changes_, first_left_changes_);
        } else {
            whole_ring_last = first_cut;  // one cut only: the whole ring is one block
        }
    } else {
        // No cut at all: one block, scanned from the anchor.
        whole_ring_last = node_[static_cast<std::size_t>(anchor_)].prev;
        scan_block(anchor_, whole_ring_last);
    }
    if (whole_ring_last >= 0) {
        // The pending list of the whole ring is already collected; no cut
        // pairs, so nothing is deferred and the block is the global loop,
        // which judges a collapse itself.
        global_window_ = true;
        run_scanned(-1, -1);
    }
    speed_bound_ = next_speed_bound;
    blocks_ += blocks_last_window_;
    check_stall_bound(window_end, run_events);
}

void EventEngine::run_block(std::int32_t first, std::int32_t last) {
    block_first_ = first;
    block_last_ = last;
    left_changes_.clear();
    right_changes_.clear();
    run_reference_ = -std::numeric_limits<double>::infinity();
    run_length_ = 0;
    densest_run_ = 0;
    while (!heap_.empty()) collide_pair(heap_.top_slot(), heap_.top_time());
}

// ReferenceEventEngine::collide_pair restricted to a block: the same statements in the
// same order, except that the cut pairs' gaps and keys (left of block_first_,
// right of block_last_) are not touched but logged for replay_cut.
[[gnu::always_inline]] inline void EventEngine::collide_pair(std::int32_t i, double t) {
    now_ = t;
    ++window_events_;
    // Densest run of events within stall_span_ of a reference event, counted
    // like the global stall detector but per block (see check_stall_bound).
    if (t - run_reference_ > stall_span_) {
        run_reference_ = t;
        run_length_ = 0;
    } else if (++run_length_ > densest_run_) {
        densest_run_ = run_length_;
    }

    const Node& a = node_[static_cast<std::size_t>(i)];
    const double relative_speed = a.velocity - node_[static_cast<std::size_t>(a.next)].velocity;
    const CollisionKind kind = classify(model_, relative_speed);
    // Never true where collapse is impossible (inelastic means g >= delta >= the collapse speed).
    if (detail::collapse_candidate(criterion_, kind, relative_speed)) [[unlikely]] {
        if (!global_window_) {
            // Blocks cannot place it in global order: abandon the window.
            candidate_seen_ = true;
            heap_.clear();
            return;
        }
        // ReferenceEventEngine::collide_pair's test, in the same global order.
        slow_pair_seen_ = true;
        const ContactCluster cluster = detail::contact_cluster(*this, i, t);
        if (cluster.members >= detail::collapse_min_members) {
            collapse_ = detail::collapse_report(i, relative_speed, t, "relative_speed", cluster);
            heap_.clear();
            return;
        }
    }
    inelastic_ += kind == CollisionKind::inelastic ? 1 : 0;
    detail::collide_neighbours(*this, i, t, kind);
}

// Replays the cut pair's gap and key updates in global (time, slot) order:
// the changes of its left end (from the left block) and of its right end (from
// the right block). Each step is ReferenceEventEngine's gap_at followed by reschedule,
// with now = the event's time.
void EventEngine::replay_cut(const Cut& cut, const std::vector<BoundaryChange>& left_side,
                                 const std::vector<BoundaryChange>& right_side) {
    if (left_side.empty() && right_side.empty()) return;
    std::int32_t left = cut.left;
    double gap = cut.gap;
    double left_velocity = cut.left_velocity;
    double left_clock = cut.left_clock;
    double right_velocity = cut.right_velocity;
    double right_clock = cut.right_clock;
    double key = never;
    std::size_t a = 0;
    std::size_t b = 0;
    while (a < left_side.size() || b < right_side.size()) {
        bool take_left = b == right_side.size();
        if (!take_left && a < left_side.size()) {
            const BoundaryChange& l = left_side[a];
            const BoundaryChange& r = right_side[b];
            take_left = l.time < r.time || (l.time == r.time && l.event_slot < r.event_slot);
        }
        const BoundaryChange& change = take_left ? left_side[a++] : right_side[b++];
        const double t = change.time;
        gap = gap_at_time(gap, left_velocity, right_velocity, left_clock, right_clock, t);
        if (take_left) {
            // A merge moved the cut's left end from one cluster to its left
            // neighbour: the gap grows by their contact gap (ReferenceEventEngine's
            // contact_gap + b.gap).
            if (change.end_slot != left) gap = change.contact_gap + gap;
            left = change.end_slot;
            left_velocity = change.velocity;
            left_clock = t;
        } else {
            right_velocity = change.velocity;
            right_clock = t;
        }
        const double closing_speed = left_velocity - right_velocity;
        key = never;
        if (closing_speed > 0.0) key = contact_time(gap, closing_speed, left_clock, right_clock, t);
        if (!(key > window_end_))
            throw std::logic_error("EventEngine: a cut pair became due inside its window");
    }
    Node& l = node_[static_cast<std::size_t>(left)];
    l.gap = gap;
    l.key = key;
    node_[static_cast<std::size_t>(cut.right)].prev = left;
}

// The global stall detector fires after stall_window_ consecutive events
// within stall_time_fraction * max(L/N, t) of a reference event. Per block we
// count the densest such run with the span of this window (its end time, an
// upper bound); a span-wide interval meets at most span/span' + 2 of a
// window's runs counted with span', each holding at most (densest run + 1)
// events of a block, so a global run is bounded by the sum of those over the
// windows it can reach. If that sum cannot exclude a stall the
// global order would be needed, which this engine does not have: throw.
void EventEngine::check_stall_bound(double window_end, std::uint64_t run_events) {
    const double span = stall_span_;
    recent_windows_.push_back({window_end, span, run_events});
    // A run that reaches into this window starts after window_start_ - span.
    while (recent_windows_.size() > 1 && recent_windows_.front().end < window_start_ - span)
        recent_windows_.pop_front();
    double bound = 0.0;
    for (const WindowRuns& w : recent_windows_)
        bound += (std::floor(span / w.stall_span) + 2.0) * static_cast<double>(w.run_events);
    if (bound >= static_cast<double>(stall_window_))
        throw StallUndecidable(
            "EventEngine: cannot exclude a stall (events too dense in time); rerun with the reference engine");
}

void EventEngine::save_rewind() {
    rewind_.nodes = node_;
    rewind_.values = rewound();
    rewind_.windows = windows_;
}

void EventEngine::rewind() {
    if (rewind_.nodes.size() != node_.size()) throw std::logic_error("EventEngine: no state to go back to");
    node_ = rewind_.nodes;
    rewound() = rewind_.values;
    heap_.clear();
    left_changes_.clear();
    right_changes_.clear();
    previous_right_changes_.clear();
    first_left_changes_.clear();
}

std::optional<EngineSnapshot> EventEngine::snapshot() const {
    if (collapse_) return std::nullopt;  // a collapsed run is finished, not paused
    EngineSnapshot out;
    out.kind = snapshot_kind;
    snapshot_io::save_ring(node_, out);
    auto& key = out.reals["key"];
    for (const Node& c : node_) key.push_back(c.key);
    out.reals["scalars"] = {now_, anchor_position_, window_length_, speed_bound_, window_start_};
    out.integers["counters"] = {static_cast<std::int64_t>(collisions_), alive_, anchor_,
                                static_cast<std::int64_t>(windows_), static_cast<std::int64_t>(blocks_),
                                static_cast<std::int64_t>(inelastic_)};
    auto& recent_end = out.reals["recent_window_end"];
    auto& recent_span = out.reals["recent_window_stall_span"];
    auto& recent_events = out.integers["recent_window_run_events"];
    for (const WindowRuns& w : recent_windows_) {
        recent_end.push_back(w.end);
        recent_span.push_back(w.stall_span);
        recent_events.push_back(static_cast<std::int64_t>(w.run_events));
    }
    return out;
}

void EventEngine::restore(const EngineSnapshot& snapshot) {
    snapshot_io::expect_kind(snapshot, snapshot_kind, "fast event");
    snapshot_io::restore_ring(snapshot, node_);
    const auto& key = snapshot_io::array(snapshot.reals, "key", node_.size(), snapshot);
    for (std::size_t s = 0; s < node_.size(); ++s) node_[s].key = key[s];
    const auto& scalars = snapshot_io::array(snapshot.reals, "scalars", 5, snapshot);
    // Six counters; checkpoints written before the inelastic count was kept
    // have five (the count then restarts at 0: it only steers HybridEngine,
    // whose checkpoints always have six).
    const auto counters_it = snapshot.integers.find("counters");
    const std::size_t counter_count =
        counters_it != snapshot.integers.end() && counters_it->second.size() == 5 ? 5 : 6;
    const auto& counters = snapshot_io::array(snapshot.integers, "counters", counter_count, snapshot);
    inelastic_ = counter_count == 6 ? static_cast<std::uint64_t>(counters[5]) : 0;
    now_ = scalars[0];
    anchor_position_ = scalars[1];
    window_length_ = scalars[2];
    speed_bound_ = scalars[3];
    window_start_ = scalars[4];
    collisions_ = static_cast<std::uint64_t>(counters[0]);
    alive_ = counters[1];
    anchor_ = static_cast<std::int32_t>(counters[2]);
    windows_ = static_cast<std::uint64_t>(counters[3]);
    blocks_ = static_cast<std::uint64_t>(counters[4]);
    if (alive_ < 1 || alive_ > particles_ || anchor_ < 0 || anchor_ >= particles_)
        throw InputError("checkpoint: fast engine state has an impossible cluster count or anchor");
    const auto windows = snapshot.reals.count("recent_window_end") ? snapshot.reals.at("recent_window_end").size() : 0;
    const auto& recent_end = snapshot_io::array(snapshot.reals, "recent_window_end", windows, snapshot);
    const auto& recent_span = snapshot_io::array(snapshot.reals, "recent_window_stall_span", windows, snapshot);
    const auto& recent_events = snapshot_io::array(snapshot.integers, "recent_window_run_events", windows, snapshot);
    recent_windows_.clear();
    for (std::size_t w = 0; w < windows; ++w)
        recent_windows_.push_back({recent_end[w], recent_span[w], static_cast<std::uint64_t>(recent_events[w])});
}

MidRunState EventEngine::mid_run_state() const {
    if (alive_ != particles_) throw std::logic_error("EventEngine::mid_run_state: clusters have merged");
    MidRunState out;
    out.ring_length = ring_length_;
    out.time = now_;
    out.frame_velocity = frame_velocity_;
    out.collisions = collisions_;
    out.inelastic_collisions = inelastic_;
    std::vector<double> walk_position;
    std::vector<std::int32_t> walk_slot;
    const std::size_t first = walk_positions(
        node_, anchor_, anchor_position_, now_, alive_, [this](std::int32_t slot, double t) { return gap_at(slot, t); },
        walk_position, walk_slot);
    // From particle 0 on (the anchor is particle 0 unless a merge moved it, so
    // normally first = 0 and no position is shifted): the part of the walk
    // before it comes one ring length later.
    const std::size_t n = walk_position.size();
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t w = (first + k) % n;
        const Node& c = node_[static_cast<std::size_t>(walk_slot[w])];
        out.position.push_back(w < first ? walk_position[w] + ring_length_ : walk_position[w]);
        out.velocity.push_back(c.velocity);
        out.mass.push_back(c.mass);
    }
    return out;
}

void EventEngine::clusters(ClusterState& out) const {
    walk_ring(node_, anchor_, anchor_position_, now_, alive_, ring_length_, frame_velocity_,
              [this](std::int32_t slot, double t) { return gap_at(slot, t); }, out);
}

}  // namespace shockgas
