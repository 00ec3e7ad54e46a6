// SPDX-License-Identifier: GPL-3.0-or-later
// The drift measurement (drift.hpp) called as a library: its rounding
// bounds as formulas, a run of every equal-mass engine that stays within them,
// and a start off by 1e-9 that must not.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "drift.hpp"
#include "shockgas/model/parameters.hpp"

namespace {

using namespace shockgas;

SimulationParameters elastic_gas(const std::string& engine) {
    SimulationParameters p;
    p.particles = 1000;
    p.collision.restitution = 0.5;
    p.collision.velocity_threshold = 1e-2;
    p.seed = 1;
    p.engine = engine;
    return p;
}

// The elastic gas above delta loses energy at every inelastic collision: over 10^6 collisions E/E0 falls
// to 3.0e-4 (N = 1000, r = 0.5, seed 1). Below half means it fell, which "never rose"
// alone would not show, with room for any engine's own rounding of the same dynamics.
constexpr double energy_ratio_after_a_million_collisions_below = 0.5;

drift::DriftOptions short_run() {
    drift::DriftOptions o;
    o.target_collisions = 1e6;  // < 1 s on any engine; the ctest drift.check runs the same through the program
    o.record_every = 2e5;
    return o;
}

TEST(Drift, BoundsAreTheirFormulas) {
    // 2u per collision times m |v|max0 over S0 (momentum); 20 sqrt(3C) 2^-53 spacing (ring length);
    // 2u m |v|max^2 / E per collision plus 2 N 2^-64 (energy): the comments in drift.hpp derive them.
    EXPECT_DOUBLE_EQ(drift::momentum_rounding_bound(1e6, 1.0, 1.0, 500.0), 1e6 * 0x1p-52 / 500.0);
    EXPECT_DOUBLE_EQ(drift::ring_length_rounding_bound(1e6, 1.0), 20.0 * std::sqrt(3e6) * 0x1p-53);
    EXPECT_DOUBLE_EQ(drift::energy_rounding_bound(1e6, 1.0, 0.5, 100.0, 1000.0),
                     1e6 * 0x1p-52 * 0.25 / 100.0 + 2000.0 * 0x1p-64);
}

TEST(Drift, EveryEqualMassEngineStaysWithinTheRoundingBounds) {
    for (const char* engine : {"event", "passthrough", "hybrid"}) {
        const auto p = elastic_gas(engine);
        const auto o = short_run();
        int rows_heard = 0;
        drift::DriftListener listener;
        listener.row = [&](const drift::DriftRow&) { ++rows_heard; };
        const auto report = drift::run_drift(p, o, listener);
        EXPECT_TRUE(drift::check_failures(p, o, report).empty()) << engine;
        ASSERT_FALSE(report.rows.empty());
        const auto& last = report.rows.back();
        EXPECT_GE(last.collisions, o.target_collisions) << engine;
        EXPECT_LE(last.drift, last.bound) << engine;
        EXPECT_LT(last.energy_ratio, energy_ratio_after_a_million_collisions_below) << engine;
        EXPECT_EQ(last.order, 1.0) << engine;
        EXPECT_EQ(rows_heard, static_cast<int>(report.rows.size())) << engine;
    }
}

TEST(Drift, AMomentumLeakFailsTheCheck) {
    const auto p = elastic_gas("event");
    auto o = short_run();
    // 1e-9 is 2e-12 of S0 = sum |v0| ~ 500, above the bound 4.5e-13 of 10^6 collisions.
    o.inject_momentum_error = 1e-9;
    const auto failures = drift::check_failures(p, o, drift::run_drift(p, o));
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_NE(failures.front().find("momentum drift"), std::string::npos) << failures.front();
}

TEST(Drift, TheReferenceLoopKeepsTheRingLength) {
    auto p = elastic_gas("event");
    p.particles = 500;
    auto o = short_run();
    o.target_collisions = 3e5;
    o.reference = true;
    const auto report = drift::run_drift(p, o);
    EXPECT_TRUE(drift::check_failures(p, o, report).empty());
    EXPECT_LE(std::fabs(report.rows.back().ring_length_drift),
              drift::ring_length_rounding_bound(report.rows.back().collisions, report.spacing));
}

TEST(Drift, MergingRunsAreNotJudgedByTheseBounds) {
    auto p = elastic_gas("event");
    p.collision.restitution = 0.0;
    EXPECT_THROW(drift::require_checkable(p), InputError);
    p.collision.restitution = 0.5;
    p.collision.subthreshold = Subthreshold::sticky;
    EXPECT_THROW(drift::require_checkable(p), InputError);
}

}  // namespace
