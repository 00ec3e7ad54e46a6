// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/model/state.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "shockgas/model/observables.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace {
// SplitMix64 finaliser (Steele, Lea & Flood 2014): decorrelates nearby seeds.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}
}  // namespace

std::uint64_t realization_seed(std::uint64_t seed, std::int64_t realization) {
    return splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(realization));
}

double unit_uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

double portable_log(double x) {
    int exponent = 0;
    double mantissa = std::frexp(x, &exponent);  // x = mantissa 2^exponent, mantissa in [1/2, 1)
    if (mantissa < 0.70710678118654752440) {      // 1/sqrt(2): centre the series on m = 1
        mantissa *= 2.0;
        --exponent;
    }
    const double z = (mantissa - 1.0) / (mantissa + 1.0);  // |z| <= 0.1716, z^2 <= 0.0295
    const double z2 = z * z;
    // atanh z = z sum_k z^(2k) / (2k + 1); 14 terms leave z2^14 < 1e-21 relative.
    double series = 0.0;
    for (int k = 13; k >= 0; --k) series = 1.0 / (2.0 * k + 1.0) + z2 * series;
    // ln 2 split into a head exact in 32 bits and a tail, so e ln2_head is exact.
    constexpr double ln2_head = 0.693147180369123816490;
    constexpr double ln2_tail = 1.90821492927058770002e-10;
    const double e = static_cast<double>(exponent);
    return e * ln2_head + (2.0 * z * series + e * ln2_tail);
}

double standard_normal_pair(std::mt19937_64& engine, double& second) {
    // Marsaglia's polar method: (a, b) uniform in the unit disc (rejection),
    // s = a^2 + b^2; then a sqrt(-2 ln s / s) and b sqrt(-2 ln s / s) are two
    // independent standard normals. sqrt is IEEE-exact; the log is ours.
    for (;;) {
        const double a = 2.0 * unit_uniform(engine) - 1.0;
        const double b = 2.0 * unit_uniform(engine) - 1.0;
        const double s = a * a + b * b;
        if (s >= 1.0 || s == 0.0) continue;
        const double factor = std::sqrt(-2.0 * portable_log(s) / s);
        second = b * factor;
        return a * factor;
    }
}

InitialCondition generate_initial_condition(std::int64_t particles, double ring_length, std::uint64_t seed,
                                            std::int64_t realization, const InitialLaw& law) {
    InitialCondition initial;
    initial.ring_length = ring_length;
    const auto n = static_cast<std::size_t>(particles);
    initial.position.resize(n);
    initial.velocity.resize(n);
    initial.mass.assign(n, 1.0);
    std::mt19937_64 engine(realization_seed(seed, realization));
    if (law.velocities == VelocityLaw::uniform) {
        // u in [0, 1); v = 2u - 1 uniform on [-1, 1), variance 1/3.
        for (std::size_t i = 0; i < n; ++i) initial.velocity[i] = 2.0 * unit_uniform(engine) - 1.0;
    } else {
        for (std::size_t i = 0; i < n; i += 2) {
            double second = 0.0;
            initial.velocity[i] = initial_velocity_sigma * standard_normal_pair(engine, second);
            if (i + 1 < n) initial.velocity[i + 1] = initial_velocity_sigma * second;
        }
    }
    if (law.positions == PositionLaw::lattice) {
        const double spacing = ring_length / static_cast<double>(particles);
        for (std::size_t i = 0; i < n; ++i) initial.position[i] = static_cast<double>(i) * spacing;
    } else {
        // N i.i.d. uniform points, sorted into ring order (the velocities are
        // i.i.d. and independent of the positions, so pairing the k-th
        // velocity with the k-th point from the left keeps the law).
        for (std::size_t i = 0; i < n; ++i) {
            const double x = unit_uniform(engine) * ring_length;
            // u L can round up to L itself: keep x in [0, L).
            initial.position[i] = x < ring_length ? x : std::nextafter(ring_length, 0.0);
        }
        std::sort(initial.position.begin(), initial.position.end());
    }
    return initial;
}

void validate(const InitialCondition& initial) {
    const auto n = initial.position.size();
    if (!(initial.ring_length > 0.0) || !std::isfinite(initial.ring_length))
        throw InputError(fmt::format("init: ring_length must be positive and finite, got {}", initial.ring_length));
    if (n < 2) throw InputError(fmt::format("init: need at least 2 particles, got {}", n));
    if (initial.velocity.size() != n)
        throw InputError(fmt::format("init: velocity has {} values but position has {}", initial.velocity.size(), n));
    if (initial.mass.size() != n)
        throw InputError(fmt::format("init: mass has {} values but position has {}", initial.mass.size(), n));
    for (std::size_t i = 0; i < n; ++i) {
        const double x = initial.position[i];
        if (!std::isfinite(x)) throw InputError(fmt::format("init: position[{}] is not finite", i));
        if (!std::isfinite(initial.velocity[i])) throw InputError(fmt::format("init: velocity[{}] is not finite", i));
        if (!std::isfinite(initial.mass[i]) || initial.mass[i] <= 0.0)
            throw InputError(fmt::format("init: mass[{}] must be positive and finite, got {}", i, initial.mass[i]));
        if (x < 0.0 || x >= initial.ring_length)
            throw InputError(fmt::format("init: position[{}] = {} lies outside [0, ring_length = {})", i, x,
                                         initial.ring_length));
        if (i > 0 && x < initial.position[i - 1])
            throw InputError(fmt::format("init: positions are not sorted: position[{}] = {} < position[{}] = {}", i, x,
                                         i - 1, initial.position[i - 1]));
    }
}

void validate_travel(const InitialCondition& initial, double t_max) {
    double fastest = 0.0;
    for (const double v : initial.velocity) fastest = std::max(fastest, std::abs(v));
    if (fastest * t_max > largest_travel)
        throw InputError(fmt::format(
            "init: speeds up to {} carry particles {:.3g} far by t_max = {}, beyond {:.3g} (2^1021), where "
            "positions would overflow double precision; give a smaller t_max",
            fastest, fastest * t_max, t_max, largest_travel));
}

double frame_velocity(const std::vector<double>& velocity, const std::vector<double>& mass) {
    if (velocity.empty()) return 0.0;
    const auto [lowest, highest] = std::minmax_element(velocity.begin(), velocity.end());
    const double spread = *highest - *lowest;
    CompensatedSum momentum, total_mass;
    for (std::size_t i = 0; i < velocity.size(); ++i) {
        momentum.add(mass[i] * velocity[i]);
        total_mass.add(mass[i]);
    }
    const double centre_of_mass = momentum.value() / total_mass.value();
    // Below the velocity unit the frame stays at rest (the header's first case).
    if (!(std::abs(centre_of_mass) >= 1.0)) return 0.0;
    if (!(spread > 0.0)) return velocity.front();
    if (!std::isfinite(spread)) return 0.0;  // speeds near overflow: no frame can help
    // q: the power of two at or above the spread (frexp: spread = m 2^e, m in [1/2, 1)).
    int exponent = 0;
    const double mantissa = std::frexp(spread, &exponent);
    const double q = std::ldexp(1.0, mantissa == 0.5 ? exponent - 1 : exponent);
    // From 2^53 q on, every double is a multiple of q already (and V_cm / q
    // could overflow).
    if (std::abs(centre_of_mass) >= std::ldexp(q, 53)) return centre_of_mass;
    return q * std::round(centre_of_mass / q) + 0.0;  // + 0.0: a frame of -0 is +0
}

void frame_to_lab_positions(ClusterState& state, double ring_length) {
    if (state.frame_velocity == 0.0) return;
    // V t = hi + lo exactly; hi mod L is exact (fmod), so the shift is
    // (hi mod L) + lo, in (-L, L + |lo|), with one rounding.
    const double hi = state.frame_velocity * state.time;
    const double lo = std::fma(state.frame_velocity, state.time, -hi);
    const double shift = std::fmod(hi, ring_length) + lo;
    for (double& x : state.position) x = wrap_position(x + shift, ring_length);
}

double wrap_position(double x, double ring_length) {
    double wrapped = x - ring_length * std::floor(x / ring_length);
    if (wrapped >= ring_length) wrapped -= ring_length;  // floor rounding at the top edge
    if (wrapped < 0.0) wrapped = 0.0;
    return wrapped;
}

}  // namespace shockgas
