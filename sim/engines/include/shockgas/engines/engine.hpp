// SPDX-License-Identifier: GPL-3.0-or-later
// The engine interface: advance one realization to a time, then report its
// clusters. Every engine implements it (event, reference event, exact,
// pass-through, hybrid; docs/engines.md), and programs choose one by name
// through the factory below, so the ensemble driver, the output and the
// analysis cannot tell which engine made a file.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "shockgas/model/parameters.hpp"
#include "shockgas/model/records.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas {

// Lets a long run be watched and stopped: the engine publishes its time and
// collision count every few thousand events and returns from advance_to when
// asked to stop (the user's Ctrl-C) or to pause (the driver wants a
// checkpoint). Either way it returns between two events, in a state that
// snapshot() captures exactly and from which advance_to can simply go on.
struct LiveStatus {
    std::atomic<double> time{0.0};
    std::atomic<std::uint64_t> collisions{0};
    const std::atomic<bool>* stop = nullptr;
    const std::atomic<bool>* abort = nullptr;  // the driver gives up (a checkpoint could not be written)
    const std::atomic<bool>* pause = nullptr;

    bool halt_requested() const {
        return (stop != nullptr && stop->load(std::memory_order_relaxed)) ||
               (abort != nullptr && abort->load(std::memory_order_relaxed)) ||
               (pause != nullptr && pause->load(std::memory_order_relaxed));
    }
};

// Thrown by advance_to when an engine meets a state it cannot decide exactly
// (the event engine's windows against an inelastic stall, where events crowd at
// one instant). The realization is then run again from its start by the engine
// make_fallback_engine builds, which decides it and matches the first engine
// bit for bit up to that point.
struct EngineUndecided : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Engine {
public:
    virtual ~Engine() = default;
    // Advances to time t (t >= current time). Returns false if the run stopped
    // earlier, because of collapse or because LiveStatus::stop was raised.
    virtual bool advance_to(double t) = 0;
    virtual double time() const = 0;
    virtual void clusters(ClusterState& out) const = 0;
    virtual std::uint64_t collisions() const = 0;
    virtual std::int64_t cluster_count() const = 0;
    virtual const std::optional<CollapseReport>& collapse() const = 0;
    virtual std::string name() const = 0;
    // When an engine that changes method mid-run (the hybrid engine) handed
    // over: +infinity while it has not; NaN for the engines that run one
    // method throughout. Written per realization as
    // /timeseries/engine_switch_time, so a file says which stretch of each
    // realization which method ran.
    virtual double switch_time() const { return std::numeric_limits<double>::quiet_NaN(); }
    // The state for a checkpoint, or nothing if this engine is cheap enough to
    // rerun from t = 0 instead (the exact engine).
    virtual std::optional<EngineSnapshot> snapshot() const { return std::nullopt; }
    // Replaces the state by a snapshot of an engine of the same kind built
    // from the same initial condition; throws InputError if it does not fit.
    virtual void restore(const EngineSnapshot& snapshot);
};

// The engine selected by parameters.engine ("auto" resolved here; see
// engine.cpp for the rule). `initial`, when known, is the run's start (an init
// file's masses decide whether the pass-through engine applies); without it
// the generated start (unit masses) is assumed.
std::unique_ptr<Engine> make_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                    LiveStatus* live);
std::string resolve_engine_name(const SimulationParameters& parameters, const InitialCondition* initial = nullptr);
// The engine that runs a realization again after its engine threw
// EngineUndecided: the reference event engine (the global event loop).
std::unique_ptr<Engine> make_fallback_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                             LiveStatus* live);
// The engine that can restore `snapshot` (snapshot.kind), built from the
// realization's initial condition and then restored.
std::unique_ptr<Engine> restore_engine(const EngineSnapshot& snapshot, const SimulationParameters& parameters,
                                       const InitialCondition& initial, LiveStatus* live);

}  // namespace shockgas
