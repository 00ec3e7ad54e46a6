// SPDX-License-Identifier: GPL-3.0-or-later
// Clusters of the coarse-grained density field (shockgas/analysis/clusters.hpp):
// hand-made fields with known answers, the union-find labelling against a plain
// flood fill on random fields, the summary over realizations and snapshots,
// and shockgas-analyze clusters' files.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <queue>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/clusters.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/spheres/ensemble.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::analysis::Cluster;
using shockgas::analysis::cluster_field;

// Hand-made fields hold counts over a mean count of 4, a power of two: every
// density and every sum of counts is exact in binary, so masses are compared
// exactly.
constexpr double exact = 0.0;
constexpr double mean_count = 4.0;
// The random fields use the mean count of the small 2D run (20000 / 32^2 =
// 19.53125): count / mean_count is rounded, and the union-find and the flood
// fill add a cluster's cells in other orders; a cluster of at most 6^3 = 216
// cells then differs by a few hundred ulps at most, far below 1e-12 relative.
constexpr double summation_order = 1e-12;
constexpr double random_mean_count = 20000.0 / 1024.0;
constexpr double threshold = 2.0;  // twice the mean: a count of 8 and more at mean_count 4
// eps = (1 - 0.8) / 2 is 0.1 to an ulp; squared and inverted, eps^-2 = 100 to a few ulps.
constexpr double power_rounding = 1e-13;

// A field of side n in d dimensions, count 1 everywhere (density 1/4), count 8
// (density 2, at the threshold) at the given cells.
std::vector<double> field_with(int d, int n, const std::vector<std::vector<int>>& dense_cells) {
    std::size_t cells = 1;
    for (int k = 0; k < d; ++k) cells *= static_cast<std::size_t>(n);
    std::vector<double> density(cells, 1.0 / mean_count);
    for (const auto& at : dense_cells) {
        std::size_t index = 0;  // x fastest: sum_k i_k n^k, as shockgas-spheres writes the field
        for (int k = d - 1; k >= 0; --k) index = index * static_cast<std::size_t>(n) + static_cast<std::size_t>(at[k]);
        density[index] = 8.0 / mean_count;
    }
    return density;
}

// The reference: breadth-first flood fill over the 2d face neighbours of each
// cell, with or without the periodic wrap, written from the definition rather
// than from the union-find.
std::vector<Cluster> flood_fill(const std::vector<double>& density, int d, int n, double count, double at_least,
                                bool periodic) {
    std::vector<int> seen(density.size(), 0);
    std::vector<Cluster> clusters;
    const auto coordinates = [&](std::size_t index) {
        std::vector<int> x(static_cast<std::size_t>(d));
        for (int k = 0; k < d; ++k, index /= static_cast<std::size_t>(n)) x[k] = static_cast<int>(index % n);
        return x;
    };
    const auto index_of = [&](const std::vector<int>& x) {
        std::size_t index = 0;
        for (int k = d - 1; k >= 0; --k) index = index * static_cast<std::size_t>(n) + static_cast<std::size_t>(x[k]);
        return index;
    };
    for (std::size_t start = 0; start < density.size(); ++start) {
        if (seen[start] || !(density[start] >= at_least)) continue;
        Cluster cluster;
        std::queue<std::size_t> queue;
        queue.push(start);
        seen[start] = 1;
        while (!queue.empty()) {
            const std::size_t cell = queue.front();
            queue.pop();
            cluster.mass += density[cell] * count;
            ++cluster.cells;
            for (int k = 0; k < d; ++k)
                for (int step : {-1, 1}) {
                    std::vector<int> x = coordinates(cell);
                    x[k] += step;
                    if (x[k] < 0 || x[k] >= n) {
                        if (!periodic) continue;
                        x[k] = (x[k] + n) % n;
                    }
                    const std::size_t next = index_of(x);
                    if (!seen[next] && density[next] >= at_least) seen[next] = 1, queue.push(next);
                }
        }
        clusters.push_back(cluster);
    }
    return clusters;
}

// Two cluster lists as multisets of (cells, mass): equal when each has the
// other's sizes and masses, in any order.
bool same_clusters(std::vector<Cluster> a, std::vector<Cluster> b, double relative) {
    const auto order = [](const Cluster& x, const Cluster& y) {
        return x.cells != y.cells ? x.cells < y.cells : x.mass < y.mass;
    };
    std::sort(a.begin(), a.end(), order);
    std::sort(b.begin(), b.end(), order);
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].cells != b[i].cells || std::abs(a[i].mass - b[i].mass) > relative * b[i].mass) return false;
    return true;
}

TEST(AnalysisClusters, OneClusterAcrossThePeriodicBoundaryInX) {
    // Cells x = 7 and x = 0 of row y = 3 share the box's face: one cluster of count 16.
    const auto density = field_with(2, 8, {{0, 3}, {7, 3}});
    const auto clusters = cluster_field(density, 2, 8, mean_count, threshold);
    ASSERT_EQ(clusters.size(), 1u);
    EXPECT_EQ(clusters[0].cells, 2u);
    EXPECT_NEAR(clusters[0].mass, 16.0, exact);
    // Without the wrap they are two: the test tells periodic from open boundaries.
    EXPECT_EQ(flood_fill(density, 2, 8, mean_count, threshold, false).size(), 2u);
    // Along y as well (stride 8): x = 5, y = 0 and y = 7.
    EXPECT_EQ(cluster_field(field_with(2, 8, {{5, 0}, {5, 7}}), 2, 8, mean_count, threshold).size(), 1u);
}

TEST(AnalysisClusters, DiagonalContactIsTwoClusters) {
    // Corners touch, faces do not: two clusters, also across the box's corner.
    EXPECT_EQ(cluster_field(field_with(2, 8, {{1, 1}, {2, 2}}), 2, 8, mean_count, threshold).size(), 2u);
    EXPECT_EQ(cluster_field(field_with(2, 8, {{0, 0}, {7, 7}}), 2, 8, mean_count, threshold).size(), 2u);
    // x fastest: cells (1, 0) and (0, 1) are indices 1 and 8, diagonal; (1, 0) and (2, 0) are faces.
    EXPECT_EQ(cluster_field(field_with(2, 8, {{1, 0}, {0, 1}}), 2, 8, mean_count, threshold).size(), 2u);
    EXPECT_EQ(cluster_field(field_with(2, 8, {{1, 0}, {2, 0}}), 2, 8, mean_count, threshold).size(), 1u);
}

TEST(AnalysisClusters, ThreeDimensionalColumnWrapsInZ) {
    // A column along z through the box's top and bottom face (z = 6, 0, 1),
    // a cell touching it along one edge only (a diagonal in 3D), and one alone.
    const auto density = field_with(3, 7, {{2, 2, 6}, {2, 2, 0}, {2, 2, 1}, {3, 3, 1}, {5, 5, 3}});
    auto clusters = cluster_field(density, 3, 7, mean_count, threshold);
    ASSERT_EQ(clusters.size(), 3u);
    std::sort(clusters.begin(), clusters.end(), [](const Cluster& a, const Cluster& b) { return a.cells > b.cells; });
    EXPECT_EQ(clusters[0].cells, 3u);
    EXPECT_NEAR(clusters[0].mass, 24.0, exact);
    EXPECT_EQ(clusters[1].cells, 1u);
    EXPECT_EQ(flood_fill(density, 3, 7, mean_count, threshold, false).size(), 4u);
}

TEST(AnalysisClusters, CheckerboardIsSingleCells) {
    // On an even side no two dense cells share a face, across the wrap either.
    for (const int d : {2, 3}) {
        const int n = 6;
        std::vector<std::vector<int>> black;
        std::vector<int> x(static_cast<std::size_t>(d), 0);
        const int cells = d == 2 ? n * n : n * n * n;
        for (int index = 0; index < cells; ++index) {
            int rest = index, parity = 0;
            for (int k = 0; k < d; ++k, rest /= n) x[k] = rest % n, parity += x[k];
            if (parity % 2 == 0) black.push_back(x);
        }
        const auto clusters = cluster_field(field_with(d, n, black), d, n, mean_count, threshold);
        ASSERT_EQ(clusters.size(), black.size()) << d << "D";
        for (const Cluster& c : clusters) EXPECT_EQ(c.cells, 1u) << d << "D";
    }
}

TEST(AnalysisClusters, EmptyAndFullFields) {
    EXPECT_TRUE(cluster_field(field_with(2, 8, {}), 2, 8, mean_count, threshold).empty());
    // Every cell at the mean, threshold 1 (inclusive): one cluster holding all N particles.
    const int n = 5;
    const std::vector<double> uniform(static_cast<std::size_t>(n * n * n), 1.0);
    const auto clusters = cluster_field(uniform, 3, n, mean_count, 1.0);
    ASSERT_EQ(clusters.size(), 1u);
    EXPECT_EQ(clusters[0].cells, uniform.size());
    EXPECT_NEAR(clusters[0].mass, mean_count * static_cast<double>(uniform.size()), exact);
    // One cell a side is its own neighbour: still one cluster.
    EXPECT_EQ(cluster_field(std::vector<double>{3.0}, 2, 1, mean_count, threshold).size(), 1u);
}

TEST(AnalysisClusters, RefusesAFieldOfTheWrongSize) {
    EXPECT_THROW(cluster_field(std::vector<double>(63, 1.0), 2, 8, mean_count, threshold), std::invalid_argument);
    EXPECT_THROW(cluster_field(std::vector<double>(64, 1.0), 3, 8, mean_count, threshold), std::invalid_argument);
}

TEST(AnalysisClusters, UnionFindAgreesWithFloodFillOnRandomFields) {
    // Counts drawn so that about 55% of cells are dense, near the site
    // percolation threshold of the square lattice (0.593), where clusters are
    // largest and most tangled; each side from 1 to 16 cells in 2D, 6 in 3D.
    std::mt19937_64 random(20240611);
    int differs_without_wrap = 0, fields = 0;
    for (const int d : {2, 3})
        for (const int n : d == 2 ? std::vector<int>{1, 2, 3, 5, 8, 16} : std::vector<int>{1, 2, 3, 4, 6})
            for (int trial = 0; trial < 20; ++trial, ++fields) {
                std::size_t cells = 1;
                for (int k = 0; k < d; ++k) cells *= static_cast<std::size_t>(n);
                std::poisson_distribution<int> count(threshold * random_mean_count);
                std::vector<double> density(cells);
                for (double& rho : density) rho = count(random) / random_mean_count;
                const auto reference = flood_fill(density, d, n, random_mean_count, threshold, true);
                EXPECT_TRUE(same_clusters(cluster_field(density, d, n, random_mean_count, threshold), reference,
                                          summation_order))
                    << d << "D, side " << n << ", trial " << trial;
                if (!same_clusters(flood_fill(density, d, n, random_mean_count, threshold, false), reference,
                                   summation_order))
                    ++differs_without_wrap;
            }
    // The fields are such that the boundary matters: open boundaries give
    // other clusters on most of them, so a labelling without the wrap fails above.
    EXPECT_GT(differs_without_wrap, fields / 2);
}

// Two realizations of a 4 x 4 field at two snapshots; realization 1 did not
// reach the second (its row NaN, as shockgas-spheres leaves it after a collapse).
shockgas::spheres::SphereOutput two_realizations() {
    shockgas::spheres::SphereOutput run;
    auto& p = run.parameters;
    p.dimension = 2;
    p.particles = 64;  // mean count 4 on 16 cells
    p.field_cells = 4;
    p.realizations = 2;
    p.collision.restitution = 0.8;
    auto& r = run.result;
    r.realizations = 2;
    r.time = {0.0};
    r.temperature = r.collisions_per_particle = r.velocity_kurtosis = {1.0, 1.0};
    r.end_time = {1.0, 0.5};
    r.status = {"complete", "collapsed"};
    const auto first = field_with(2, 4, {{0, 0}, {3, 0}, {2, 2}});    // clusters of 16 and 8 particles
    const auto second = field_with(2, 4, {{1, 1}});                    // one of 8
    const auto later = field_with(2, 4, {{0, 1}, {1, 1}, {2, 1}, {3, 1}});  // a band round the box: 32
    shockgas::spheres::SphereSnapshot early, late;
    early.time = 1.0;
    early.density = first;
    early.density.insert(early.density.end(), second.begin(), second.end());
    late.time = 2.0;
    late.density = later;
    late.density.insert(late.density.end(), 16, std::nan(""));
    for (auto* s : {&early, &late}) s->velocity_field.assign(2 * 16 * 2, 0.0);
    r.snapshots = {early, late};
    return run;
}

TEST(AnalysisClusters, SummaryOverRealizations) {
    const auto summary = shockgas::analysis::summarize_clusters(two_realizations(), threshold);
    EXPECT_NEAR(summary.mean_count, mean_count, exact);
    EXPECT_NEAR(summary.critical_size_scale.value, 100.0, 100.0 * power_rounding);  // eps = 0.1 in 2D: eps^-2
    ASSERT_EQ(summary.snapshots.size(), 2u);
    const auto& early = summary.snapshots[0];
    EXPECT_EQ(early.realizations, 2u);
    EXPECT_NEAR(early.clusters.value, 1.5, exact);
    EXPECT_NEAR(early.largest_mass.value, 12.0, exact);  // (16 + 8) / 2
    // The jackknife sigma of a mean is its standard error: |16 - 8| / 2.
    EXPECT_NEAR(early.largest_mass.sigma, 4.0, exact);
    EXPECT_NEAR(early.mean_mass.value, (16.0 * 16 + 8 * 8 + 8 * 8) / (16.0 + 8 + 8), exact);
    EXPECT_NEAR(early.clustered_fraction.value, (24.0 / 64 + 8.0 / 64) / 2, exact);
    double pooled = 0.0;
    for (double c : early.bin_clusters) pooled += c;
    EXPECT_NEAR(pooled, 3.0, exact);
    // The second snapshot: realization 0 alone (realization 1's row is NaN), one band.
    const auto& late = summary.snapshots[1];
    EXPECT_EQ(late.realizations, 1u);
    EXPECT_NEAR(late.clusters.value, 1.0, exact);
    EXPECT_NEAR(late.largest_mass.value, 32.0, exact);
    EXPECT_TRUE(std::isnan(late.largest_mass.sigma));  // one realization: nothing to leave out
}

TEST(AnalysisClusters, NoClusterIsZerosNotNaN) {
    auto run = two_realizations();
    const auto summary = shockgas::analysis::summarize_clusters(run, 100.0);  // no cell reaches 100 x the mean
    for (const auto& at : summary.snapshots) {
        EXPECT_EQ(at.clusters.value, 0.0);
        EXPECT_EQ(at.mean_mass.value, 0.0);
        EXPECT_EQ(at.largest_mass.value, 0.0);
        EXPECT_EQ(at.clustered_fraction.value, 0.0);
    }
    EXPECT_EQ(summary.snapshots[0].largest_mass.sigma, 0.0);
}

TEST(AnalysisClusters, CommandWritesResultsAndTables) {
    const fs::path dir = fs::temp_directory_path() / "shockgas_clusters_command";
    fs::create_directories(dir);
    const std::string input = (dir / "run.h5").string(), output = (dir / "clusters.h5").string(),
                      data = (dir / "clusters.dat").string(), distribution = (dir / "masses.dat").string();
    const auto run = two_realizations();
    shockgas::spheres::write_spheres_output(input, run.parameters, run.result);
    shockgas::analysis::AnalysisInvocation invocation{"shockgas-analyze clusters", "shockgas-analyze clusters run.h5", {}};
    shockgas::analysis::run_clusters(invocation, {input}, output, threshold, data, distribution);
    const auto file = shockgas::h5::File::open_read(output);
    const auto root = file.root();
    EXPECT_EQ(root.attribute_string("input_schema"), "spheres");  // provenance carried forward
    const auto early = root.open_group("clusters0").open_group("snapshots").open_group("0");
    EXPECT_NEAR(early.attribute_double("largest_mass"), 12.0, exact);
    EXPECT_NEAR(early.attribute_double("largest_mass_sigma"), 4.0, exact);
    EXPECT_EQ(early.attribute_integer("realizations"), 2);
    // The table: a row per snapshot; the distribution: a block per snapshot.
    std::ifstream table(data), masses(distribution);
    std::string line;
    int rows = 0, blocks = 0;
    while (std::getline(table, line)) rows += !line.empty() && line[0] != '#';
    while (std::getline(masses, line)) blocks += line.rfind("# 2D", 0) == 0;
    EXPECT_EQ(rows, 2);
    EXPECT_EQ(blocks, 2);
    fs::remove_all(dir);
}

}  // namespace
