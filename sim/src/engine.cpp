#include "shockgas/engine.hpp"

#include "shockgas/event_engine.hpp"

namespace shockgas {

std::string resolve_engine_name(const SimulationParameters& parameters) {
    if (parameters.engine == "auto") return "event";
    return parameters.engine;
}

std::unique_ptr<Engine> make_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                    LiveStatus* live) {
    const std::string name = resolve_engine_name(parameters);
    if (name == "event") return std::make_unique<EventEngine>(initial, parameters.collision, parameters.collapse, live);
    throw InputError("engine '" + name + "' is not available in this build");
}

}  // namespace shockgas
