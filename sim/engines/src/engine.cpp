// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/engines/engine.hpp"

#include <fmt/format.h>

#include "reference_event_engine.hpp"
#include "exact_engine.hpp"
#include "event_engine.hpp"
#include "hybrid_engine.hpp"
#include "passthrough_engine.hpp"

namespace shockgas {

// auto: the exact engine whenever it applies (r = 0: every collision merges,
// whatever the threshold), since it gives every observable the event engine
// gives there. Where the pass-through engine applies (equal masses, delta > 0,
// elastic sub-threshold collisions: PassThroughEngine::unsupported_reason is
// empty), the hybrid engine: the event engine (EventEngine) while many
// collisions are inelastic, the pass-through engine once at most 10% of them
// are (hybrid_engine.cpp, default_max_inelastic_share). Side by side with the
// event engine it took less CPU time on every workload measured where it
// switches (Figs. 4 and 5 among them; docs/measurements.md, "The hybrid
// engine"); where it never switches (short runs) it does the event engine's
// work plus one window boundary per check. Everywhere else (delta = 0, sticky
// sub-threshold, unequal masses) the event engine (windowed where
// EventEngine::supports, collapses included).
// Called on the main thread before any realization starts, so an impossible
// choice is one InputError.
std::string resolve_engine_name(const SimulationParameters& parameters, const InitialCondition* initial) {
    const bool sticky_gas = parameters.collision.restitution == 0.0;
    // The init file's masses decide; the generated start has unit masses.
    static const std::vector<double> unit_mass{1.0};
    const std::vector<double>& mass = initial != nullptr ? initial->mass : unit_mass;
    if (parameters.engine == "auto") {
        if (sticky_gas) return "exact";
        return PassThroughEngine::unsupported_reason(mass, parameters.collision, parameters.collapse).empty()
                   ? "hybrid"
                   : "event";
    }
    if (parameters.engine == "exact" && !sticky_gas)
        throw InputError(fmt::format("--engine exact solves only the sticky gas r = 0, got r = {}; use --engine "
                                     "event or auto",
                                     parameters.collision.restitution));
    if (parameters.engine == "passthrough" || parameters.engine == "hybrid") {
        // The hybrid engine hands over to the pass-through engine, so it
        // applies exactly where that one does.
        const std::string refusal =
            PassThroughEngine::unsupported_reason(mass, parameters.collision, parameters.collapse);
        if (!refusal.empty()) throw InputError("--engine " + parameters.engine + " cannot run this: " + refusal);
    }
    return parameters.engine;
}

void Engine::restore(const EngineSnapshot& snapshot) {
    throw InputError(fmt::format("checkpoint: the {} engine keeps no state to restore (got '{}')", name(),
                                 snapshot.kind));
}

// A snapshot names the class that wrote it: the event engine's and the
// reference loop's states differ (EventEngine's also carries its window
// history), and a realization may have fallen back to the reference loop.
std::unique_ptr<Engine> restore_engine(const EngineSnapshot& snapshot, const SimulationParameters& parameters,
                                       const InitialCondition& initial, LiveStatus* live) {
    std::unique_ptr<Engine> engine;
    if (snapshot.kind == EventEngine::snapshot_kind)
        engine = std::make_unique<EventEngine>(initial, parameters.collision, parameters.collapse, live);
    else if (snapshot.kind == ReferenceEventEngine::snapshot_kind)
        engine = std::make_unique<ReferenceEventEngine>(initial, parameters.collision, parameters.collapse, live);
    else if (snapshot.kind == PassThroughEngine::snapshot_kind)
        engine = std::make_unique<PassThroughEngine>(initial, parameters.collision, live);
    else if (snapshot.kind == HybridEngine::snapshot_kind)
        engine = std::make_unique<HybridEngine>(initial, parameters.collision, parameters.collapse, live);
    else
        throw InputError(fmt::format("checkpoint: unknown engine state kind '{}'", snapshot.kind));
    engine->restore(snapshot);
    return engine;
}

std::unique_ptr<Engine> make_fallback_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                             LiveStatus* live) {
    return std::make_unique<ReferenceEventEngine>(initial, parameters.collision, parameters.collapse, live);
}

std::unique_ptr<Engine> make_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                    LiveStatus* live) {
    const std::string name = resolve_engine_name(parameters, &initial);
    if (name == "event") {
        // The event engine gives bit-identical results, faster, wherever it
        // can be exact (EventEngine::supports); the global loop otherwise.
        if (EventEngine::supports(initial, parameters.collision, parameters.collapse))
            return std::make_unique<EventEngine>(initial, parameters.collision, parameters.collapse, live);
        return std::make_unique<ReferenceEventEngine>(initial, parameters.collision, parameters.collapse, live);
    }
    if (name == "reference")
        return std::make_unique<ReferenceEventEngine>(initial, parameters.collision, parameters.collapse, live);
    if (name == "exact") return std::make_unique<ExactEngine>(initial, live);
    if (name == "passthrough") return std::make_unique<PassThroughEngine>(initial, parameters.collision, live);
    if (name == "hybrid")
        return std::make_unique<HybridEngine>(initial, parameters.collision, parameters.collapse, live);
    throw InputError("engine '" + name + "' is not available in this build");
}

}  // namespace shockgas
