// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/spheres/start.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "shockgas/model/state.hpp"

namespace shockgas::spheres {

namespace {

// Random sequential insertion on a grid of cells of side >= 1: a candidate is
// kept if no sphere in the 3^d cells around it is closer than one diameter.
std::vector<double> insert_randomly(int d, std::int64_t n, double box, std::mt19937_64& random) {
    const int m = cells_per_side(box);
    const double width = box / m;
    std::size_t cell_count = 1;
    for (int k = 0; k < d; ++k) cell_count *= static_cast<std::size_t>(m);
    std::vector<std::vector<std::int64_t>> members(cell_count);
    std::vector<double> positions(static_cast<std::size_t>(n * d));
    // At the offered packing fractions insertion takes a few attempts per
    // sphere; 10^4 per sphere on average means the limit was set wrong.
    const std::uint64_t attempt_limit = 10000 * static_cast<std::uint64_t>(n);
    std::uint64_t attempts = 0;
    for (std::int64_t i = 0; i < n;) {
        if (++attempts > attempt_limit)
            throw InputError(fmt::format("random insertion placed only {} of {} spheres in {} attempts", i, n,
                                         attempt_limit));
        double x[3];
        int c[3];
        for (int k = 0; k < d; ++k) {
            x[k] = unit_uniform(random) * box;
            c[k] = std::min(m - 1, static_cast<int>(x[k] / width));
        }
        bool free = true;
        for (int code = 0; code < (d == 2 ? 9 : 27) && free; ++code) {
            int offset[3];
            for (int k = 0, rest = code; k < d; ++k, rest /= 3) offset[k] = rest % 3 - 1;
            std::size_t index = 0;
            for (int k = d - 1; k >= 0; --k)
                index = index * static_cast<std::size_t>(m) + static_cast<std::size_t>((c[k] + offset[k] + m) % m);
            for (std::int64_t j : members[index]) {
                double r2 = 0.0;
                for (int k = 0; k < d; ++k) {
                    double dx = positions[static_cast<std::size_t>(j * d + k)] - x[k];
                    dx -= box * std::round(dx / box);
                    r2 += dx * dx;
                }
                if (r2 < 1.0) {
                    free = false;
                    break;
                }
            }
        }
        if (!free) continue;
        std::size_t index = 0;
        for (int k = d - 1; k >= 0; --k) index = index * static_cast<std::size_t>(m) + static_cast<std::size_t>(c[k]);
        members[index].push_back(i);
        for (int k = 0; k < d; ++k) positions[static_cast<std::size_t>(i * d + k)] = x[k];
        ++i;
    }
    return positions;
}

// N of the s^d sites of a simple cubic (square) lattice of spacing L/s,
// s = ceil(N^(1/d)), chosen by a Fisher-Yates shuffle with the portable uniform.
std::vector<double> lattice_sites(int d, std::int64_t n, double box, std::mt19937_64& random) {
    auto s = static_cast<std::int64_t>(std::ceil(std::pow(static_cast<double>(n), 1.0 / d) - 1e-9));
    std::int64_t sites = 1;
    for (int k = 0; k < d; ++k) sites *= s;
    if (sites < n) ++s, sites = d == 2 ? s * s : s * s * s;
    std::vector<std::int64_t> order(static_cast<std::size_t>(sites));
    std::iota(order.begin(), order.end(), 0);
    for (std::int64_t i = sites - 1; i > 0; --i) {
        const auto j = static_cast<std::int64_t>(unit_uniform(random) * static_cast<double>(i + 1));
        std::swap(order[static_cast<std::size_t>(i)], order[static_cast<std::size_t>(std::min(j, i))]);
    }
    const double spacing = box / static_cast<double>(s);
    std::vector<double> positions(static_cast<std::size_t>(n * d));
    for (std::int64_t i = 0; i < n; ++i) {
        std::int64_t site = order[static_cast<std::size_t>(i)];
        for (int k = 0; k < d; ++k) {
            positions[static_cast<std::size_t>(i * d + k)] = (static_cast<double>(site % s) + 0.5) * spacing;
            site /= s;
        }
    }
    return positions;
}

}  // namespace

void sort_by_cell(SphereState& state) {
    const int d = state.dimension;
    const auto n = static_cast<std::size_t>(state.particles());
    const int m = cells_per_side(state.box_length);
    const double width = state.box_length / m;
    std::vector<std::pair<std::int64_t, std::size_t>> keys(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::int64_t key = 0;
        for (int k = d - 1; k >= 0; --k)
            key = key * m + std::min<std::int64_t>(m - 1, static_cast<std::int64_t>(state.positions[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] / width));
        keys[i] = {key, i};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<double> positions(state.positions.size()), velocities(state.velocities.size());
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < d; ++k) {
            const std::size_t from = keys[i].second * static_cast<std::size_t>(d) + static_cast<std::size_t>(k);
            positions[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] = state.positions[from];
            velocities[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)] = state.velocities[from];
        }
    state.positions = std::move(positions);
    state.velocities = std::move(velocities);
}

void write_start_text(const SphereState& state, const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "w");
    if (file == nullptr) throw InputError(fmt::format("cannot write the start to '{}'", path));
    const int d = state.dimension;
    fmt::print(file, "{} {} {:.17g}\n", d, state.particles(), state.box_length);
    for (std::int64_t i = 0; i < state.particles(); ++i) {
        const auto base = static_cast<std::size_t>(i * d);
        for (int k = 0; k < d; ++k) fmt::print(file, "{:.17g} ", state.positions[base + static_cast<std::size_t>(k)]);
        for (int k = 0; k < d; ++k)
            fmt::print(file, "{:.17g}{}", state.velocities[base + static_cast<std::size_t>(k)], k + 1 < d ? " " : "\n");
    }
    if (std::fclose(file) != 0) throw InputError(fmt::format("cannot write the start to '{}'", path));
}

std::vector<double> mean_velocity(const std::vector<double>& v, int d) {
    std::vector<double> mean(static_cast<std::size_t>(d), 0.0);
    const std::size_t n = v.size() / static_cast<std::size_t>(d);
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < d; ++k)
            mean[static_cast<std::size_t>(k)] += v[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(k)];
    for (double& m : mean) m /= static_cast<double>(n);
    return mean;
}

double temperature(const std::vector<double>& velocities, int dimension) {
    const auto mean = mean_velocity(velocities, dimension);
    double sum = 0.0;
    for (std::size_t i = 0; i < velocities.size(); ++i) {
        const double u = velocities[i] - mean[i % static_cast<std::size_t>(dimension)];
        sum += u * u;
    }
    return sum / static_cast<double>(velocities.size());
}

void draw_maxwell_velocities(SphereState& state, std::mt19937_64& random) {
    const int d = state.dimension;
    auto& v = state.velocities;
    double second = 0.0;
    bool have_second = false;
    for (double& component : v) {
        if (have_second) {
            component = second;
            have_second = false;
        } else {
            component = standard_normal_pair(random, second);
            have_second = true;
        }
    }
    const auto mean = mean_velocity(v, d);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] -= mean[i % static_cast<std::size_t>(d)];
    const double scale = 1.0 / std::sqrt(temperature(v, d));
    for (double& component : v) component *= scale;
}

SphereState place_particles(const SphereParameters& p, std::mt19937_64& random) {
    SphereState state;
    state.dimension = p.dimension;
    state.box_length = box_length(p.dimension, p.particles, p.packing_fraction);
    state.positions = p.start == StartMethod::insertion
                          ? insert_randomly(p.dimension, p.particles, state.box_length, random)
                          : lattice_sites(p.dimension, p.particles, state.box_length, random);
    state.velocities.assign(state.positions.size(), 0.0);
    draw_maxwell_velocities(state, random);
    return state;
}

SphereState make_start(const SphereParameters& p, std::int64_t realization) {
    std::mt19937_64 random(realization_seed(p.seed, realization));
    SphereState state = place_particles(p, random);
    if (p.melt_collisions_per_particle > 0.0) {
        // Each collision involves two particles: N c / 2 collisions give c per particle.
        HardSphereEngine melt(state, CollisionModel{1.0, 0.0, Subthreshold::elastic});
        melt.run_collisions(static_cast<std::uint64_t>(std::ceil(p.melt_collisions_per_particle * static_cast<double>(p.particles) / 2.0)));
        // Stop between events, not at the last collision, whose pair is in contact:
        // with fresh velocities it could approach and collide at t = 0.
        melt.advance_to(melt.time() + 0.01);
        state = melt.state();
    }
    state.time = 0.0;
    sort_by_cell(state);
    draw_maxwell_velocities(state, random);
    return state;
}

}  // namespace shockgas::spheres
