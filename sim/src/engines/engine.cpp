#include "shockgas/engine.hpp"

#include <fmt/format.h>

#include "shockgas/event_engine.hpp"
#include "shockgas/exact_engine.hpp"
#include "shockgas/fast_engine.hpp"
#include "shockgas/passthrough_engine.hpp"

namespace shockgas {

namespace {
// The masses the run will start from: the init file's, or unit masses.
InitialCondition masses_of(const SimulationParameters& parameters, const InitialCondition* initial) {
    if (initial != nullptr) return *initial;
    InitialCondition unit;
    unit.mass.assign(2, 1.0);
    (void)parameters;
    return unit;
}
}  // namespace

// auto: the exact engine whenever it applies (r = 0: every collision merges,
// whatever the threshold), since it gives every observable the event engine
// gives there; the pass-through engine wherever it is exact (equal masses,
// elastic sub-threshold, delta > 0: PassThroughEngine::supports), since it
// skips the elastic collisions; the event engine otherwise. Called on the
// main thread before any realization starts, so an impossible choice is one
// InputError.
std::string resolve_engine_name(const SimulationParameters& parameters, const InitialCondition* initial) {
    const bool sticky_gas = parameters.collision.restitution == 0.0;
    const InitialCondition start = masses_of(parameters, initial);
    const std::string passthrough_refusal =
        PassThroughEngine::unsupported_reason(start, parameters.collision, parameters.collapse);
    if (parameters.engine == "auto") {
        if (sticky_gas) return "exact";
        return passthrough_refusal.empty() ? "passthrough" : "event";
    }
    if (parameters.engine == "exact" && !sticky_gas)
        throw InputError(fmt::format("--engine exact solves only the sticky gas r = 0, got r = {}; use --engine "
                                     "event or auto",
                                     parameters.collision.restitution));
    if (parameters.engine == "passthrough" && !passthrough_refusal.empty())
        throw InputError("--engine passthrough cannot run this: " + passthrough_refusal);
    return parameters.engine;
}

void Engine::restore(const EngineSnapshot& snapshot) {
    throw InputError(fmt::format("checkpoint: the {} engine keeps no state to restore (got '{}')", name(),
                                 snapshot.kind));
}

// A snapshot names the class that wrote it: the windowed engine's and the
// reference loop's states differ (the windowed one also carries its window
// history), and a realization may have fallen back to the reference loop.
std::unique_ptr<Engine> restore_engine(const EngineSnapshot& snapshot, const SimulationParameters& parameters,
                                       const InitialCondition& initial, LiveStatus* live) {
    std::unique_ptr<Engine> engine;
    if (snapshot.kind == FastEventEngine::snapshot_kind)
        engine = std::make_unique<FastEventEngine>(initial, parameters.collision, parameters.collapse, live);
    else if (snapshot.kind == EventEngine::snapshot_kind)
        engine = std::make_unique<EventEngine>(initial, parameters.collision, parameters.collapse, live);
    else if (snapshot.kind == PassThroughEngine::snapshot_kind)
        engine = std::make_unique<PassThroughEngine>(initial, parameters.collision, live);
    else
        throw InputError(fmt::format("checkpoint: unknown engine state kind '{}'", snapshot.kind));
    engine->restore(snapshot);
    return engine;
}

std::unique_ptr<Engine> make_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                    LiveStatus* live) {
    const std::string name = resolve_engine_name(parameters, &initial);
    if (name == "event") {
        // The windowed engine gives bit-identical results, faster, wherever it
        // can be exact (FastEventEngine::supports); the global loop otherwise.
        if (FastEventEngine::supports(initial, parameters.collision, parameters.collapse))
            return std::make_unique<FastEventEngine>(initial, parameters.collision, parameters.collapse, live);
        return std::make_unique<EventEngine>(initial, parameters.collision, parameters.collapse, live);
    }
    if (name == "exact") return std::make_unique<ExactEngine>(initial, live);
    if (name == "passthrough") return std::make_unique<PassThroughEngine>(initial, parameters.collision, live);
    throw InputError("engine '" + name + "' is not available in this build");
}

}  // namespace shockgas
