// Helpers shared by the test executables (header only, tests only).
#pragma once

#include <utility>
#include <vector>

#include "shockgas/state.hpp"

namespace shockgas::testing {

// A hand-made ring: the given positions and velocities, unit masses.
inline InitialCondition unit_masses(double ring_length, std::vector<double> position, std::vector<double> velocity) {
    InitialCondition initial;
    initial.ring_length = ring_length;
    initial.position = std::move(position);
    initial.velocity = std::move(velocity);
    initial.mass.assign(initial.position.size(), 1.0);
    return initial;
}

}  // namespace shockgas::testing
