// SPDX-License-Identifier: GPL-3.0-or-later
// The fast (windowed) engine against the reference global-order loop: the
// 4-ary queue pops in exactly the reference order, and every engine
// make_engine picks for "event" gives BIT-IDENTICAL states, collision counts
// and temperatures to ReferenceEventEngine, for several seeds and every collision mode
// (fast path and fallbacks alike).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../queue_workload.hpp"
#include "../test_support.hpp"

#include "shockgas/engines/engine.hpp"
#include "reference_event_engine.hpp"
#include "event_queue.hpp"
#include "event_engine.hpp"
#include "quaternary_heap.hpp"
#include "shockgas/model/observables.hpp"

namespace {

using shockgas::ClusterState;
using shockgas::CollisionModel;
using shockgas::ReferenceEventEngine;
using shockgas::EventEngine;
using shockgas::InitialCondition;
using shockgas::QuaternaryHeap;
using shockgas::SimulationParameters;
using shockgas::Subthreshold;

// The fast engine's heap against the reference engine's queue and the
// reference order, starting, as a block does, from a bulk load.
TEST(QuaternaryHeap, MatchesEventQueueOrderOnRandomWorkloads) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        shockgas::testing::QueueWorkload workload(seed, 700);
        QuaternaryHeap heap(workload.slots());
        shockgas::EventQueue queue(workload.slots());
        for (const auto& [slot, t] : workload.bulk_load()) {
            heap.append_unordered(slot, t);
            queue.schedule(slot, t);
        }
        heap.heapify();
        workload.run(20000, heap, queue);
        ASSERT_FALSE(HasFatalFailure()) << "seed " << seed;
    }
}

// pop_top_and_schedule, which both event loops on this heap use after an
// event (the event's pair leaves, its two neighbour pairs get new times),
// against a std::set of (time, slot) under random schedules, removals, pops
// and such updates, with exact ties common (times on a 1/8 grid) and slots
// absent or queued, times never, after the window's end or not, and a
// neighbour missing (-1).
TEST(QuaternaryHeap, TakingTheTopAndSchedulingTwoKeepsTheOrder) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        std::mt19937_64 rng(seed);
        const auto slots = static_cast<std::int32_t>(2 + rng() % 300);
        QuaternaryHeap heap(slots);
        std::set<std::pair<double, std::int32_t>> reference;
        std::vector<double> scheduled(static_cast<std::size_t>(slots), QuaternaryHeap::never);
        const auto grid_time = [&] { return std::uniform_int_distribution<int>(0, 64)(rng) / 8.0; };
        const auto set = [&](std::int32_t slot, double t) {
            double& current = scheduled[static_cast<std::size_t>(slot)];
            if (current != QuaternaryHeap::never) reference.erase({current, slot});
            if (t != QuaternaryHeap::never) reference.insert({t, slot});
            current = t;
        };
        const auto neighbour = [&] {
            const auto pick = rng() % 8;
            return pick == 0 ? std::int32_t{-1} : static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(slots));
        };
        int entered = 0;
        for (int op = 0; op < 20000; ++op) {
            const auto slot = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(slots));
            const auto action = rng() % 4;
            if (action <= 1) {
                const double t = grid_time();
                set(slot, t);
                heap.schedule(slot, t);
            } else if (action == 2 && !heap.empty()) {
                const std::int32_t a = neighbour();
                std::int32_t b = neighbour();
                if (b == a) b = -1;  // two distinct slots, or fewer
                const double ta = rng() % 4 == 0 ? QuaternaryHeap::never : grid_time();
                const double tb = rng() % 4 == 0 ? QuaternaryHeap::never : grid_time();
                const double due = rng() % 2 == 0 ? 8.0 : grid_time();  // the window's end
                const auto kept = [due](double t) { return t <= due ? t : QuaternaryHeap::never; };
                entered += (a >= 0 && kept(ta) != QuaternaryHeap::never && !heap.contains(a)) ? 1 : 0;
                set(reference.begin()->second, QuaternaryHeap::never);
                if (a >= 0) set(a, kept(ta));
                if (b >= 0) set(b, kept(tb));
                heap.pop_top_and_schedule(a, ta, b, tb, due);
            } else if (!heap.empty()) {
                set(reference.begin()->second, QuaternaryHeap::never);
                heap.pop_top();
            }
            ASSERT_EQ(heap.size(), reference.size()) << "seed " << seed << ", operation " << op;
            for (std::int32_t s = 0; s < slots; ++s)
                ASSERT_EQ(heap.contains(s), scheduled[static_cast<std::size_t>(s)] != QuaternaryHeap::never)
                    << "seed " << seed << ", operation " << op << ", slot " << s;
            if (reference.empty()) continue;
            ASSERT_EQ(heap.top_slot(), reference.begin()->second) << "seed " << seed << ", operation " << op;
            ASSERT_EQ(heap.top_time(), reference.begin()->first) << "seed " << seed << ", operation " << op;
        }
        EXPECT_GT(entered, 500) << "seed " << seed << ": a neighbour taking the top's place was hardly exercised";
    }
}

TEST(QuaternaryHeap, EmptyHeapReportsNever) {
    QuaternaryHeap heap(3);
    EXPECT_TRUE(heap.empty());
    EXPECT_EQ(heap.top_time(), QuaternaryHeap::never);
    heap.schedule(1, 2.0);
    heap.schedule(1, QuaternaryHeap::never);
    EXPECT_TRUE(heap.empty());
    EXPECT_FALSE(heap.contains(1));
}

using shockgas::testing::expect_identical;

struct Mode {
    const char* name;
    CollisionModel model;
    bool fast_path;  // whether make_engine must pick the event engine
};

// Runs make_engine("event") and the reference side by side and compares them
// at every sample time.
void compare(const Mode& mode, const InitialCondition& initial, const std::vector<double>& times) {
    SimulationParameters parameters;
    parameters.particles = initial.size();
    parameters.collision = mode.model;
    parameters.engine = "event";
    auto picked = shockgas::make_engine(parameters, initial, nullptr);
    EXPECT_EQ(dynamic_cast<EventEngine*>(picked.get()) != nullptr, mode.fast_path) << mode.name;
    ReferenceEventEngine reference(initial, mode.model, parameters.collapse);
    ClusterState fast_state;
    ClusterState reference_state;
    for (const double t : times) {
        const bool fast_ok = picked->advance_to(t);
        const bool reference_ok = reference.advance_to(t);
        const std::string where = std::string(mode.name) + " t=" + std::to_string(t);
        ASSERT_EQ(fast_ok, reference_ok) << where;
        ASSERT_EQ(picked->collisions(), reference.collisions()) << where;
        ASSERT_EQ(picked->cluster_count(), reference.cluster_count()) << where;
        ASSERT_EQ(picked->collapse().has_value(), reference.collapse().has_value()) << where;
        picked->clusters(fast_state);
        reference.clusters(reference_state);
        expect_identical(fast_state, reference_state, where);
        if (!reference_ok) break;
    }
    if (reference.collapse()) {
        EXPECT_EQ(picked->collapse()->time, reference.collapse()->time) << mode.name;
        EXPECT_EQ(picked->collapse()->left_slot, reference.collapse()->left_slot) << mode.name;
        EXPECT_EQ(picked->collapse()->cluster_mass, reference.collapse()->cluster_mass) << mode.name;
        EXPECT_EQ(picked->collapse()->relative_speed, reference.collapse()->relative_speed) << mode.name;
        EXPECT_EQ(picked->collapse()->criterion, reference.collapse()->criterion) << mode.name;
    }
}

const std::vector<double> sample_times = {0.0, 0.5, 1.0, 3.0, 10.0, 31.6, 100.0, 300.0};

TEST(EventEngine, BitIdenticalToReferenceInThePapersGas) {
    // r = 0.9, delta = 1e-2, elastic sub-threshold: the benchmark workload.
    const Mode mode{"r0.9-elastic", {0.9, 1e-2, Subthreshold::elastic}, true};
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
        compare(mode, shockgas::generate_initial_condition(20000, 20000.0, seed, 0), sample_times);
}

TEST(EventEngine, BitIdenticalToReferenceAtStrongInelasticity) {
    // r = 0.5 clusters strongly: long quiet stretches, dense clusters, cuts in
    // between, and many events on block boundaries.
    const Mode mode{"r0.5-elastic", {0.5, 5e-2, Subthreshold::elastic}, true};
    for (std::uint64_t seed = 4; seed <= 5; ++seed)
        compare(mode, shockgas::generate_initial_condition(10000, 10000.0, seed, 0), sample_times);
}

TEST(EventEngine, BitIdenticalToReferenceInTheStickyGas) {
    // r = 0: every collision merges; merges across block boundaries move the
    // cut pairs' left ends. Unequal masses appear at once.
    const Mode mode{"r0-sticky-gas", {0.0, 1e-2, Subthreshold::elastic}, true};
    for (std::uint64_t seed = 6; seed <= 8; ++seed)
        compare(mode, shockgas::generate_initial_condition(20000, 20000.0, seed, 0),
                {0.0, 1.0, 10.0, 100.0, 1000.0, 1e4, 1e5});
}

TEST(EventEngine, BitIdenticalFromRandomPositions) {
    // Non-lattice start (positions uniform on the ring, sorted): gaps of all
    // sizes from t = 0, including a ring seam inside a block.
    for (std::uint64_t seed = 9; seed <= 10; ++seed) {
        auto initial = shockgas::generate_initial_condition(5000, 5000.0, seed, 0);
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> where(0.0, 5000.0);
        for (double& x : initial.position) x = where(rng);
        std::sort(initial.position.begin(), initial.position.end());
        compare({"random-positions-r0.9", {0.9, 1e-2, Subthreshold::elastic}, true}, initial, sample_times);
        compare({"random-positions-r0", {0.0, 0.0, Subthreshold::elastic}, true}, initial, {1.0, 100.0, 1e4});
    }
}

TEST(EventEngine, FallsBackAndStaysIdenticalWhereWindowsCannotBeExact) {
    // Sticky sub-threshold with r > 0: unequal masses collide inelastically,
    // |v|max can grow, so make_engine keeps the global loop.
    compare({"r0.9-sticky", {0.9, 1e-2, Subthreshold::sticky}, false},
            shockgas::generate_initial_condition(5000, 5000.0, 11, 0), sample_times);
    // Unequal initial masses with r > 0.
    auto heavy = shockgas::generate_initial_condition(2000, 2000.0, 13, 0);
    heavy.mass[7] = 3.0;
    compare({"unequal-masses", {0.9, 1e-2, Subthreshold::elastic}, false}, heavy, sample_times);
}

// delta = 0: the first slow inelastic collision with three clusters in
// contact, in global time order, ends the run, and the ring at that instant
// is reported. The event engine goes back to its copy and runs that window
// as the global loop (event_engine.hpp), so the collapse report and the ring
// are the reference's bit for bit. Sizes and r chosen so that the runs
// collapse (r = 0.5 near t ~ 1-10 at N = 5000; r = 0.9, 0.99 later) after
// many windows, with the samples after the collapse checked too.
TEST(EventEngine, BitIdenticalThroughInelasticCollapse) {
    const std::vector<double> long_times = {0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5};
    std::uint64_t collapsed = 0;
    for (const double r : {0.5, 0.9, 0.99}) {
        for (std::uint64_t seed = 12; seed <= 13; ++seed) {
            const auto initial = shockgas::generate_initial_condition(5000, 5000.0, seed, 0);
            const std::string name = "delta0-r" + std::to_string(r) + "-seed" + std::to_string(seed);
            compare({name.c_str(), {r, 0.0, Subthreshold::elastic}, true}, initial, long_times);
            ReferenceEventEngine reference(initial, {r, 0.0, Subthreshold::elastic}, shockgas::CollapseCriterion{});
            reference.advance_to(long_times.back());
            collapsed += reference.collapse() ? 1 : 0;
        }
    }
    // The comparison is only a test of the collapse path if the reference collapsed.
    EXPECT_EQ(collapsed, 6u);
}

// A ring of a few particles at delta = 0 cools by Haff's law until pairs
// collide slower than the collapse speed with no third cluster in contact
// (not a collapse, ReferenceEventEngine's rule): the event engine goes back and runs
// those windows as the global loop, and goes on identically. A ring of 3 at
// r = 0.5 has pairs below 10^-12 by t ~ 10^12.
TEST(EventEngine, SlowPairsThatAreNoCollapseStayIdentical) {
    const std::vector<double> times = {1.0, 1e2, 1e4, 1e6, 1e8, 1e10, 1e12, 1e14, 1e16};
    for (const std::int64_t particles : {2, 3, 4}) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            const auto initial =
                shockgas::generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
            compare({"few-delta0-r0.5", {0.5, 0.0, Subthreshold::elastic}, true}, initial, times);
            // The path under test was taken: the reference cooled below the
            // collapse speed without collapsing (only 2 or 3 clusters to touch).
            ReferenceEventEngine reference(initial, {0.5, 0.0, Subthreshold::elastic}, shockgas::CollapseCriterion{});
            ASSERT_TRUE(reference.advance_to(times.back()));
            ClusterState state;
            reference.clusters(state);
            const auto [slowest, fastest] = std::minmax_element(state.velocity.begin(), state.velocity.end());
            EXPECT_LT(*fastest - *slowest, shockgas::CollapseCriterion{}.collapse_speed) << particles << " " << seed;
        }
    }
}

TEST(EventEngine, SmallRingsAreIdentical) {
    // Rings too small for more than one block run as one block (no cuts).
    for (const std::int64_t particles : {2, 3, 5, 50, 200}) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            const auto initial =
                shockgas::generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
            compare({"small-r0.9", {0.9, 1e-2, Subthreshold::elastic}, true}, initial, sample_times);
            compare({"small-r0", {0.0, 0.0, Subthreshold::elastic}, true}, initial, sample_times);
        }
    }
}

// A dense start (spacing 1e-6, velocities of order 1: a million collisions
// per particle per unit time) gets windows of its own scale from the first
// one on. With a first window of 0.05 fixed in time, as before, the whole run
// to t = 1e-2 (the same as t = 10^4 at unit spacing) was one window, and a real run of that kind
// answered neither Ctrl-C nor the progress line for minutes. Results are the
// reference's bit for bit, whatever the windows.
TEST(EventEngine, ADenseStartGetsWindowsOfItsOwnScale) {
    const std::int64_t particles = 100;
    const auto dense = shockgas::generate_initial_condition(particles, 1e-6 * particles, 14, 0);
    const CollisionModel model{0.9, 1e-2, Subthreshold::elastic};
    EventEngine engine(dense, model, shockgas::CollapseCriterion{});
    ASSERT_TRUE(engine.advance_to(1e-2));
    // About target_events_per_cluster (0.3) events per cluster per window
    // once adapted; 5 per cluster is far above that and far below the one
    // window holding every collision (> 30 per particle) of a fixed first window.
    constexpr double events_per_cluster_per_window_bound = 5.0;
    EXPECT_GT(engine.collisions(), 30u * particles);
    EXPECT_LT(static_cast<double>(engine.collisions()) / static_cast<double>(engine.windows()),
              events_per_cluster_per_window_bound * particles);
    compare({"dense-r0.9", model, true}, dense, {0.0, 1e-5, 1e-4, 1e-3, 1e-2});
}

}  // namespace
