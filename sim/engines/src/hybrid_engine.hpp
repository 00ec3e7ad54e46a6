// SPDX-License-Identifier: GPL-3.0-or-later
// The hybrid engine (`--engine hybrid`; docs/passthrough-engine.md): the
// event engine (EventEngine) early in a run, while most collisions are
// inelastic and it is the faster, then the pass-through engine, once nearly
// all collisions are elastic and passing lines through each other is cheaper
// than processing them.
//
// The switch is decided on counts only, never on timings, so that a run is
// bit-for-bit reproducible and resumable: at simulated times
// first_check * check_factor^k the engine looks at the stretch of collisions
// since the previous check, and hands over when the inelastic share of that
// stretch is at most max_inelastic_share. The hand-over passes the physical
// state: positions (from the same walk over the gaps that the event engine's
// output uses), velocities, particle order (line k starts at particle k), the
// time and the collision counts, so every observable at that moment is what
// the event engine reports, and every later one is what the pass-through
// engine, started from that state, reports. Both engines use the one
// collision rule (collision.hpp).
//
// Valid exactly where the pass-through engine is
// (PassThroughEngine::unsupported_reason); resolve_engine_name refuses the
// rest with one line.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "shockgas/engines/engine.hpp"
#include "event_engine.hpp"
#include "passthrough_engine.hpp"

namespace shockgas {

struct HybridSwitchRule {
    // Checks at first_check * check_factor^k in units of the run's time unit
    // L/N (time_unit, state.hpp; simulated time for the paper's L = N), so
    // that they scale with the ring. A check costs one window boundary of the
    // event engine (nothing measurable); the factor bounds how late a switch
    // can come to 25% of its time.
    double first_check = 1.0;
    double check_factor = 1.25;
    // Hand over when at most this share of the collisions since the previous
    // check was inelastic. measured() sets the measured crossover
    // (hybrid_engine.cpp, default_max_inelastic_share); 0 here, so a rule
    // built by hand without it switches only on stretches with no inelastic
    // collision at all.
    double max_inelastic_share = 0.0;

    static HybridSwitchRule measured();
};

class HybridEngine final : public Engine {
public:
    HybridEngine(const InitialCondition& initial, const CollisionModel& model, const CollapseCriterion& collapse,
                 LiveStatus* live = nullptr, const HybridSwitchRule& rule = HybridSwitchRule::measured());

    bool advance_to(double t) override;
    double time() const override;
    void clusters(ClusterState& out) const override;
    std::uint64_t collisions() const override;
    std::int64_t cluster_count() const override;
    const std::optional<CollapseReport>& collapse() const override { return no_collapse_; }
    std::string name() const override { return "hybrid"; }
    // Kind "hybrid": the phase, the next check and the counts at the last
    // one, and the inner engine's arrays under "inner_" names.
    std::optional<EngineSnapshot> snapshot() const override;
    void restore(const EngineSnapshot& snapshot) override;
    static constexpr const char* snapshot_kind = "hybrid";

    // For tests and the benchmark.
    bool switched() const { return passthrough_ != nullptr; }
    // The time of the hand-over (infinity before it).
    double switch_time() const override { return switch_time_; }
    std::uint64_t inelastic_collisions() const;

private:
    void hand_over();

    CollisionModel model_;
    LiveStatus* live_;
    HybridSwitchRule rule_;
    std::unique_ptr<EventEngine> event_;
    std::unique_ptr<PassThroughEngine> passthrough_;
    double next_check_;
    std::uint64_t collisions_at_check_ = 0;
    std::uint64_t inelastic_at_check_ = 0;
    double switch_time_ = std::numeric_limits<double>::infinity();
    std::optional<CollapseReport> no_collapse_;
};

}  // namespace shockgas
