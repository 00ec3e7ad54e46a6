// SPDX-License-Identifier: GPL-3.0-or-later
// The open-line sticky solver on the one PAV (sim/model/include/shockgas/model/pav.hpp).
#include "shockgas/model/pav.hpp"

#include <algorithm>
#include <stdexcept>

namespace shockgas {

void sticky_clusters_on_line(std::span<const double> position, std::span<const double> velocity, double t,
                             std::vector<LineCluster>& clusters) {
    if (position.size() != velocity.size())
        throw std::invalid_argument("sticky_clusters_on_line: positions and velocities differ in number");
    clusters.resize(position.size());
    for (std::size_t i = 0; i < position.size(); ++i) clusters[i] = {i, 1, 1.0, position[i], velocity[i]};
    // Violators: the left cluster's centre of mass at t is beyond the right
    // one's, or they touch at t while approaching (Y_A - Y_B compared as
    // M_B (X_A + t P_A) - M_A (X_B + t P_B) to avoid two divisions).
    auto must_pool = [t](const LineCluster& left, const LineCluster& right) {
        const double left_y = left.first_moment + t * left.momentum;
        const double right_y = right.first_moment + t * right.momentum;
        const double overlap = right.mass * left_y - left.mass * right_y;
        if (overlap != 0.0) return overlap > 0.0;
        return left.momentum * right.mass > right.momentum * left.mass;
    };
    // Perfectly inelastic merger (collision.hpp merge(): mass, momentum and
    // first moment add).
    auto pooled = [](const LineCluster& left, const LineCluster& right) {
        return LineCluster{left.first, left.count + right.count, left.mass + right.mass,
                           left.first_moment + right.first_moment, left.momentum + right.momentum};
    };
    pool_adjacent_violators(clusters, must_pool, pooled);
}

const LineCluster& cluster_holding(const std::vector<LineCluster>& clusters, std::size_t tagged) {
    // Clusters are in order of their first particle: the holder is the last
    // one that starts at or before the tagged particle.
    auto after = std::upper_bound(clusters.begin(), clusters.end(), tagged,
                                  [](std::size_t index, const LineCluster& c) { return index < c.first; });
    if (after == clusters.begin()) throw std::out_of_range("cluster_holding: no cluster holds that particle");
    return *(after - 1);
}

}  // namespace shockgas
