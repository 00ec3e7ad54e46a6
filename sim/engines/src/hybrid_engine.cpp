// SPDX-License-Identifier: GPL-3.0-or-later
#include "hybrid_engine.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "snapshot_io.hpp"

namespace shockgas {

namespace {
// The switch rule's threshold: hand over once at most 10% of a stretch's
// collisions (t to 1.25 t, between checks) were inelastic. It comes from the
// crossover measured per stretch with `SHOCKGAS_BENCH_CROSSOVER=paper|fig5
// bench_engine`: the event engine's CPU seconds over those of a pass-through
// engine started from the same state, against the stretch's inelastic share,
// in the paper's setting (r = 0.9, delta = 1e-2, N = 1e5) and in Fig. 5's
// (r = 0.99, delta = 1e-4, N = 2e4). Every stretch at or below 28% (first
// setting) and 15.4% (second) ran faster in the pass-through engine, every one
// above 49% slower, so the rule takes 10%: below both, with the second
// setting's 15.4% stretch as the margin. The per-stretch tables:
// docs/measurements.md, "The hybrid engine".
constexpr double default_max_inelastic_share = 0.10;
constexpr const char* inner_prefix = "inner_";
}  // namespace

HybridSwitchRule HybridSwitchRule::measured() {
    HybridSwitchRule rule;
    rule.max_inelastic_share = default_max_inelastic_share;
    return rule;
}

HybridEngine::HybridEngine(const InitialCondition& initial, const CollisionModel& model,
                           const CollapseCriterion& collapse, LiveStatus* live, const HybridSwitchRule& rule)
    : model_(model), live_(live), rule_(rule), next_check_(rule.first_check * time_unit(initial)) {
    const std::string refusal = PassThroughEngine::unsupported_reason(initial.mass, model, collapse);
    if (!refusal.empty()) throw std::invalid_argument("HybridEngine cannot run this: " + refusal);
    if (!(rule.first_check > 0.0) || !(rule.check_factor > 1.0))
        throw std::invalid_argument("HybridEngine: checks need first_check > 0 and check_factor > 1");
    // Where the pass-through engine applies, so do the windows (equal masses,
    // elastic sub-threshold, no collapse detection can fire).
    event_ = std::make_unique<EventEngine>(initial, model, collapse, live);
}

double HybridEngine::time() const { return event_ ? event_->time() : passthrough_->time(); }
std::uint64_t HybridEngine::collisions() const { return event_ ? event_->collisions() : passthrough_->collisions(); }
std::uint64_t HybridEngine::inelastic_collisions() const {
    return event_ ? event_->inelastic_collisions() : passthrough_->inelastic_collisions();
}
std::int64_t HybridEngine::cluster_count() const {
    return event_ ? event_->cluster_count() : passthrough_->cluster_count();
}
void HybridEngine::clusters(ClusterState& out) const {
    if (event_)
        event_->clusters(out);
    else
        passthrough_->clusters(out);
}

bool HybridEngine::advance_to(double t) {
    while (event_) {
        if (!event_->advance_to(std::min(t, next_check_))) return false;
        if (event_->time() < next_check_) return true;  // at t, before the next check
        // A check: the inelastic share of the stretch since the last one.
        const std::uint64_t collisions = event_->collisions() - collisions_at_check_;
        const std::uint64_t inelastic = event_->inelastic_collisions() - inelastic_at_check_;
        collisions_at_check_ = event_->collisions();
        inelastic_at_check_ = event_->inelastic_collisions();
        next_check_ *= rule_.check_factor;
        if (static_cast<double>(inelastic) <= rule_.max_inelastic_share * static_cast<double>(collisions))
            hand_over();
        if (!(time() < t)) return true;
    }
    return passthrough_->advance_to(t);
}

// The physical state, bit for bit, into a pass-through engine started there.
void HybridEngine::hand_over() {
    switch_time_ = event_->time();
    passthrough_ = std::make_unique<PassThroughEngine>(event_->mid_run_state(), model_, live_);
    event_.reset();
}

std::optional<EngineSnapshot> HybridEngine::snapshot() const {
    const std::optional<EngineSnapshot> inner = event_ ? event_->snapshot() : passthrough_->snapshot();
    EngineSnapshot out;
    out.kind = snapshot_kind;
    // "scalars" first holds the time, as every engine's does (the ensemble
    // driver reads the resume time there).
    out.reals["scalars"] = {time(), next_check_, switch_time_};
    out.integers["hybrid"] = {event_ ? 0 : 1, static_cast<std::int64_t>(collisions_at_check_),
                              static_cast<std::int64_t>(inelastic_at_check_)};
    for (const auto& [name, values] : inner->reals) out.reals[inner_prefix + name] = values;
    for (const auto& [name, values] : inner->integers) out.integers[inner_prefix + name] = values;
    return out;
}

void HybridEngine::restore(const EngineSnapshot& snapshot) {
    snapshot_io::expect_kind(snapshot, snapshot_kind, name());
    const auto& scalars = snapshot_io::array(snapshot.reals, "scalars", 3, snapshot);
    const auto& state = snapshot_io::array(snapshot.integers, "hybrid", 3, snapshot);
    if (state[0] != 0 && state[0] != 1) throw InputError("checkpoint: hybrid engine state has an unknown phase");
    const bool passthrough_phase = state[0] == 1;
    EngineSnapshot inner;
    inner.kind = passthrough_phase ? PassThroughEngine::snapshot_kind : EventEngine::snapshot_kind;
    const std::string prefix = inner_prefix;
    for (const auto& [name, values] : snapshot.reals)
        if (name.rfind(prefix, 0) == 0) inner.reals[name.substr(prefix.size())] = values;
    for (const auto& [name, values] : snapshot.integers)
        if (name.rfind(prefix, 0) == 0) inner.integers[name.substr(prefix.size())] = values;
    if (!event_) throw InputError("checkpoint: a hybrid engine restores only before it has run");
    if (passthrough_phase) {
        // A pass-through engine of this ring's size (from the start the event
        // engine holds), then its own state.
        passthrough_ = std::make_unique<PassThroughEngine>(event_->mid_run_state(), model_, live_);
        passthrough_->restore(inner);
        event_.reset();
    } else {
        event_->restore(inner);
    }
    next_check_ = scalars[1];
    switch_time_ = scalars[2];
    collisions_at_check_ = static_cast<std::uint64_t>(state[1]);
    inelastic_at_check_ = static_cast<std::uint64_t>(state[2]);
}

}  // namespace shockgas
