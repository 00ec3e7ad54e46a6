// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/burgers_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "shockgas/model/state.hpp"

namespace shockgas::analysis {
namespace {

using burgers::Shock;
using burgers::Solver;

double periodic_distance(double a, double b, double length) {
    const double d = std::fmod(std::abs(a - b), length);
    return std::min(d, length - d);
}

// For each position in `from`, the distance to the nearest position in `to` around the ring.
std::vector<double> nearest_distances(const std::vector<double>& from, const std::vector<double>& to, double length) {
    std::vector<double> out;
    for (const double x : from) {
        double best = length;
        for (const double y : to) best = std::min(best, periodic_distance(x, y, length));
        out.push_back(best);
    }
    return out;
}

double median(std::vector<double> values) {
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double mean_absolute_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
    return sum / static_cast<double>(a.size());
}

}  // namespace

std::vector<double> strong_burgers_shocks(const Solver& solver, double t, double jump_fraction) {
    const double v_rms = std::sqrt(solver.temperature(t));
    std::vector<double> out;
    for (const Shock& s : solver.shocks(t))
        if (s.mass() / t >= jump_fraction * v_rms) out.push_back(s.position);
    return out;
}

BurgersComparison compare_with_burgers(const Snapshot& snapshot, const Solver& solver, double t, double jump_fraction,
                                       const std::vector<double>& burgers_shocks, std::int64_t particles) {
    const double length = snapshot.ring_length;
    const double v_rms = std::sqrt(solver.temperature(t));
    BurgersComparison out;
    out.clusters_are_shocks = std::any_of(snapshot.mass.begin(), snapshot.mass.end(), [](double m) { return m > 1.5; });
    std::vector<double> particle_shocks;
    if (out.clusters_are_shocks) {
        for (std::size_t i = 0; i < snapshot.mass.size(); ++i)
            if (snapshot.mass[i] / t >= jump_fraction * v_rms) particle_shocks.push_back(snapshot.position[i]);
    } else {
        ShockRule rule;
        rule.jump_fraction = jump_fraction;
        particle_shocks = find_shocks(snapshot, rule).shock_position;
    }
    for (double& p : particle_shocks) p = wrap_position(p, length);
    // At a shock the Burgers field jumps, and its value there is one side of the jump; what moves
    // at a shock is its mass, with the shock's velocity (v_- + v_+)/2, the mean initial velocity of
    // that mass (Rankine-Hugoniot). So an element on a shock (within shock_match of it) is compared
    // with the shock's velocity: for the sticky gas every cluster sits on a shock to rounding (1e-8,
    // test_burgers), and comparing it with one side made the misfit about v_rms where the two agree
    // exactly.
    const double shock_match = 1e-6 * length / static_cast<double>(particles);
    std::vector<std::pair<double, double>> shock_at;  // (position, velocity), sorted
    for (const Shock& shock : solver.shocks(t)) shock_at.emplace_back(shock.position, shock.velocity);
    std::sort(shock_at.begin(), shock_at.end());
    auto at_particles = solver.inviscid(snapshot.position, t);
    for (std::size_t i = 0; i < at_particles.size() && !shock_at.empty(); ++i) {
        const double here = wrap_position(snapshot.position[i], length);
        const auto above = std::lower_bound(shock_at.begin(), shock_at.end(), std::make_pair(here, -HUGE_VAL));
        // The nearest shocks are the ones either side of it, around the ring.
        const auto& after = above == shock_at.end() ? shock_at.front() : *above;
        const auto& before = above == shock_at.begin() ? shock_at.back() : *(above - 1);
        for (const auto& [position, velocity] : {after, before})
            if (periodic_distance(here, position, length) <= shock_match) {
                at_particles[i] = velocity;
                break;
            }
    }
    double misfit = 0.0, mass = 0.0;
    for (std::size_t i = 0; i < at_particles.size(); ++i) {
        misfit += snapshot.mass[i] * std::abs(snapshot.velocity[i] - at_particles[i]);
        mass += snapshot.mass[i];
    }
    out.velocity_misfit = misfit / (mass * v_rms);
    const auto to_burgers = nearest_distances(particle_shocks, burgers_shocks, length);
    out.particle_shocks = particle_shocks.size();
    out.mean_separation = length / std::max<double>(1.0, static_cast<double>(burgers_shocks.size()));
    out.median_distance = median(to_burgers);
    out.max_distance = to_burgers.empty() ? std::nan("") : *std::max_element(to_burgers.begin(), to_burgers.end());
    for (const double d : to_burgers) out.matched += d < 0.1 * out.mean_separation;
    out.median_distance_reverse = median(nearest_distances(burgers_shocks, particle_shocks, length));
    return out;
}

BurgersConvergence burgers_convergence(const InitialCondition& initial, const Solver& solver,
                                       const std::vector<double>& x, const std::vector<double>& v_inviscid, double t,
                                       double jump_fraction) {
    BurgersConvergence out;
    // (1) nu -> 0 at the solver's grid.
    for (const double nu : {1.0, 0.3, 0.1, 0.03, 0.01, 1e-3, 1e-4, 1e-5, 1e-6})
        out.viscous_limit.push_back({nu, mean_absolute_difference(solver.viscous(x, t, nu), v_inviscid)});
    // (2) grid refinement: 1/16 ... 4 cells per particle against the particle field (one per particle).
    const std::int64_t n = initial.size();
    const Solver exact(burgers::grid_from_particles(initial, n));
    const auto reference = strong_burgers_shocks(exact, t, jump_fraction);
    const auto v_exact = exact.inviscid(x, t);
    for (const double per : {1.0 / 16, 1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0, 2.0, 4.0}) {
        BurgersConvergence::GridLevel level{per};
        // A coarse cell holds a whole number of particles (grid_from_particles): the coarse
        // levels exist only where N divides into them.
        const auto divisor = static_cast<std::int64_t>(std::llround(1.0 / per));
        if (per < 1.0 && n % divisor != 0) {
            level.skipped = true;
            out.grid.push_back(level);
            continue;
        }
        const auto cells = static_cast<std::int64_t>(std::llround(per * static_cast<double>(n)));
        const Solver coarse(burgers::grid_from_particles(initial, cells));
        const auto found = strong_burgers_shocks(coarse, t, jump_fraction);
        const auto shift = nearest_distances(reference, found, initial.ring_length);
        level.strong_shocks = found.size();
        level.median_shift = median(shift);
        level.max_shift = shift.empty() ? 0.0 : *std::max_element(shift.begin(), shift.end());
        level.mean_deviation = mean_absolute_difference(coarse.inviscid(x, t), v_exact);
        out.grid.push_back(level);
    }
    return out;
}

}  // namespace shockgas::analysis
