// SPDX-License-Identifier: GPL-3.0-or-later
// The engine contract: what every engine behind the Engine interface
// (shockgas/engines/engine.hpp) promises, written once and run for each
// engine as make_engine builds it from parameters.engine (event, reference,
// exact, passthrough, hybrid):
//   * a snapshot restored into a fresh engine continues bit for bit; an engine
//     that keeps none (the exact engine) is rerun from t = 0 instead, as the
//     ensemble driver does, and gives the same bits;
//   * a snapshot of another engine is refused, naming both;
//   * pausing for checkpoints (the driver raising LiveStatus::pause, the
//     engine returning between two events) changes nothing, bit for bit;
//   * a pair touching and closing at t = 0 collides at the start time;
//   * total momentum is kept, kinetic energy never rises, and the clusters
//     stay in ring order, each up to a named rounding bound;
//   * the factory refuses what the engine cannot run with a one-line
//     InputError naming the reason, and builds it for the rest.
// Each engine's traits below say in which settings (N, r, delta, the
// sub-threshold rule, times) it is held to these. What only one engine does
// (its agreement with the reference loop, its own diagnostics) is tested in
// that engine's file.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../test_support.hpp"

#include "shockgas/engines/engine.hpp"
#include "shockgas/run/ensemble.hpp"
#include "event_engine.hpp"
#include "hybrid_engine.hpp"
#include "passthrough_engine.hpp"
#include "reference_event_engine.hpp"

// A named namespace (not an anonymous one): ctest's test names carry the
// traits type, EngineContract.SnapshotResumesBitForBit<engine_contract::Event>.
namespace engine_contract {

using shockgas::ClusterState;
using shockgas::CollapseCriterion;
using shockgas::CollisionModel;
using shockgas::Engine;
using shockgas::InitialCondition;
using shockgas::SimulationParameters;
using shockgas::Subthreshold;
using shockgas::testing::log_times;

// ---- Tolerances (all for the invariants run: N = 1000 to t = 3e4) ----------

// Rounding of momentum: N values of size <= 1, each collision exact up to an
// ulp; 1e-10 absolute is orders above that and far below a lost kick.
constexpr double momentum_tolerance = 1e-10;
// Energy may "rise" only by the rounding of a sum of 1000 squares.
constexpr double energy_rounding = 1e-14;
// Gaps are differences of positions computed from numbers of size <= L + |v| t
// ~ 1e3 to 1e4: their rounding is ~1e-12; a missed crossing or a cluster out
// of order would give -O(1).
constexpr double gap_tolerance = 1e-9;
// The sum of 1000 gaps of the pass-through engine's unwrapped lines: each
// rounded to ~1e-12, a missed or doubled line would move it by the spacing, 1.
constexpr double ring_length_tolerance = 1e-6;

// A snapshot run must go on for this many collisions after the checkpoint, or
// it compared too little to test anything.
constexpr std::uint64_t minimum_collisions_after_checkpoint = 100;

std::string at(double t) {
    std::ostringstream out;
    out << "t = " << t;
    return out.str();
}

SimulationParameters parameters(const std::string& engine, std::int64_t particles, const CollisionModel& collision) {
    SimulationParameters p;
    p.engine = engine;
    p.particles = particles;
    p.collision = collision;
    return p;
}

InitialCondition start_of(const SimulationParameters& p, std::uint64_t seed) {
    return shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), seed, 0);
}

// ---- What the traits give ---------------------------------------------------

// A run that is checkpointed: the engine made for `parameters` from
// realization 0 of `seed`, snapshotted at each of `checkpoints` (a fresh run
// each), then it and the engine restored from the snapshot advanced to each of
// `later`. `kind` is the snapshot's kind (empty for an engine that keeps none).
struct SnapshotCase {
    std::string name;
    SimulationParameters parameters;
    std::uint64_t seed;
    std::vector<double> checkpoints;
    std::vector<double> later;
    std::string kind;
};

// A run sampled at `times` (realization 0 of `seed`), with at least
// `minimum_collisions` collisions by the last, so that what is checked at the
// samples was checked over many.
struct Run {
    SimulationParameters parameters;
    std::uint64_t seed;
    std::vector<double> times;
    std::uint64_t minimum_collisions;
};

// The start-time collision in a model the engine runs, and the velocities
// and masses of the clusters just after it.
struct StartCollision {
    CollisionModel model;
    std::vector<double> velocity;
    std::vector<double> mass;
};

// A setting some engines cannot run.
struct Setting {
    const char* name;
    CollisionModel collision;
    double collapse_speed;
    bool unequal_masses;
};
const double default_collapse_speed = CollapseCriterion{}.collapse_speed;
const Setting sticky_gas{"r = 0", {0.0, 0.01, Subthreshold::elastic}, default_collapse_speed, false};
const Setting no_threshold{"delta = 0", {0.9, 0.0, Subthreshold::elastic}, default_collapse_speed, false};
const Setting sticky_subthreshold{"sticky sub-threshold", {0.9, 0.01, Subthreshold::sticky}, default_collapse_speed,
                                  false};
const Setting unequal_masses{"unequal masses", {0.9, 0.01, Subthreshold::elastic}, default_collapse_speed, true};
const Setting slow_collapse{"collapse speed above delta", {0.9, 0.01, Subthreshold::elastic}, 0.1, false};
const Setting strong_inelasticity{"r = 0.5", {0.5, 0.01, Subthreshold::elastic}, default_collapse_speed, false};
const Setting papers_gas{"r = 0.9, delta = 1e-2", {0.9, 0.01, Subthreshold::elastic}, default_collapse_speed, false};

// What the factory says to a setting: the start of its one-line refusal, or
// empty where it builds the engine.
struct FactoryAnswer {
    Setting setting;
    std::string refusal;
};

// ---- Settings shared by several engines -------------------------------------

// The event loops (windowed and plain) in every collision mode, N = 3000,
// seeds 1 to 3: checkpointed at t = 20 (delta = 0 collapses near t ~ 1-10 at
// this size: at t = 0.2 there) and compared to t = 200. `sticky_kind` is the
// snapshot's kind in the sticky sub-threshold gas, where the windowed engine
// falls back to the plain loop.
std::vector<SnapshotCase> event_loop_snapshot_cases(const std::string& engine, const std::string& kind,
                                                    const std::string& sticky_kind) {
    struct Mode {
        std::string name;
        CollisionModel model;
        double checkpoint;
        std::string kind;
    };
    const std::vector<Mode> modes = {{"r=0.5 elastic", {0.5, 1e-2, Subthreshold::elastic}, 20.0, kind},
                                     {"r=0.9 sticky sub-threshold", {0.9, 1e-2, Subthreshold::sticky}, 20.0, sticky_kind},
                                     {"r=0 sticky gas", {0.0, 1e-2, Subthreshold::elastic}, 20.0, kind},
                                     {"delta=0 before collapse", {0.5, 0.0, Subthreshold::elastic}, 0.2, kind}};
    std::vector<SnapshotCase> cases;
    for (const Mode& mode : modes)
        for (std::uint64_t seed = 1; seed <= 3; ++seed)
            cases.push_back({mode.name + ", seed " + std::to_string(seed), parameters(engine, 3000, mode.model), seed,
                             {mode.checkpoint}, {3.0 * mode.checkpoint, 200.0}, mode.kind});
    return cases;
}

// The paper's gas r = 0.9, delta = 1e-2 at N = 1000 (seed 99) to t = 3e4:
// over a million collisions, tens of thousands of them inelastic.
Run papers_gas_invariants(const std::string& engine) {
    return {parameters(engine, 1000, papers_gas.collision), 99, log_times(1.0, 3e4, 4), 1000000};
}

// Lines level and closing at the start, r = 0.5, delta = 0.1: g = 1 >= delta,
// so Eq. (1) leaves -0.25 and +0.25, exactly.
const StartCollision inelastic_bounce{{0.5, 0.1, Subthreshold::elastic}, {0.0, -0.25, 0.25}, {1.0, 1.0, 1.0}};

// At least `minimum` of the run's collisions were inelastic: the invariants
// were tested across the collisions that change them.
template <class Concrete>
void expect_inelastic_collisions(const Engine& engine, std::uint64_t minimum) {
    const auto* concrete = dynamic_cast<const Concrete*>(&engine);
    ASSERT_NE(concrete, nullptr) << "the factory built another engine";
    EXPECT_GT(concrete->inelastic_collisions(), minimum);
}

// The factory's answers for an engine that runs where the pass-through engine does.
std::vector<FactoryAnswer> passthrough_answers(const std::string& engine) {
    const std::string refused = "--engine " + engine + " cannot run this: ";
    return {{sticky_gas, refused + "r = 0"},
            {no_threshold, refused + "delta = 0"},
            {sticky_subthreshold, refused + "sticky"},
            {unequal_masses, refused + "unequal masses"},
            {slow_collapse, refused + "the collapse speed 0.1 exceeds delta = 0.01"},
            {papers_gas, ""}};
}

// The event loops run every setting (they are the factory's fallback).
const std::vector<FactoryAnswer> runs_everything = {
    {sticky_gas, ""}, {no_threshold, ""}, {sticky_subthreshold, ""}, {unequal_masses, ""}, {papers_gas, ""}};

// What an engine's traits (Self) give unless they say otherwise: a snapshot
// kept, one method throughout, the paper's gas for the invariants, the
// checkpoint test's ensemble, the inelastic bounce at the start time.
template <class Self>
struct Defaults {
    static constexpr bool keeps_snapshot = true;
    static constexpr bool switches = false;  // changes method mid-run (Engine::switch_time)
    // Pauses that must land inside an advance_to, between two events, in the
    // paused run (the invariants run unless the traits give a paused_run()):
    // a run of a few hundred milliseconds paused every millisecond has hundreds.
    static constexpr int minimum_pauses_between_events = 10;
    static Run invariants() { return papers_gas_invariants(Self::engine); }
    static SimulationParameters paused_ensemble() {
        SimulationParameters p = shockgas::testing::checkpoint_ensemble();
        p.engine = Self::engine;
        return p;
    }
    static StartCollision start_collision() { return inelastic_bounce; }
    // Checks of the engine's own diagnostics at each sample of the invariants
    // run, and after it.
    static void expect_own_invariants(const Engine&, const InitialCondition&, const std::string&) {}
    static void expect_substance(const Engine&) {}
};

// ---- One traits type per engine ---------------------------------------------
// engine: parameters.engine; name: Engine::name() of what the factory builds;
// foreign: an engine whose snapshot this one must refuse.

struct Event : Defaults<Event> {
    static constexpr const char* engine = "event";
    static constexpr const char* name = "event";
    static constexpr const char* foreign = "passthrough";
    static std::vector<SnapshotCase> snapshot_cases() {
        return event_loop_snapshot_cases(engine, shockgas::EventEngine::snapshot_kind,
                                         shockgas::ReferenceEventEngine::snapshot_kind);
    }
    static void expect_substance(const Engine& e) { expect_inelastic_collisions<shockgas::EventEngine>(e, 10000); }
    static std::vector<FactoryAnswer> factory_answers() { return runs_everything; }
};

// (It does not count inelastic collisions: no substance check beyond the count.)
struct Reference : Defaults<Reference> {
    static constexpr const char* engine = "reference";
    static constexpr const char* name = "event";
    static constexpr const char* foreign = "event";
    static std::vector<SnapshotCase> snapshot_cases() {
        return event_loop_snapshot_cases(engine, shockgas::ReferenceEventEngine::snapshot_kind,
                                         shockgas::ReferenceEventEngine::snapshot_kind);
    }
    // The paper's gas at N = 10^4 (the plain loop is the slower): still a few
    // hundred milliseconds per run, several checkpoints at 20 ms.
    static SimulationParameters paused_ensemble() {
        SimulationParameters p = Defaults::paused_ensemble();
        p.particles = 10000;
        return p;
    }
    static std::vector<FactoryAnswer> factory_answers() { return runs_everything; }
};

// Every collision of the sticky gas is inelastic: no substance check beyond the count.
struct Exact : Defaults<Exact> {
    static constexpr const char* engine = "exact";
    static constexpr const char* name = "exact";
    static constexpr bool keeps_snapshot = false;
    static constexpr const char* foreign = "reference";
    static std::vector<SnapshotCase> snapshot_cases() {
        std::vector<SnapshotCase> cases;
        for (std::uint64_t seed = 1; seed <= 3; ++seed)
            cases.push_back({"r=0 sticky gas, seed " + std::to_string(seed), parameters(engine, 3000, sticky_gas.collision),
                             seed, {20.0}, {60.0, 200.0}, ""});
        return cases;
    }
    // The sticky gas at N = 10^5: PAV over every cluster at each of the
    // driver's samples, a few hundred milliseconds per run.
    static SimulationParameters paused_ensemble() {
        SimulationParameters p = Defaults::paused_ensemble();
        p.collision = sticky_gas.collision;
        p.particles = 100000;
        return p;
    }
    // The sticky gas from the same start: by t = 3e4 nearly every particle
    // has merged into a few clusters (each merge one collision).
    static Run invariants() {
        return {parameters(engine, 1000, sticky_gas.collision), 99, log_times(1.0, 3e4, 4), 990};
    }
    // It looks for a pause only as a call starts (one call is one PAV over the
    // clusters, no events): the sticky gas at N = 10^5, sampled 16 times a
    // decade, so that pauses land between its calls.
    static Run paused_run() {
        return {parameters(engine, 100000, sticky_gas.collision), 99, log_times(1.0, 3e4, 16), 99000};
    }
    static constexpr int minimum_pauses_between_events = 0;
    // r = 0: the closing pair merges at once, mass 2, velocity (0.5 - 0.5)/2 = 0.
    static StartCollision start_collision() { return {sticky_gas.collision, {0.0, 0.0}, {1.0, 2.0}}; }
    static std::vector<FactoryAnswer> factory_answers() {
        const std::string refused = "--engine exact solves only the sticky gas r = 0, got r = 0.9";
        return {{sticky_gas, ""},
                {strong_inelasticity, "--engine exact solves only the sticky gas r = 0, got r = 0.5"},
                {no_threshold, refused},
                {sticky_subthreshold, refused},
                {unequal_masses, refused},
                {papers_gas, refused}};
    }
};

struct PassThrough : Defaults<PassThrough> {
    static constexpr const char* engine = "passthrough";
    static constexpr const char* name = "passthrough";
    static constexpr const char* foreign = "hybrid";
    // A checkpoint between steps (advance_to returns only between windows).
    static std::vector<SnapshotCase> snapshot_cases() {
        return {{"r=0.8 delta=0.02, seed 5", parameters(engine, 500, {0.8, 0.02, Subthreshold::elastic}), 5, {700.0},
                 {1000.0, 2000.0}, shockgas::PassThroughEngine::snapshot_kind}};
    }
    static SimulationParameters paused_ensemble() {
        SimulationParameters p = shockgas::testing::elastic_ensemble(5000, 2000.0, engine);
        p.threads = 2;
        return p;
    }
    static void expect_substance(const Engine& e) {
        expect_inelastic_collisions<shockgas::PassThroughEngine>(e, 10000);
    }
    // Its lines, unwrapped: never out of order beyond rounding, and one ring
    // round (clusters() wraps positions, so a line that missed or doubled a
    // winding shows only here).
    static void expect_own_invariants(const Engine& e, const InitialCondition& start, const std::string& where) {
        const auto gaps = dynamic_cast<const shockgas::PassThroughEngine&>(e).gaps();
        EXPECT_GE(*std::min_element(gaps.begin(), gaps.end()), -gap_tolerance) << where;
        EXPECT_NEAR(std::accumulate(gaps.begin(), gaps.end(), 0.0), start.ring_length, ring_length_tolerance) << where;
    }
    static std::vector<FactoryAnswer> factory_answers() { return passthrough_answers(engine); }
};

struct Hybrid : Defaults<Hybrid> {
    static constexpr const char* engine = "hybrid";
    static constexpr const char* name = "hybrid";
    static constexpr bool switches = true;
    static constexpr const char* foreign = "passthrough";
    // Checkpointed before the switch (the event engine's state and the rule's
    // counts) and after it (the pass-through engine's): with the measured rule
    // this run hands over at t ~ 414.
    static std::vector<SnapshotCase> snapshot_cases() {
        return {{"r=0.8 delta=0.02, seed 9", parameters(engine, 1000, {0.8, 0.02, Subthreshold::elastic}), 9,
                 {100.0, 1000.0}, {2000.0, 3000.0}, shockgas::HybridEngine::snapshot_kind}};
    }
    // The measured rule switches at t ~ 5e3 here, so pauses fall on both sides.
    static SimulationParameters paused_ensemble() {
        SimulationParameters p = shockgas::testing::elastic_ensemble(5000, 12000.0, engine);
        p.threads = 2;
        return p;
    }
    static void expect_substance(const Engine& e) { expect_inelastic_collisions<shockgas::HybridEngine>(e, 10000); }
    static std::vector<FactoryAnswer> factory_answers() { return passthrough_answers(engine); }
};

// ---- The contract -------------------------------------------------------------

template <class Traits>
class EngineContract : public ::testing::Test {};

using Engines = ::testing::Types<Event, Reference, Exact, PassThrough, Hybrid>;

TYPED_TEST_SUITE(EngineContract, Engines);

void expect_same_engine_state(const Engine& a, const Engine& b, const std::string& where) {
    EXPECT_EQ(a.time(), b.time()) << where;
    shockgas::testing::expect_identical(a, b, where);
    EXPECT_TRUE(shockgas::testing::same({a.switch_time()}, {b.switch_time()})) << where;
}

// Snapshot, restore into a fresh engine (restore_engine, as a resumed run
// does), and both go on alike bit for bit: every cluster's position, velocity
// and mass, the collision count, the time, the switch time, at the
// checkpoint and at each later time. An engine that keeps no snapshot is
// rerun from t = 0 through the same calls.
TYPED_TEST(EngineContract, SnapshotResumesBitForBit) {
    for (const SnapshotCase& c : TypeParam::snapshot_cases()) {
        const SimulationParameters& p = c.parameters;
        const InitialCondition initial = start_of(p, c.seed);
        bool before_switch = false;
        bool after_switch = false;
        for (const double checkpoint : c.checkpoints) {
            const std::string what = c.name + ", checkpoint at " + at(checkpoint);
            auto original = shockgas::make_engine(p, initial, nullptr);
            ASSERT_EQ(original->name(), TypeParam::name) << what;
            ASSERT_TRUE(original->advance_to(checkpoint)) << what;
            const std::uint64_t collisions_at_checkpoint = original->collisions();
            const auto snapshot = original->snapshot();
            std::unique_ptr<Engine> resumed;
            if constexpr (TypeParam::keeps_snapshot) {
                ASSERT_TRUE(snapshot.has_value()) << what;
                EXPECT_EQ(snapshot->kind, c.kind) << what;
                resumed = shockgas::restore_engine(*snapshot, p, initial, nullptr);
            } else {
                ASSERT_FALSE(snapshot.has_value()) << what;
                resumed = shockgas::make_engine(p, initial, nullptr);
                ASSERT_TRUE(resumed->advance_to(checkpoint)) << what;
            }
            EXPECT_EQ(resumed->name(), original->name()) << what;
            expect_same_engine_state(*original, *resumed, what + " (at the checkpoint)");
            if constexpr (TypeParam::switches) {
                before_switch = before_switch || original->switch_time() == std::numeric_limits<double>::infinity();
                after_switch = after_switch || original->switch_time() <= checkpoint;
            } else {
                EXPECT_TRUE(std::isnan(original->switch_time())) << what << ": an engine that never switches";
            }
            for (const double t : c.later) {
                const bool original_ran = original->advance_to(t);
                const bool resumed_ran = resumed->advance_to(t);
                EXPECT_EQ(original_ran, resumed_ran) << what << ", " << at(t);
                EXPECT_EQ(original->collapse().has_value(), resumed->collapse().has_value()) << what << ", " << at(t);
                expect_same_engine_state(*original, *resumed, what + ", " + at(t));
            }
            EXPECT_GT(original->collisions(), collisions_at_checkpoint + minimum_collisions_after_checkpoint)
                << what << ": too few events to test";
        }
        if constexpr (TypeParam::switches) {
            EXPECT_TRUE(before_switch) << c.name << ": no checkpoint before the switch";
            EXPECT_TRUE(after_switch) << c.name << ": no checkpoint after the switch";
        }
    }
}

// A snapshot of another engine (another kind) is refused by restore, with one
// line naming its kind and this engine.
TYPED_TEST(EngineContract, RefusesAnotherEnginesSnapshot) {
    const Run run = TypeParam::invariants();
    const InitialCondition initial = start_of(run.parameters, run.seed);
    SimulationParameters other = run.parameters;
    other.engine = TypeParam::foreign;
    auto foreign = shockgas::make_engine(other, initial, nullptr);
    ASSERT_TRUE(foreign->advance_to(1.0));
    const auto snapshot = foreign->snapshot();
    ASSERT_TRUE(snapshot.has_value());
    auto engine = shockgas::make_engine(run.parameters, initial, nullptr);
    try {
        engine->restore(*snapshot);
        ADD_FAILURE() << "a snapshot of kind '" << snapshot->kind << "' was restored";
    } catch (const shockgas::InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("'" + snapshot->kind + "'"), std::string::npos) << message;
        EXPECT_NE(message.find(engine->name() + " engine"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// Through the ensemble driver: a run paused for checkpoints every 20 ms (the
// driver raises LiveStatus::pause, takes a snapshot and goes on) gives bit for
// bit the result of the run that never paused, and each realization records
// its switch time.
TYPED_TEST(EngineContract, CheckpointPausesChangeNothing) {
    const SimulationParameters p = TypeParam::paused_ensemble();
    std::vector<double> switch_times;
    if constexpr (TypeParam::switches) {
        for (std::int64_t k = 0; k < p.realizations; ++k) {
            // The switch comes within the run, so pauses fall on both sides of it.
            auto probe = shockgas::make_engine(
                p, shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), p.seed, k), nullptr);
            ASSERT_TRUE(probe->advance_to(p.t_max));
            ASSERT_LT(probe->switch_time(), 0.8 * p.t_max);
            switch_times.push_back(probe->switch_time());
        }
    } else {
        switch_times.assign(static_cast<std::size_t>(p.realizations), std::numeric_limits<double>::quiet_NaN());
    }
    const auto [reference, paused] =
        shockgas::testing::run_with_and_without_checkpoint_pauses(p, std::string("contract_") + TypeParam::engine);
    shockgas::testing::expect_same_result(reference, paused);
    EXPECT_EQ(reference.engine, TypeParam::engine);
    EXPECT_TRUE(shockgas::testing::same(reference.engine_switch_time, switch_times));
}

// Raises `pause` every `period` from its own thread, as the ensemble driver
// asks its realizations for checkpoints, until destroyed.
class PauseTimer {
public:
    explicit PauseTimer(std::chrono::microseconds period)
        : thread_([this, period] {
              while (!done_.load()) {
                  std::this_thread::sleep_for(period);
                  pause.store(true);
              }
          }) {}
    ~PauseTimer() {
        done_.store(true);
        thread_.join();
    }
    PauseTimer(const PauseTimer&) = delete;
    PauseTimer& operator=(const PauseTimer&) = delete;

    std::atomic<bool> pause{false};

private:
    std::atomic<bool> done_{false};
    std::thread thread_;
};

// A pause every millisecond: hundreds in a run of a few hundred milliseconds.
constexpr std::chrono::microseconds pause_period{1000};

// The engine alone, paused through LiveStatus::pause every millisecond: each
// time advance_to returns between two events, its state is snapshotted (as
// the driver's checkpoint does) and the same advance_to is called again. At
// every sample it is bit for bit the engine that was never paused. (Through
// the driver, above, most pauses land between samples instead.)
TYPED_TEST(EngineContract, PausingBetweenEventsChangesNothing) {
    Run run = TypeParam::invariants();
    if constexpr (requires { TypeParam::paused_run(); }) run = TypeParam::paused_run();
    const InitialCondition start = start_of(run.parameters, run.seed);
    PauseTimer timer(pause_period);
    shockgas::LiveStatus live;
    live.pause = &timer.pause;
    auto paused = shockgas::make_engine(run.parameters, start, &live);
    auto straight = shockgas::make_engine(run.parameters, start, nullptr);
    int pauses = 0;
    int pauses_between_events = 0;
    for (const double t : run.times) {
        for (;;) {
            const std::uint64_t collisions_before = paused->collisions();
            if (paused->advance_to(t)) break;
            ASSERT_FALSE(paused->collapse().has_value()) << at(t);
            ++pauses;
            if (paused->collisions() > collisions_before && paused->time() < t) ++pauses_between_events;
            EXPECT_EQ(paused->snapshot().has_value(), TypeParam::keeps_snapshot) << at(t);
            timer.pause.store(false);
        }
        ASSERT_TRUE(straight->advance_to(t)) << at(t);
        expect_same_engine_state(*straight, *paused, at(t));
        if (::testing::Test::HasFatalFailure()) return;
    }
    std::printf("%s: %d pauses, %d of them inside an advance_to between events\n", TypeParam::engine, pauses,
                pauses_between_events);
    EXPECT_GT(straight->collisions(), run.minimum_collisions);
    EXPECT_GE(pauses, 2) << "the run ended before it was paused: the test did not test";
    EXPECT_GE(pauses_between_events, TypeParam::minimum_pauses_between_events);
}

// Two particles level and closing at t = 0 collide at the start time, and the
// state at a sample includes every collision at its time: the sample at t = 0
// holds that one collision, as the reference loop's does.
TYPED_TEST(EngineContract, CollidesAtTheStartTime) {
    const StartCollision expected = TypeParam::start_collision();
    const InitialCondition start = shockgas::testing::unit_masses(3.0, {0.5, 1.0, 1.0}, {0.0, 0.5, -0.5});
    SimulationParameters p = parameters(TypeParam::engine, 3, expected.model);
    p.ring_length = start.ring_length;
    auto engine = shockgas::make_engine(p, start, nullptr);
    shockgas::ReferenceEventEngine reference(start, expected.model, CollapseCriterion{});
    ASSERT_TRUE(engine->advance_to(0.0));
    ASSERT_TRUE(reference.advance_to(0.0));
    EXPECT_EQ(engine->collisions(), 1u);
    EXPECT_EQ(reference.collisions(), 1u);
    ClusterState mine;
    ClusterState theirs;
    engine->clusters(mine);
    reference.clusters(theirs);
    EXPECT_EQ(mine.velocity, theirs.velocity);
    EXPECT_EQ(mine.velocity, expected.velocity);
    EXPECT_EQ(mine.mass, expected.mass);
}

// Clusters in ring order: from cluster 0 (the one holding the smallest
// particle index) the positions, wrapped into [0, L), rise, drop once where
// the ring's seam falls, and rise again to at most the first position. Any
// cluster out of order makes a second drop, or a last position past the
// first; overlaps within rounding are allowed.
void expect_ring_order(const ClusterState& state, double ring_length, const std::string& where) {
    const std::size_t n = state.size();
    ASSERT_GT(n, 0u) << where;
    int seams = 0;
    for (std::size_t k = 0; k < n; ++k) {
        ASSERT_GE(state.position[k], 0.0) << where << ", cluster " << k;
        ASSERT_LT(state.position[k], ring_length) << where << ", cluster " << k;
        if (k == 0) continue;
        ASSERT_GT(state.first_particle[k], state.first_particle[k - 1]) << where << ", cluster " << k;
        if (state.position[k] < state.position[k - 1] - gap_tolerance) ++seams;
    }
    ASSERT_LE(seams, 1) << where << ": the positions drop more than once round the ring";
    if (seams == 1) {
        ASSERT_LE(state.position[n - 1], state.position[0] + gap_tolerance)
            << where << ": the last cluster is past the first one round the ring";
    }
}

// Momentum kept, kinetic energy never rising, the ring in order, at every
// sample of a run of many collisions (an inelastic gas).
TYPED_TEST(EngineContract, KeepsMomentumLosesEnergyAndStaysInRingOrder) {
    const Run run = TypeParam::invariants();
    const InitialCondition start = start_of(run.parameters, run.seed);
    auto engine = shockgas::make_engine(run.parameters, start, nullptr);
    const auto momentum_of = [](const std::vector<double>& v, const std::vector<double>& m) {
        return std::inner_product(v.begin(), v.end(), m.begin(), 0.0);
    };
    const auto energy_of = [](const std::vector<double>& v, const std::vector<double>& m) {
        double e = 0.0;
        for (std::size_t k = 0; k < v.size(); ++k) e += m[k] * v[k] * v[k];
        return e;
    };
    const double momentum = momentum_of(start.velocity, start.mass);
    double energy = energy_of(start.velocity, start.mass);
    for (const double t : run.times) {
        const std::string where = at(t);
        ASSERT_TRUE(engine->advance_to(t)) << where;
        ClusterState state;
        engine->clusters(state);
        EXPECT_NEAR(momentum_of(state.velocity, state.mass), momentum, momentum_tolerance) << where;
        const double e = energy_of(state.velocity, state.mass);
        EXPECT_LE(e, energy * (1.0 + energy_rounding)) << where;
        energy = e;
        expect_ring_order(state, start.ring_length, where);
        TypeParam::expect_own_invariants(*engine, start, where);
    }
    EXPECT_GT(engine->collisions(), run.minimum_collisions);
    TypeParam::expect_substance(*engine);
}

// The factory (make_engine, and resolve_engine_name with it) refuses each
// setting the engine cannot run with one line that starts by naming the
// engine and the reason; the rest it builds, and validation accepts them too.
TYPED_TEST(EngineContract, FactoryRefusesWhatItCannotRunNamingTheReason) {
    const auto refusal = [](const auto& call) -> std::string {
        try {
            call();
        } catch (const shockgas::InputError& error) {
            return error.what();
        }
        return "";
    };
    for (const auto& [setting, expected] : TypeParam::factory_answers()) {
        SimulationParameters p = parameters(TypeParam::engine, 10, setting.collision);
        p.collapse.collapse_speed = setting.collapse_speed;
        InitialCondition start = start_of(p, 1);
        if (setting.unequal_masses) start.mass[3] = 2.0;
        // Without an initial condition the generated start (unit masses) is assumed.
        const InitialCondition* known = setting.unequal_masses ? &start : nullptr;
        const std::string resolved = refusal([&] { shockgas::resolve_engine_name(p, known); });
        const std::string made = refusal([&] { shockgas::make_engine(p, start, nullptr); });
        if (expected.empty()) {
            EXPECT_EQ(resolved, "") << setting.name;
            EXPECT_EQ(made, "") << setting.name;
            EXPECT_EQ(shockgas::make_engine(p, start, nullptr)->name(), TypeParam::name) << setting.name;
            EXPECT_NO_THROW(shockgas::validate(p)) << setting.name;
        } else {
            EXPECT_EQ(made.rfind(expected, 0), 0u) << setting.name << ": " << made;
            EXPECT_EQ(made.find('\n'), std::string::npos) << setting.name << ": " << made;
            EXPECT_EQ(resolved, made) << setting.name;
        }
    }
}

}  // namespace engine_contract
