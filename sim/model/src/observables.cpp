// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/model/observables.hpp"

#include <algorithm>
#include <cmath>

namespace shockgas {

Moments velocity_moments(const std::vector<double>& velocity, const std::vector<double>& mass,
                         double frame_velocity) {
    CompensatedSum total_mass, momentum;
    for (std::size_t i = 0; i < velocity.size(); ++i) {
        total_mass.add(mass[i]);
        momentum.add(mass[i] * velocity[i]);
    }
    Moments moments;
    moments.total_mass = total_mass.value();
    moments.frame_mean_velocity = momentum.value() / moments.total_mass;
    // In the frame at rest nothing is added, so the lab numbers are the
    // frame's bit for bit.
    const bool at_rest = frame_velocity == 0.0;
    moments.mean_velocity = at_rest ? moments.frame_mean_velocity : frame_velocity + moments.frame_mean_velocity;
    CompensatedSum fluctuation, energy;
    for (std::size_t i = 0; i < velocity.size(); ++i) {
        const double deviation = velocity[i] - moments.frame_mean_velocity;
        fluctuation.add(mass[i] * deviation * deviation);
        const double lab = at_rest ? velocity[i] : frame_velocity + velocity[i];
        energy.add(mass[i] * lab * lab);
    }
    moments.temperature = fluctuation.value() / moments.total_mass;
    moments.kinetic_energy = 0.5 * energy.value() / moments.total_mass;
    return moments;
}

std::vector<double> histogram_edges(double time, int bins, double range) {
    std::vector<double> edges(static_cast<std::size_t>(bins) + 1);
    const double velocity_scale = std::cbrt(1.0 / time);  // t^(-1/3)
    for (int k = 0; k <= bins; ++k)
        edges[static_cast<std::size_t>(k)] = (-range + 2.0 * range * k / bins) * velocity_scale;
    return edges;
}

void accumulate_histogram(const ClusterState& state, double frame_mean_velocity, const std::vector<double>& edges,
                          std::vector<double>& counts) {
    const std::size_t bins = edges.size() - 1;
    counts.resize(bins + 2, 0.0);
    for (std::size_t i = 0; i < state.size(); ++i) {
        const double v = state.velocity[i] - frame_mean_velocity;
        std::size_t index;
        if (v < edges.front()) {
            index = 0;
        } else if (v >= edges.back()) {
            index = bins + 1;
        } else {
            // upper_bound finds the first edge above v; bin k covers [edges[k-1], edges[k]).
            index = static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
        }
        counts[index] += state.mass[i];
    }
}

}  // namespace shockgas
