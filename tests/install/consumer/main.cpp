// SPDX-License-Identifier: GPL-3.0-or-later
// Runs one realization of the event engine through the installed library and
// prints T at t = 10 (r = 0.9, delta = 1e-2, N = 1000, seed 1).
#include <cstdio>

#include "shockgas/engines/engine.hpp"
#include "shockgas/model/observables.hpp"

int main() {
    shockgas::SimulationParameters parameters;
    parameters.particles = 1000;
    parameters.collision.restitution = 0.9;
    parameters.collision.velocity_threshold = 1e-2;
    const auto initial = shockgas::generate_initial_condition(parameters.particles, parameters.effective_ring_length(),
                                                              parameters.seed, 0);
    const auto engine = shockgas::make_engine(parameters, initial, nullptr);
    engine->advance_to(10.0);
    shockgas::ClusterState state;
    engine->clusters(state);
    const auto moments = shockgas::velocity_moments(state);
    std::printf("engine %s t %.17g collisions %llu T %.17g\n", engine->name().c_str(), engine->time(),
                static_cast<unsigned long long>(engine->collisions()), moments.temperature);
    return 0;
}
