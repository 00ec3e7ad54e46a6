// SPDX-License-Identifier: GPL-3.0-or-later
// Burgers solver (analysis/src/burgers.cpp): analytic Riemann solutions, nu -> 0,
// grid refinement, no overflow at small nu, the sticky-gas identity, and the comparison of a
// run with Burgers (analysis/burgers_comparison.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "shockgas/analysis/burgers_comparison.hpp"
#include "shockgas/analysis/burgers.hpp"
#include "exact_engine.hpp"
#include "shockgas/model/state.hpp"

using namespace shockgas;
using namespace shockgas::burgers;

namespace {

// Periodic step: v0 = +1 on [0, L/2), -1 on [L/2, L). Mean zero. Inviscid solution for
// t < L/4: a stationary shock at L/2 (Rankine-Hugoniot speed (1 + (-1))/2 = 0) and a
// centred rarefaction at x = 0, v = x/t for |x| < t (Eq. 7 with q = 0).
Grid step_grid(double length, std::int64_t cells) {
    Grid grid;
    grid.ring_length = length;
    grid.origin = 0.0;
    grid.velocity.resize(cells);
    for (std::int64_t c = 0; c < cells; ++c) grid.velocity[c] = c < cells / 2 ? 1.0 : -1.0;
    return grid;
}

double step_exact(double x, double t, double length) {
    if (x > length / 2) x -= length;  // x in (-L/2, L/2]
    if (std::abs(x) < t) return x / t;
    return x > 0 ? 1.0 : -1.0;
}

}  // namespace

TEST(Burgers, InviscidRiemannShockAndRarefaction) {
    const double length = 100.0, t = 10.0;
    const Solver solver(step_grid(length, 1000));
    const auto x = sample_points(length, 997);  // points off the cell edges and the shock
    const auto v = solver.inviscid(x, t);
    // Piecewise-constant data are represented exactly: only rounding remains.
    constexpr double tolerance = 1e-12;
    for (std::size_t j = 0; j < x.size(); ++j) ASSERT_NEAR(v[j], step_exact(x[j], t, length), tolerance) << x[j];
    const auto shocks = solver.shocks(t, 1.0);
    ASSERT_EQ(shocks.size(), 1u);
    EXPECT_NEAR(shocks[0].position, 50.0, 1e-12);
    EXPECT_NEAR(shocks[0].mass(), 2.0 * t, 1e-9);  // swept from [L/2 - t, L/2 + t]
    EXPECT_NEAR(shocks[0].velocity, 0.0, 1e-12);
}

TEST(Burgers, ViscousShockIsTheTanhTravellingWave) {
    // The stationary viscous shock between +1 and -1: v = -tanh((x - L/2)/(2 nu)), reached
    // exponentially fast once t >> nu (Hopf-Cole of the step).
    const double length = 100.0, t = 10.0, nu = 0.05;
    const Solver solver(step_grid(length, 1000));
    std::vector<double> x;
    for (double d = -0.5; d <= 0.5; d += 0.01) x.push_back(50.0 + d);
    const auto v = solver.viscous(x, t, nu);
    constexpr double tolerance = 1e-9;  // corrections ~ exp(-t/(4 nu)) ~ 1e-22 and rounding
    for (std::size_t j = 0; j < x.size(); ++j) EXPECT_NEAR(v[j], -std::tanh((x[j] - 50.0) / (2.0 * nu)), tolerance);
}

TEST(Burgers, ViscousConvergesToInviscidAsNuGoesToZero) {
    const auto initial = generate_initial_condition(2000, 2000.0, 7, 0);
    const Solver solver(grid_from_particles(initial, 2000));
    const double t = 1000.0;
    const auto x = sample_points(2000.0, 7919);
    const auto v0 = solver.inviscid(x, t);
    std::vector<double> error;
    for (double nu : {1e-1, 1e-2, 1e-3}) {
        const auto v = solver.viscous(x, t, nu);
        double sum = 0.0;
        for (std::size_t j = 0; j < x.size(); ++j) sum += std::abs(v[j] - v0[j]);
        error.push_back(sum / static_cast<double>(x.size()));
    }
    // Shock widths ~ nu / jump: the L1 distance falls about linearly in nu.
    EXPECT_LT(error[1], 0.3 * error[0]);
    EXPECT_LT(error[2], 0.3 * error[1]);
}

TEST(Burgers, NoOverflowAtTinyViscosity) {
    const auto initial = generate_initial_condition(1000, 1000.0, 11, 0);
    const Solver solver(grid_from_particles(initial, 4000));
    const double t = 500.0;
    const auto x = sample_points(1000.0, 3001);
    const auto v0 = solver.inviscid(x, t);
    const auto v = solver.viscous(x, t, 1e-6);
    const auto v_smaller = solver.viscous(x, t, 1e-8);
    double largest = 0.0, largest_smaller = 0.0;
    for (std::size_t j = 0; j < x.size(); ++j) {
        ASSERT_TRUE(std::isfinite(v[j]) && std::isfinite(v_smaller[j])) << x[j];
        largest = std::max(largest, std::abs(v[j] - v0[j]));
        largest_smaller = std::max(largest_smaller, std::abs(v_smaller[j] - v0[j]));
    }
    // The viscous correction is O(nu): measured max |v - v0| = 1.4e-5 at nu = 1e-6 (next to a
    // weak shock), 100 times less at nu = 1e-8. No sample falls inside a shock (width nu/jump).
    EXPECT_LT(largest, 1e-4);
    EXPECT_LT(largest_smaller, 0.1 * largest);
}

TEST(Burgers, GridRefinementConvergesForSmoothData) {
    // v0 = sin(2 pi x / L): the shock forms at t = L/(2 pi) at x = L/2 and stays there;
    // at t = L/pi the inviscid velocity solves v = sin(2 pi (x - v t)/L). Check the
    // error at x = L/4 (smooth part) falls as the grid is refined (piecewise-constant data: O(h)).
    const double length = 1.0, t = 1.0 / 3.14159265358979323846;
    const double x = 0.25;
    double exact = 0.5;
    for (int i = 0; i < 100; ++i) {  // Newton on v - sin(2 pi (x - v t)) = 0
        const double arg = 2.0 * 3.14159265358979323846 * (x - exact * t);
        const double f = exact - std::sin(arg);
        const double df = 1.0 + std::cos(arg) * 2.0 * 3.14159265358979323846 * t;
        exact -= f / df;
    }
    std::vector<double> error;
    for (std::int64_t cells : {100, 400, 1600, 6400}) {
        Grid grid;
        grid.ring_length = length;
        grid.origin = 0.0;
        for (std::int64_t c = 0; c < cells; ++c) {
            // Cell average of sin: exact data conservation on every grid.
            const double a = static_cast<double>(c) / static_cast<double>(cells);
            const double b = static_cast<double>(c + 1) / static_cast<double>(cells);
            const double k = 2.0 * 3.14159265358979323846;
            grid.velocity.push_back((std::cos(k * a) - std::cos(k * b)) / (k * (b - a)));
        }
        const Solver solver(grid);
        error.push_back(std::abs(solver.inviscid({x}, t)[0] - exact));
        // v = (x - q)/t with q resolved to one cell: |error| <= h/t (Eq. 7).
        EXPECT_LE(error.back(), length / static_cast<double>(cells) / t);
        const auto shocks = solver.shocks(t, 0.05);
        ASSERT_EQ(shocks.size(), 1u);
        EXPECT_NEAR(shocks[0].position, 0.5, 2.0 / static_cast<double>(cells));
    }
    EXPECT_LT(error.back(), 0.01 * error.front());  // 64 times finer: measured 6.0e-3 -> 6.6e-6
}

namespace {

// The sticky gas of both tests below: N = 3000 (seed 42) at t = 2000, clusters from the exact engine.
constexpr std::int64_t sticky_particles = 3000;
constexpr double sticky_time = 2000.0;
InitialCondition sticky_start() {
    return generate_initial_condition(sticky_particles, static_cast<double>(sticky_particles), 42, 0);
}
ClusterState sticky_clusters(const InitialCondition& initial) {
    ExactEngine engine(initial);
    EXPECT_TRUE(engine.advance_to(sticky_time));
    ClusterState state;
    engine.clusters(state);
    return state;
}

}  // namespace

TEST(Burgers, InviscidShocksAreTheStickyGasClusters) {
    // Hopf-Lax argmin of (x - q)^2/(2t) + Phi0(q) is the convex minorant of q^2/2 + t Phi0(q),
    // the sticky gas's variational principle (E, Rykov & Sinai 1996): with one cell per particle
    // each shock is one cluster, at the same place, with the same mass and velocity.
    const std::int64_t n = sticky_particles;
    const auto initial = sticky_start();
    const double t = sticky_time;
    const ClusterState state = sticky_clusters(initial);
    std::vector<std::size_t> heavy;
    for (std::size_t i = 0; i < state.size(); ++i)
        if (state.mass[i] >= 2.0) heavy.push_back(i);
    const Solver solver(grid_from_particles(initial, n));
    const auto shocks = solver.shocks(t, 2.0);
    ASSERT_EQ(shocks.size(), heavy.size());
    constexpr double tolerance = 1e-8;  // positions ~ 1e3 summed from ~1e3 terms
    for (std::size_t k = 0; k < heavy.size(); ++k) {
        const auto& s = *std::min_element(shocks.begin(), shocks.end(), [&](const Shock& a, const Shock& b) {
            return std::abs(a.position - state.position[heavy[k]]) < std::abs(b.position - state.position[heavy[k]]);
        });
        EXPECT_NEAR(s.position, state.position[heavy[k]], tolerance);
        EXPECT_NEAR(s.mass(), state.mass[heavy[k]], 1e-9);
        EXPECT_NEAR(s.velocity, state.velocity[heavy[k]], 1e-12);
    }
}

// The comparison shockgas-burgers prints (analysis/burgers_comparison.hpp), on the sticky gas,
// where it must find nothing to tell apart, and on the same clusters with every velocity moved by
// a known amount, where the misfit must be that amount.
TEST(BurgersComparison, StickyGasClustersAreTheBurgersShocks) {
    const std::int64_t n = sticky_particles;
    const auto initial = sticky_start();
    const double t = sticky_time;
    const ClusterState state = sticky_clusters(initial);
    analysis::Snapshot snapshot{t, 0, initial.ring_length, state.position, state.velocity, state.mass};
    const Solver solver(grid_from_particles(initial, n));
    constexpr double jump_fraction = 1.0;  // the detector's default: a drop of at least v_rms
    const auto strong = analysis::strong_burgers_shocks(solver, t, jump_fraction);
    ASSERT_GE(strong.size(), 3u) << "too few shocks for the comparison to mean anything";
    const auto same = analysis::compare_with_burgers(snapshot, solver, t, jump_fraction, strong, n);
    EXPECT_TRUE(same.clusters_are_shocks);
    // Velocities agree to rounding (every element moves with its shock, or lies between shocks on
    // v = (x - q)/t); positions as in InviscidShocksAreTheStickyGasClusters.
    constexpr double velocity_rounding = 1e-12;  // in units of v_rms, which is about 0.07 here
    constexpr double position_rounding = 1e-8;
    EXPECT_LT(same.velocity_misfit, velocity_rounding);
    EXPECT_EQ(same.particle_shocks, strong.size());
    EXPECT_EQ(same.matched, strong.size());
    EXPECT_LT(same.median_distance, position_rounding);
    EXPECT_LT(same.max_distance, position_rounding);
    EXPECT_LT(same.median_distance_reverse, position_rounding);
    EXPECT_DOUBLE_EQ(same.mean_separation, initial.ring_length / static_cast<double>(strong.size()));

    // Every velocity moved by 0.1 v_rms: the misfit is 0.1, the shocks (from masses) unchanged.
    const double v_rms = std::sqrt(solver.temperature(t));
    for (double& v : snapshot.velocity) v += 0.1 * v_rms;
    const auto moved = analysis::compare_with_burgers(snapshot, solver, t, jump_fraction, strong, n);
    EXPECT_NEAR(moved.velocity_misfit, 0.1, velocity_rounding);
    EXPECT_EQ(moved.matched, strong.size());
}
