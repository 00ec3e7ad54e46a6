// SPDX-License-Identifier: GPL-3.0-or-later
// The one PAV (shockgas/model/pav.hpp) on the open line: cases solved by hand, and
// agreement with the exact engine on the ring for clusters far from the seam.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "../test_support.hpp"

#include "exact_engine.hpp"
#include "shockgas/model/pav.hpp"
#include "shockgas/model/state.hpp"

namespace {

using shockgas::LineCluster;

TEST(OpenLinePav, ThreeConvergingParticlesMergeOnlyAfterContact) {
    // x = (0, 1, 2), v = (1, 0, -1): y = x + t v = (t, 1, 2 - t). At t = 0.6
    // nobody has met; at t = 1 all three meet at x = 1 (touching while
    // approaching is merged, the exact engine's convention) with V = 0.
    const std::vector<double> x{0.0, 1.0, 2.0}, v{1.0, 0.0, -1.0};
    std::vector<LineCluster> clusters;
    shockgas::sticky_clusters_on_line(x, v, 0.6, clusters);
    EXPECT_EQ(clusters.size(), 3u);
    shockgas::sticky_clusters_on_line(x, v, 1.0, clusters);
    ASSERT_EQ(clusters.size(), 1u);
    EXPECT_EQ(clusters[0].count, 3u);
    EXPECT_EQ(clusters[0].velocity(), 0.0);
    EXPECT_EQ(clusters[0].position(1.0), 1.0);
    EXPECT_EQ(shockgas::cluster_holding(clusters, 2).first, 0u);
}

TEST(OpenLinePav, FastParticlesCatchTheSlowOneTogether) {
    // x = (0, 1, 2), v = (2, 1, 0): y = (2t, 1 + t, 2), all three meet at
    // x = 2 at t = 1 and move on together at V = 3/3 = 1. At t = 0.75: three.
    const std::vector<double> x{0.0, 1.0, 2.0}, v{2.0, 1.0, 0.0};
    std::vector<LineCluster> clusters;
    shockgas::sticky_clusters_on_line(x, v, 0.75, clusters);
    EXPECT_EQ(clusters.size(), 3u);
    shockgas::sticky_clusters_on_line(x, v, 2.0, clusters);
    ASSERT_EQ(clusters.size(), 1u);
    EXPECT_EQ(clusters[0].velocity(), 1.0);
    EXPECT_EQ(clusters[0].mass, 3.0);
}

TEST(OpenLinePav, InteriorClustersAreTheExactEngineClusters) {
    // On a ring of 4000 unit-spaced particles with the project's uniform
    // velocities, at t = 30 a cluster is influenced only by particles within
    // ~2t = 60 of it (|v| <= 1): clusters whose particles lie in [200, 3800)
    // must be the same on the open line [0, 4000) as on the ring.
    const auto initial = shockgas::generate_initial_condition(4000, 4000.0, 7, 0);
    const double t = 30.0;
    shockgas::ExactEngine engine(initial);
    ASSERT_TRUE(engine.advance_to(t));
    shockgas::ClusterState ring;
    engine.clusters(ring);
    std::vector<LineCluster> line;
    shockgas::sticky_clusters_on_line(initial.position, initial.velocity, t, line);
    std::size_t compared = 0;
    for (const auto& cluster : line) {
        if (cluster.first < 200 || cluster.first + cluster.count > 3800) continue;
        const auto k = static_cast<std::size_t>(
            std::find(ring.first_particle.begin(), ring.first_particle.end(), static_cast<std::int64_t>(cluster.first)) -
            ring.first_particle.begin());
        ASSERT_LT(k, ring.size()) << "no ring cluster starts at particle " << cluster.first;
        EXPECT_EQ(ring.mass[k], cluster.mass);
        // Ring velocities are rounded once from double-double, the line's sum
        // in double over <= ~100 particles: a few ulp of |v| <= 1.
        constexpr double summation_tolerance = 1e-13;
        EXPECT_NEAR(ring.velocity[k], cluster.velocity(), summation_tolerance);
        ++compared;
    }
    EXPECT_GT(compared, 100u);  // ~ N / (t^(2/3)) clusters in all
}

}  // namespace
