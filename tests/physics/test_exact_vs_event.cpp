// SPDX-License-Identifier: GPL-3.0-or-later
// The exact sticky-gas engine against the event-driven engine at r = 0,
// cluster for cluster: 60 seeds x 3 kinds of initial condition, N = 2..10^4,
// from t < 1 to past the single-cluster final state.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "reference_event_engine.hpp"
#include "exact_engine.hpp"
#include "shockgas/model/observables.hpp"

namespace {

using namespace shockgas;

constexpr double epsilon_machine = std::numeric_limits<double>::epsilon();

// Velocities. The exact engine rounds each cluster's P / M once (<= 1/2 ulp).
// The event engine applies merge() once per collision, each rounding <= 1 ulp
// of the largest |v| (<= 1.5 with the drifts below); a cluster's velocity
// carries the roundings of its merge history weighted by mass fractions, so
// in the worst case (merge-tree depth) ulps, but independent roundings mostly
// cancel: the largest difference seen over all states is 1 ulp of 1 (this test
// prints it). 8 ulps of 1.5 leaves a margin of 8 over that.
constexpr double velocity_tolerance = 8.0 * 1.5 * epsilon_machine;

// Positions. The event engine places clusters by summing K gaps from an
// anchor; each gap is advanced as gap + (v_right - v_left)(t - tau), so a
// velocity rounding of dv becomes dv t, and each of the K terms rounds at the
// ulp of the ring length (sum of random roundings: ~ sqrt(K) ulps). The exact
// engine rounds each position once.
double position_tolerance(double ring_length, std::size_t clusters, double t) {
    return 16.0 * (std::sqrt(static_cast<double>(clusters)) + 1.0) * epsilon_machine * ring_length +
           velocity_tolerance * t;
}

// Temperature: the same observables code on both states; velocity errors of
// ~10 ulps change T = <(v - V)^2> by ~10 ulps relative (1e-12 is the issue's
// requirement). Where T is itself rounding noise (a single cluster: T is the
// square of the rounding in V = sum m v / M), compare absolutely at that
// noise level.
constexpr double temperature_relative_tolerance = 1e-12;
double temperature_noise_floor(double velocity_scale) {
    return std::pow(16.0 * epsilon_machine * velocity_scale, 2);
}

enum class Kind { generated, drifting, irregular };
const char* name(Kind kind) {
    return kind == Kind::generated ? "generated" : kind == Kind::drifting ? "drifting" : "irregular";
}

// generated: the paper's lattice and uniform velocities.
// drifting: the same with every velocity shifted by U in [0.1, 0.5): nonzero
//   total momentum, clusters wrap the ring (an --init style condition).
// irregular: sorted uniform random positions, integer masses 1..3, velocities
//   uniform on [-1, 1) + U: unequal spacing and weights.
InitialCondition make_initial(Kind kind, std::int64_t particles, std::uint64_t seed) {
    const double ring_length = static_cast<double>(particles);
    InitialCondition initial = generate_initial_condition(particles, ring_length, seed, 0);
    std::mt19937_64 random(seed * 7919 + 17);
    const double drift = 0.1 + 0.4 * static_cast<double>(random() >> 11) * 0x1p-53;
    if (kind == Kind::generated) return initial;
    for (double& v : initial.velocity) v += drift;
    if (kind == Kind::drifting) return initial;
    for (std::size_t i = 0; i < initial.position.size(); ++i) {
        initial.position[i] = ring_length * static_cast<double>(random() >> 11) * 0x1p-53;
        initial.mass[i] = static_cast<double>(1 + random() % 3);
    }
    std::sort(initial.position.begin(), initial.position.end());
    return initial;
}

// Time of the last merge (the ring becomes one cluster), by stepping events.
double final_merge_time(const InitialCondition& initial) {
    ReferenceEventEngine engine(initial, CollisionModel{0.0, 0.0, Subthreshold::elastic}, {});
    double last = 0.0;
    while (engine.cluster_count() > 1) {
        last = engine.next_event_time();
        if (!engine.step(std::numeric_limits<double>::infinity())) break;
    }
    return last;
}

struct Deviation {
    double velocity = 0.0;
    double position_over_tolerance = 0.0;
    double position = 0.0;
    double temperature_relative = 0.0;
    std::size_t comparisons = 0;
    std::size_t clusters_compared = 0;
    std::size_t seam_clusters = 0;
    std::size_t single_cluster_states = 0;
};

void compare(const ClusterState& exact, const ClusterState& event, double ring_length, const std::string& where,
             Deviation& worst) {
    ASSERT_EQ(exact.size(), event.size()) << where;
    ASSERT_EQ(exact.first_particle, event.first_particle) << where;
    ASSERT_EQ(exact.mass, event.mass) << where;
    const double tolerance = position_tolerance(ring_length, exact.size(), exact.time);
    double velocity_scale = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
        const double dv = std::abs(exact.velocity[k] - event.velocity[k]);
        EXPECT_LE(dv, velocity_tolerance) << where << " cluster " << k;
        const double dx_raw = std::abs(exact.position[k] - event.position[k]);
        const double dx = std::min(dx_raw, ring_length - dx_raw);  // distance on the ring
        EXPECT_LE(dx, tolerance) << where << " cluster " << k;
        worst.velocity = std::max(worst.velocity, dv);
        worst.position = std::max(worst.position, dx);
        worst.position_over_tolerance = std::max(worst.position_over_tolerance, dx / tolerance);
        velocity_scale = std::max(velocity_scale, std::abs(event.velocity[k]));
    }
    // The last cluster straddles the seam when particle 0 is not the first
    // particle of the first cluster (it belongs to the last one).
    if (exact.first_particle[0] > 0) ++worst.seam_clusters;
    const double t_exact = velocity_moments(exact.velocity, exact.mass).temperature;
    const double t_event = velocity_moments(event.velocity, event.mass).temperature;
    const double floor = exact.size() == 1 ? temperature_noise_floor(velocity_scale) : 0.0;
    EXPECT_LE(std::abs(t_exact - t_event), temperature_relative_tolerance * t_event + floor) << where;
    if (t_event > 0.0 && exact.size() > 1)
        worst.temperature_relative = std::max(worst.temperature_relative, std::abs(t_exact - t_event) / t_event);
    ++worst.comparisons;
    worst.clusters_compared += exact.size();
    if (exact.size() == 1) ++worst.single_cluster_states;
}

TEST(ExactVersusEvent, ClusterForClusterOverSixtySeedsToTheFinalState) {
    const std::int64_t sizes[] = {2, 3, 4, 5, 8, 13, 31, 100, 317, 1000, 3162, 10000};
    constexpr int seeds = 60;
    constexpr int samples_per_decade = 10;
    Deviation worst;
    for (int seed = 0; seed < seeds; ++seed) {
        const std::int64_t particles = sizes[seed % std::size(sizes)];
        for (const Kind kind : {Kind::generated, Kind::drifting, Kind::irregular}) {
            const InitialCondition initial = make_initial(kind, particles, static_cast<std::uint64_t>(seed));
            const double t_final = final_merge_time(initial);
            // Log-spaced times from 1/4 to 4 t_final, plus times just after
            // the final merge (a contact decided 10^-9 t_final ago).
            std::vector<double> times;
            for (double t = 0.25; t < 4.0 * t_final; t *= std::pow(10.0, 1.0 / samples_per_decade)) times.push_back(t);
            times.push_back(t_final * (1.0 + 1e-9));
            times.push_back(4.0 * t_final);
            std::sort(times.begin(), times.end());
            ReferenceEventEngine event(initial, CollisionModel{0.0, 0.0, Subthreshold::elastic}, {});
            ExactEngine exact(initial);
            ClusterState event_state, exact_state;
            for (const double t : times) {
                ASSERT_TRUE(event.advance_to(t));
                ASSERT_TRUE(exact.advance_to(t));
                event.clusters(event_state);
                exact.clusters(exact_state);
                const std::string where = std::string(name(kind)) + " N = " + std::to_string(particles) +
                                          " seed " + std::to_string(seed) + " t = " + std::to_string(t);
                compare(exact_state, event_state, initial.ring_length, where, worst);
                ASSERT_EQ(exact.collisions(), event.collisions()) << where;
                if (HasFatalFailure()) return;
            }
            EXPECT_EQ(exact.cluster_count(), 1) << name(kind) << " seed " << seed;
        }
    }
    // The coverage the issue asks for actually happened.
    EXPECT_GT(worst.seam_clusters, 0u);
    EXPECT_GE(worst.single_cluster_states, 3u * seeds);
    std::printf("exact vs event: %zu states, %zu clusters compared (%zu straddling the seam, %zu single-cluster "
                "states)\n  max |dv| = %.3g (tolerance %.3g), max |dx| = %.3g (max |dx| / tolerance = %.3g), "
                "max |dT|/T = %.3g\n",
                worst.comparisons, worst.clusters_compared, worst.seam_clusters, worst.single_cluster_states,
                worst.velocity, velocity_tolerance, worst.position, worst.position_over_tolerance,
                worst.temperature_relative);
}

}  // namespace
