// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_event_engine.hpp"

#include <algorithm>

#include "shockgas/model/collision.hpp"
#include "snapshot_io.hpp"
#include "ring_kinematics.hpp"
#include "neighbour_collision.hpp"

namespace shockgas {

namespace {
// Publish progress and look at the stop flag every 4096 events: rare enough to
// cost nothing, often enough that Ctrl-C answers within milliseconds.
constexpr std::uint64_t live_status_period_mask = 0xFFF;
}  // namespace

ReferenceEventEngine::ReferenceEventEngine(const InitialCondition& initial, const CollisionModel& model,
                         const CollapseCriterion& collapse, LiveStatus* live)
    : queue_(static_cast<std::int32_t>(initial.size())),
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
    const auto n = static_cast<std::int32_t>(initial.size());
    link_ring(initial, frame_velocity_, cluster_);
    anchor_position_ = initial.position[0];
    for (std::int32_t i = 0; i < n; ++i) reschedule(i);
}

// Gap between slot and its right neighbour at time t (>= both clocks):
//   gap(t) = gap(tau) + (v_right - v_left) (t - tau),  tau = max(clock_left, clock_right).
double ReferenceEventEngine::gap_at(std::int32_t slot, double t) const {
    const Cluster& left = cluster_[static_cast<std::size_t>(slot)];
    const Cluster& right = cluster_[static_cast<std::size_t>(left.next)];
    return gap_at_time(left.gap, left.velocity, right.velocity, left.clock, right.clock, t);
}

// Pair (slot, next) collides at tau + gap / (v_left - v_right) if approaching;
// an approaching pair whose gap is already <= 0 collides now.
void ReferenceEventEngine::reschedule(std::int32_t slot) {
    const Cluster& left = cluster_[static_cast<std::size_t>(slot)];
    if (left.next == slot) {
        queue_.remove(slot);
        return;
    }
    const Cluster& right = cluster_[static_cast<std::size_t>(left.next)];
    const double closing_speed = left.velocity - right.velocity;
    if (!(closing_speed > 0.0)) {
        queue_.remove(slot);
        return;
    }
    queue_.schedule(slot, contact_time(left.gap, closing_speed, left.clock, right.clock, now_));
}

void ReferenceEventEngine::move_anchor_clock(std::int32_t slot, double t) {
    if (slot != anchor_) return;
    const Cluster& c = cluster_[static_cast<std::size_t>(slot)];
    anchor_position_ += c.velocity * (t - c.clock);
}

bool ReferenceEventEngine::step(double t_limit) {
    if (collapse_ || queue_.empty()) return false;
    const double t = queue_.top_time();
    if (!(t <= t_limit)) return false;
    collide_pair(queue_.top_slot(), t);
    return true;
}

bool ReferenceEventEngine::advance_to(double t) {
    while (!collapse_) {
        const double next = queue_.top_time();
        if (!(next <= t)) break;
        collide_pair(queue_.top_slot(), next);
        if (live_ != nullptr && (collisions_ & live_status_period_mask) == 0) {
            live_->time.store(now_, std::memory_order_relaxed);
            live_->collisions.store(collisions_, std::memory_order_relaxed);
            if (live_->halt_requested()) return false;
        }
    }
    if (collapse_) return false;
    now_ = std::max(now_, t);
    return true;
}

void ReferenceEventEngine::collide_pair(std::int32_t i, double t) {
    now_ = t;
    const Cluster& a = cluster_[static_cast<std::size_t>(i)];
    const double relative_speed = a.velocity - cluster_[static_cast<std::size_t>(a.next)].velocity;
    const CollisionKind kind = classify(model_, relative_speed);

    // Collapse: time no longer advances, or relative speeds have decayed
    // geometrically to nothing in an inelastic collision. Where the model
    // forbids collapse, time that no longer advances is a numerical failure.
    if (t - stall_reference_time_ <= criterion_.stall_time_fraction * std::max(time_unit_, t)) {
        if (++stall_events_ >= stall_window_) {
            if (detail::collapse_forbidden(model_)) numerical_stall(t, relative_speed);
            detect_collapse(i, relative_speed, t, "stall", detail::contact_cluster(*this, i, t));
            return;
        }
    } else {
        stall_reference_time_ = t;
        stall_events_ = 0;
    }
    if (detail::collapse_candidate(criterion_, kind, relative_speed)) {
        const ContactCluster cluster = detail::contact_cluster(*this, i, t);
        if (cluster.members >= detail::collapse_min_members) {
            detect_collapse(i, relative_speed, t, "relative_speed", cluster);
            return;
        }
    }

    detail::collide_neighbours(*this, i, t, kind);
}

void ReferenceEventEngine::detect_collapse(std::int32_t i, double relative_speed, double t, const char* criterion,
                                  const ContactCluster& cluster) {
    // The collapsing cluster is the pair's contact cluster.
    collapse_ = detail::collapse_report(i, relative_speed, t, criterion, cluster);
    now_ = t;
}

void ReferenceEventEngine::numerical_stall(double t, double relative_speed) const {
    throw NumericalFailure(
        detail::stall_message(model_, criterion_, stall_window_, stall_reference_time_, t, relative_speed));
}

std::vector<double> ReferenceEventEngine::gaps() const {
    std::vector<double> out;
    out.reserve(static_cast<std::size_t>(alive_));
    std::int32_t s = anchor_;
    for (std::int64_t k = 0; k < alive_; ++k) {
        out.push_back(gap_at(s, now_));
        s = cluster_[static_cast<std::size_t>(s)].next;
    }
    return out;
}

std::optional<EngineSnapshot> ReferenceEventEngine::snapshot() const {
    if (collapse_) return std::nullopt;  // a collapsed run is finished, not paused
    EngineSnapshot out;
    out.kind = snapshot_kind;
    snapshot_io::save_ring(cluster_, out);
    auto& key = out.reals["key"];
    for (std::size_t s = 0; s < cluster_.size(); ++s) key.push_back(queue_.time_of(static_cast<std::int32_t>(s)));
    out.reals["scalars"] = {now_, anchor_position_, stall_reference_time_};
    out.integers["counters"] = {static_cast<std::int64_t>(collisions_), alive_, anchor_,
                                static_cast<std::int64_t>(stall_events_)};
    return out;
}

// The queue is rebuilt from the saved keys: it orders events by (time, slot),
// a total order, so its pops do not depend on the heap's internal layout.
void ReferenceEventEngine::restore(const EngineSnapshot& snapshot) {
    snapshot_io::expect_kind(snapshot, snapshot_kind, name());
    snapshot_io::restore_ring(snapshot, cluster_);
    const auto& key = snapshot_io::array(snapshot.reals, "key", cluster_.size(), snapshot);
    const auto& scalars = snapshot_io::array(snapshot.reals, "scalars", 3, snapshot);
    const auto& counters = snapshot_io::array(snapshot.integers, "counters", 4, snapshot);
    now_ = scalars[0];
    anchor_position_ = scalars[1];
    stall_reference_time_ = scalars[2];
    collisions_ = static_cast<std::uint64_t>(counters[0]);
    alive_ = counters[1];
    anchor_ = static_cast<std::int32_t>(counters[2]);
    stall_events_ = static_cast<std::uint64_t>(counters[3]);
    if (alive_ < 1 || alive_ > particles_ || anchor_ < 0 || anchor_ >= particles_)
        throw InputError("checkpoint: event engine state has an impossible cluster count or anchor");
    queue_.reset(static_cast<std::int32_t>(cluster_.size()));
    for (std::size_t s = 0; s < key.size(); ++s)
        if (key[s] != EventQueue::never) queue_.schedule(static_cast<std::int32_t>(s), key[s]);
}

void ReferenceEventEngine::clusters(ClusterState& out) const {
    walk_ring(cluster_, anchor_, anchor_position_, now_, alive_, ring_length_, frame_velocity_,
              [this](std::int32_t slot, double t) { return gap_at(slot, t); }, out);
}

}  // namespace shockgas
