#include "shockgas/engine.hpp"

#include <fmt/format.h>

#include "shockgas/event_engine.hpp"
#include "shockgas/exact_engine.hpp"
#include "shockgas/fast_engine.hpp"
#include "shockgas/hybrid_engine.hpp"
#include "shockgas/passthrough_engine.hpp"

namespace shockgas {

// auto: the exact engine whenever it applies (r = 0: every collision merges,
// whatever the threshold), since it gives every observable the event engine
// gives there; the event engine otherwise. The pass-through engine is not
// chosen by auto: it is exact wherever PassThroughEngine::unsupported_reason is empty, but
// as measured (docs/passthrough-engine.md) it is faster than the windowed
// event engine only late in a run, when nearly all collisions are elastic,
// and several times slower in the inelastic early phase, so it is asked for
// by name. Nor the hybrid engine (event engine, then pass-through; same
// domain): measured 2026-11-23 (docs/passthrough-engine.md, "Hybrid") it is
// 1.05-1.10x faster than the event engine at r = 0.9, delta = 1e-2,
// N = 1e5 to t = 1e4 and 1.55x to t = 1e5, but where it never switches
// (Fig. 5's r = 0.99, delta = 1e-4, N = 2e4 to t = 1e4) its checks cost
// 0.7-2%, and in Fig. 5's setting the pass-through engine was measured 4.7x
// slower on a stretch at 2.2% inelastic collisions, just above the rule's 2%;
// auto must never be slower, so the hybrid engine too is asked for by name.
// Called on the main thread before any realization starts, so an impossible
// choice is one InputError.
std::string resolve_engine_name(const SimulationParameters& parameters, const InitialCondition* initial) {
    const bool sticky_gas = parameters.collision.restitution == 0.0;
    if (parameters.engine == "auto") return sticky_gas ? "exact" : "event";
    if (parameters.engine == "exact" && !sticky_gas)
        throw InputError(fmt::format("--engine exact solves only the sticky gas r = 0, got r = {}; use --engine "
                                     "event or auto",
                                     parameters.collision.restitution));
    if (parameters.engine == "passthrough" || parameters.engine == "hybrid") {
        // The init file's masses decide; the generated start has unit masses.
        // The hybrid engine hands over to the pass-through engine, so it
        // applies exactly where that one does.
        static const std::vector<double> unit_mass{1.0};
        const std::string refusal = PassThroughEngine::unsupported_reason(
            initial != nullptr ? initial->mass : unit_mass, parameters.collision, parameters.collapse);
        if (!refusal.empty()) throw InputError("--engine " + parameters.engine + " cannot run this: " + refusal);
    }
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
    else if (snapshot.kind == HybridEngine::snapshot_kind)
        engine = std::make_unique<HybridEngine>(initial, parameters.collision, parameters.collapse, live);
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
    if (name == "hybrid")
        return std::make_unique<HybridEngine>(initial, parameters.collision, parameters.collapse, live);
    throw InputError("engine '" + name + "' is not available in this build");
}

}  // namespace shockgas
