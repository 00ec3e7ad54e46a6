// SPDX-License-Identifier: GPL-3.0-or-later
// Metamorphic tests: transformations of a start that the model maps onto the
// same dynamics, so that every engine must give the same collision counts and
// temperatures (docs/reliability.md, "Scales and shifts"):
//  * scale, x -> lambda x and t -> lambda t (velocities unchanged), for lambda
//    from 1e-300 to 1e300: no tolerance of an engine may be an absolute time,
//    gap or speed;
//  * a Galilean shift of every velocity by u, up to |u| = 1e9, on starts whose
//    shifted velocities are exact in double precision: only the lab's mean
//    velocity (and positions, by u t) may change;
//  * the mirror image x -> L - x, v -> -v;
//  * relabelling the start by a rotation of the ring;
//  * for the sticky gas, the exact engine against the event engine on each of
//    these transformed starts.
// Engines: event, reference, passthrough and hybrid at r = 0.5, delta = 1e-2
// (a setting that cools into the elastic regime); exact and event for the sticky gas r = 0; event and
// reference for the pure inelastic gas r = 0.5, delta = 0, which collapses.
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/model/observables.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/model/state.hpp"

namespace {

using namespace shockgas;

constexpr double epsilon_machine = std::numeric_limits<double>::epsilon();

// T of two runs that must be the same dynamics: the same velocities summed in
// another order (a mirrored or rotated ring lists its clusters in another
// order), or velocities that differ by the rounding of a start that is the
// same up to rounding (i L/N for a lambda that is no power of two). T is a
// compensated sum (Neumaier), good to ~1 ulp in any order; 8 ulp leaves a
// margin. Measured: every T of these tests is equal to the last bit.
constexpr double temperature_rounding = 8.0 * epsilon_machine;

// The hybrid engine's hand-over time: a check time 1.25^k L/N, each check's
// time the last one's times 1.25, so k roundings (k = 26 reaches t = 300),
// besides the rounding of L/N itself when lambda is no power of two. 2 ulp
// per check.
constexpr double hand_over_time_relative = 64.0 * epsilon_machine;

// The time a collapse is reported at, on a start that is the same up to the
// rounding of its positions (i L/N for a lambda that is no power of two, or
// x -> L - x), or whose last gaps before the collapse are subnormal (2^-996):
// the collapse is found inside its final burst, whose events come closer in
// time than the spacing of doubles, and a change of every position by its
// rounding moves the reported time by up to 1.2e-12 relative (measured over
// the scales below; a 1-ulp change of one velocity moves it by nothing).
// 1e-11 leaves a margin of 8.
constexpr double collapse_time_relative = 1e-11;

// The sticky gas, exact engine against event engine: the tolerance of
// tests/physics/test_exact_vs_event.cpp (velocity roundings of ~10 ulp in
// merges change T by ~10 ulp relative; 1e-12 there too).
constexpr double sticky_temperature_relative = 1e-12;

const CollisionModel elastic_threshold{0.5, 1e-2, Subthreshold::elastic};
const CollisionModel sticky_gas{0.0, 0.0, Subthreshold::elastic};
const CollisionModel pure_inelastic{0.5, 0.0, Subthreshold::elastic};  // collapses

struct EngineCase {
    const char* engine;
    CollisionModel model;
};
const std::vector<EngineCase> every_engine = {
    {"event", elastic_threshold}, {"reference", elastic_threshold}, {"passthrough", elastic_threshold},
    {"hybrid", elastic_threshold}, {"exact", sticky_gas},           {"event", sticky_gas},
    {"event", pure_inelastic},    {"reference", pure_inelastic}};

std::string describe(const EngineCase& c) {
    char text[96];
    std::snprintf(text, sizeof text, "%s (r = %g, delta = %g)", c.engine, c.model.restitution,
                  c.model.velocity_threshold);
    return text;
}

struct Sample {
    std::uint64_t collisions = 0;
    std::int64_t clusters = 0;
    double temperature = 0.0;
    double mean_velocity = 0.0;  // in the lab
};
struct Trajectory {
    std::vector<Sample> samples;  // at the times reached
    ClusterState last;            // the state at the last time reached
    std::optional<CollapseReport> collapse;
    std::string failure;  // a NumericalFailure's message
    double switch_time = 0.0;  // Engine::switch_time() at the end (the hybrid's hand-over)
};

Trajectory follow(Engine& engine, const std::vector<double>& times) {
    Trajectory out;
    for (const double t : times) {
        if (!engine.advance_to(t)) {
            out.collapse = engine.collapse();
            break;
        }
        engine.clusters(out.last);
        const Moments moments = velocity_moments(out.last);
        out.samples.push_back(
            {engine.collisions(), engine.cluster_count(), moments.temperature, moments.mean_velocity});
    }
    out.switch_time = engine.switch_time();
    return out;
}

// The engine by name through the factory, as shockgas-sim runs it: after an
// EngineUndecided the realization is run again on the fallback engine, as the
// ensemble driver does.
Trajectory run(const EngineCase& c, const InitialCondition& initial, const std::vector<double>& times,
               const CollapseCriterion& collapse = {}) {
    SimulationParameters p;
    p.particles = initial.size();
    p.ring_length = initial.ring_length;
    p.collision = c.model;
    p.collapse = collapse;
    p.engine = c.engine;
    p.t_max = times.back();
    validate(p);
    try {
        try {
            const auto engine = make_engine(p, initial, nullptr);
            return follow(*engine, times);
        } catch (const EngineUndecided&) {
            const auto engine = make_fallback_engine(p, initial, nullptr);
            return follow(*engine, times);
        }
    } catch (const NumericalFailure& failure) {
        Trajectory out;
        out.failure = failure.what();
        return out;
    }
}

// b must be a itself: the same collisions, clusters and collapse, and T equal
// to `temperature_relative` (both within the noise floor of a single cluster,
// whose T is the rounding of its velocity: the sticky gas's final state).
void expect_same_dynamics(const Trajectory& a, const Trajectory& b, double temperature_relative,
                          const std::string& where) {
    EXPECT_EQ(b.failure, a.failure) << where;
    ASSERT_EQ(b.samples.size(), a.samples.size()) << where << ": reached another number of sample times";
    for (std::size_t s = 0; s < a.samples.size(); ++s) {
        EXPECT_EQ(b.samples[s].collisions, a.samples[s].collisions) << where << ", sample " << s;
        EXPECT_EQ(b.samples[s].clusters, a.samples[s].clusters) << where << ", sample " << s;
        const double floor = a.samples[s].clusters == 1 ? std::pow(16.0 * epsilon_machine, 2) : 0.0;
        EXPECT_LE(std::abs(b.samples[s].temperature - a.samples[s].temperature),
                  temperature_relative * a.samples[s].temperature + floor)
            << where << ", sample " << s << ": T " << b.samples[s].temperature << " against "
            << a.samples[s].temperature;
    }
    ASSERT_EQ(b.collapse.has_value(), a.collapse.has_value()) << where;
    if (a.collapse) {
        EXPECT_EQ(b.collapse->criterion, a.collapse->criterion) << where;
        EXPECT_EQ(b.collapse->cluster_mass, a.collapse->cluster_mass) << where;
    }
}

// The times of the runs: early (most collisions inelastic), and late, past
// the cooling into the elastic regime (r = 0.5, delta = 1e-2: about 3e5
// collisions at t = 300 for N = 1000).
const std::vector<double> sample_times = {3.0, 30.0, 300.0};
constexpr std::int64_t particles = 1000;
constexpr std::uint64_t seed = 1;

std::vector<double> scaled_times(double lambda) {
    std::vector<double> times;
    for (const double t : sample_times) times.push_back(lambda * t);
    return times;
}

// ---------------------------------------------------------------------------
// Scale: the start a user gets with --ring-length lambda N, run to lambda t.

// The stall criterion's window shortened from max(10^6, 10 N) to 10^4 events
// (10 N), so that a criterion tied to an absolute time would fire within these
// short runs (3e5 collisions), as the default window does at 10^6 events in
// the longer runs below (UserRunsAtTinySpacings): with a floor of 1, every event of a
// ring with L/N = 1e-16 is "within 1e-12 of the last".
CollapseCriterion short_stall_window() {
    CollapseCriterion criterion;
    criterion.stall_events_min = 10000;
    return criterion;
}

TEST(Symmetries, ScaleFromTenToTheMinus300To10To300ChangesNothing) {
    // Powers of two scale every operation exactly (the first two and last
    // two, 2^-996 = 1.5e-300 and 2^996 = 6.7e299); powers of ten start from
    // i L/N rounded otherwise, the same start up to rounding.
    const double lambdas[] = {0x1p-996, 1e-300, 1e-200, 1e-100, 1e-18, 1e-16, 1e16, 1e100, 1e200, 1e300, 0x1p996};
    for (const EngineCase& c : every_engine) {
        const Trajectory base = run(c, generate_initial_condition(particles, static_cast<double>(particles), seed, 0),
                                    sample_times, short_stall_window());
        ASSERT_TRUE(base.failure.empty()) << describe(c) << ": " << base.failure;
        if (c.model.velocity_threshold > 0.0 || c.model.restitution == 0.0) {
            ASSERT_EQ(base.samples.size(), sample_times.size()) << describe(c) << ": stopped at L = N";
        }
        for (const double lambda : lambdas) {
            const InitialCondition initial =
                generate_initial_condition(particles, lambda * static_cast<double>(particles), seed, 0);
            const Trajectory scaled = run(c, initial, scaled_times(lambda), short_stall_window());
            char where[160];
            std::snprintf(where, sizeof where, "%s, lambda = %g", describe(c).c_str(), lambda);
            expect_same_dynamics(base, scaled, temperature_rounding, where);
            // The hybrid hands over at the same instant of the scaled run
            // (its checks are at 1.25^k L/N), and so writes lambda times the
            // same /timeseries/engine_switch_time.
            if (std::isfinite(base.switch_time)) {
                EXPECT_NEAR(scaled.switch_time / lambda, base.switch_time, hand_over_time_relative * base.switch_time)
                    << where << ": hand-over time";
            }
            if (base.collapse && scaled.collapse) {
                EXPECT_NEAR(scaled.collapse->time / lambda, base.collapse->time,
                            collapse_time_relative * base.collapse->time)
                    << where << ": collapse time";
            }
        }
    }
}

// Two runs a user asks for, through the event and hybrid engines, with the
// default stall criterion: shockgas-sim -N 1000 --ring-length 1e-13 (and
// 1e-15) -r 0.5 -d 0.01 -t 1e-10 (and 1e-12). A criterion with an absolute
// floor (max(1, t)) stops the second as a "collapse" at t = 2.02e-14, where
// its first 10^6 events fall within 1e-12 of each other.
TEST(Symmetries, UserRunsAtTinySpacingsCompleteWithIdenticalCollisionCounts) {
    for (const char* engine : {"event", "hybrid"}) {
        const EngineCase c{engine, elastic_threshold};
        const Trajectory first = run(c, generate_initial_condition(particles, 1e-13, seed, 0), {1e-10});
        const Trajectory second = run(c, generate_initial_condition(particles, 1e-15, seed, 0), {1e-12});
        ASSERT_EQ(first.samples.size(), 1u) << engine << ": " << first.failure;
        ASSERT_EQ(second.samples.size(), 1u)
            << engine << ": " << second.failure
            << (second.collapse ? " (collapsed: " + second.collapse->criterion + ")" : "");
        EXPECT_EQ(first.samples[0].collisions, 2920912u) << engine;
        EXPECT_EQ(second.samples[0].collisions, first.samples[0].collisions) << engine;
        EXPECT_EQ(second.samples[0].temperature, first.samples[0].temperature) << engine;
    }
}

// ---------------------------------------------------------------------------
// Galilean shifts: velocities on the grid 2^-20 (|v| <= 1), so v + u is exact
// for |u| <= 2^32.

InitialCondition on_velocity_grid() {
    InitialCondition initial = generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
    for (double& v : initial.velocity) v = std::round(v * 0x1p20) * 0x1p-20;
    return initial;
}

InitialCondition shifted(InitialCondition initial, double u) {
    for (double& v : initial.velocity) v += u;
    return initial;
}

// The chaos horizon at these times: the run against itself with one initial
// velocity changed by one ulp. What such a change does to the collision count
// and T is what a shift may do at most. Measured with
// the particles 0, 1, 2, 500 and 999 nudged, on this grid start and on the
// generated one, at r = 0.9, delta = 1e-2; r = 0.5, delta = 1e-3 and 1e-2 to
// t = 300: no change at all, collision count and T equal to the last bit (a
// change of one ulp is rounded away in the next collisions). The tolerance is
// measured again here, on the particle below, for each engine.
constexpr std::size_t nudged_particle = 500;

struct Horizon {
    std::uint64_t collisions = 0;  // largest |difference| of the counts at a sample
    double temperature_relative = 0.0;
};
Horizon chaos_horizon(const Trajectory& base, const Trajectory& nudged) {
    Horizon h;
    for (std::size_t s = 0; s < std::min(base.samples.size(), nudged.samples.size()); ++s) {
        const auto a = base.samples[s].collisions;
        const auto b = nudged.samples[s].collisions;
        h.collisions = std::max(h.collisions, a > b ? a - b : b - a);
        const double a_temperature = base.samples[s].temperature;
        const double b_temperature = nudged.samples[s].temperature;
        h.temperature_relative =
            std::max(h.temperature_relative, std::abs(b_temperature - a_temperature) / a_temperature);
    }
    return h;
}

// Positions after a shift: the engines' frame moves at V = u here, and its
// positions are moved into the lab by u t mod L, reduced before rounding
// (frame_to_lab_positions): one rounding of a number below L, and one of the
// wrap. 4 ulp of L.
constexpr double lab_position_ulps = 4.0;

TEST(Symmetries, GalileanShiftUpTo1e9ChangesOnlyTheMeanVelocity) {
    const InitialCondition base_start = on_velocity_grid();
    InitialCondition nudged_start = base_start;
    nudged_start.velocity[nudged_particle] = std::nextafter(nudged_start.velocity[nudged_particle], 2.0);
    const double ring_length = base_start.ring_length;
    const double ulp_of_ring = std::nextafter(ring_length, 2.0 * ring_length) - ring_length;
    const double position_tolerance = lab_position_ulps * ulp_of_ring;
    for (const EngineCase& c : every_engine) {
        const Trajectory base = run(c, base_start, sample_times);
        ASSERT_FALSE(base.samples.empty()) << describe(c);
        const Horizon horizon = chaos_horizon(base, run(c, nudged_start, sample_times));
        std::printf("%s: chaos horizon at t = 3, 30, 300: %llu collisions, T %.3g relative\n", describe(c).c_str(),
                    static_cast<unsigned long long>(horizon.collisions), horizon.temperature_relative);
        for (const double u : {1e3, -1e3, 1e6, -1e6, 1e9, -1e9}) {
            const Trajectory moved = run(c, shifted(base_start, u), sample_times);
            char where[160];
            std::snprintf(where, sizeof where, "%s, u = %g", describe(c).c_str(), u);
            ASSERT_EQ(moved.samples.size(), base.samples.size()) << where;
            ASSERT_EQ(moved.collapse.has_value(), base.collapse.has_value()) << where;
            if (base.collapse) {
                // The same collapse: the frame runs the same numbers.
                EXPECT_EQ(moved.collapse->time, base.collapse->time) << where;
                EXPECT_EQ(moved.collapse->cluster_mass, base.collapse->cluster_mass) << where;
            }
            for (std::size_t s = 0; s < base.samples.size(); ++s) {
                const auto a = base.samples[s].collisions;
                const auto b = moved.samples[s].collisions;
                EXPECT_LE(a > b ? a - b : b - a, horizon.collisions) << where << ", t = " << sample_times[s];
                EXPECT_EQ(moved.samples[s].clusters, base.samples[s].clusters) << where;
                EXPECT_LE(std::abs(moved.samples[s].temperature - base.samples[s].temperature),
                          horizon.temperature_relative * base.samples[s].temperature)
                    << where << ", t = " << sample_times[s];
                // The mean velocity moves by u, to the rounding of that addition.
                EXPECT_EQ(moved.samples[s].mean_velocity, u + base.samples[s].mean_velocity) << where;
            }
            // Every cluster where the unshifted one is, moved by u t on the ring.
            const ClusterState& a = base.last;
            const ClusterState& b = moved.last;
            ASSERT_EQ(a.size(), b.size()) << where;
            const double shift = std::fmod(u * a.time, ring_length);
            for (std::size_t k = 0; k < a.size(); ++k) {
                ASSERT_EQ(b.first_particle[k], a.first_particle[k]) << where;
                const double expected = wrap_position(a.position[k] + shift, ring_length);
                const double d = std::abs(b.position[k] - expected);
                EXPECT_LE(std::min(d, ring_length - d), position_tolerance) << where << ", cluster " << k;
                EXPECT_EQ(b.lab_velocity(k), u + a.lab_velocity(k)) << where << ", cluster " << k;
            }
        }
    }
}

// The frame itself (state.hpp): at rest for the paper's start, whatever N;
// moved by u for a shifted one.
TEST(Symmetries, FrameIsAtRestForThePapersStartAndFollowsAShift) {
    for (const std::int64_t n : {2, 3, 10, 1000}) {
        for (std::uint64_t s = 0; s < 20; ++s) {
            const InitialCondition initial = generate_initial_condition(n, static_cast<double>(n), s, 0);
            EXPECT_EQ(frame_velocity(initial.velocity, initial.mass), 0.0) << "N = " << n << ", seed " << s;
        }
    }
    const InitialCondition grid = on_velocity_grid();
    for (const double u : {1e3, -1e6, 1e9}) {
        const InitialCondition moved = shifted(grid, u);
        EXPECT_EQ(frame_velocity(moved.velocity, moved.mass), u);
    }
}

// ---------------------------------------------------------------------------
// Mirror image and rotation. On the lattice with L = N the positions are
// integers, so L - x and x - x_m + 1/2 are exact: the transformed start is
// exactly the mirrored or the turned and relabelled one. The rotation turns
// the ring by half a spacing besides, so that no particle starts at 0: the
// seam falls between other particles than on the original ring.

InitialCondition mirrored(const InitialCondition& base) {
    InitialCondition out = base;
    const std::size_t n = base.position.size();
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t j = (n - k) % n;  // particle j is the k-th from 0 going left
        out.position[k] = k == 0 ? 0.0 : base.ring_length - base.position[j];
        out.velocity[k] = -base.velocity[j];
    }
    return out;
}

InitialCondition rotated(const InitialCondition& base, std::size_t m) {
    InitialCondition out = base;
    const std::size_t n = base.position.size();
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t j = (k + m) % n;
        out.position[k] = base.position[j] - base.position[m] + 0.5 + (j < m ? base.ring_length : 0.0);
        out.velocity[k] = base.velocity[j];
        out.mass[k] = base.mass[j];
    }
    return out;
}

TEST(Symmetries, MirrorImageAndRotationOfTheRingChangeNothing) {
    const InitialCondition start = generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
    for (const EngineCase& c : every_engine) {
        const Trajectory base = run(c, start, sample_times);
        const Trajectory mirror = run(c, mirrored(start), sample_times);
        expect_same_dynamics(base, mirror, temperature_rounding, describe(c) + ", mirror image");
        for (std::size_t s = 0; s < std::min(base.samples.size(), mirror.samples.size()); ++s)
            EXPECT_EQ(mirror.samples[s].mean_velocity, -base.samples[s].mean_velocity) << describe(c);
        for (const std::size_t m : {1, 337}) {
            const Trajectory rotation = run(c, rotated(start, m), sample_times);
            expect_same_dynamics(base, rotation, temperature_rounding,
                                 describe(c) + ", rotated by " + std::to_string(m));
        }
        if (base.collapse && mirror.collapse) {
            EXPECT_NEAR(mirror.collapse->time, base.collapse->time, collapse_time_relative * base.collapse->time)
                << describe(c);
        }
    }
}

// ---------------------------------------------------------------------------
// The sticky gas: the exact engine (no events) against the event engine on
// each transformed start, cluster count for cluster count.

TEST(Symmetries, StickyGasExactEngineAgreesWithEventEngineUnderEveryTransformation) {
    const InitialCondition start = generate_initial_condition(particles, static_cast<double>(particles), seed, 0);
    const InitialCondition grid = on_velocity_grid();
    struct Transformed {
        std::string name;
        InitialCondition initial;
        std::vector<double> times;
    };
    const std::vector<Transformed> starts = {
        {"identity", start, sample_times},
        {"scale 1e-300", generate_initial_condition(particles, 1e-300 * particles, seed, 0), scaled_times(1e-300)},
        {"scale 1e300", generate_initial_condition(particles, 1e300 * particles, seed, 0), scaled_times(1e300)},
        {"shift 1e9", shifted(grid, 1e9), sample_times},
        {"shift -1e9", shifted(grid, -1e9), sample_times},
        {"mirror", mirrored(start), sample_times},
        {"rotation", rotated(start, 337), sample_times}};
    for (const Transformed& t : starts) {
        const Trajectory exact = run({"exact", sticky_gas}, t.initial, t.times);
        const Trajectory event = run({"event", sticky_gas}, t.initial, t.times);
        expect_same_dynamics(exact, event, sticky_temperature_relative, "sticky gas, " + t.name);
    }
}

}  // namespace
