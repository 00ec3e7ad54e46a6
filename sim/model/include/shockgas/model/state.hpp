// SPDX-License-Identifier: GPL-3.0-or-later
// Initial conditions and the state of the ring at one time, shared by every
// engine (event-driven and exact) so that both read and report the same way.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "shockgas/model/parameters.hpp"

namespace shockgas {

// Particles on a ring of length ring_length, in ring order: positions
// non-decreasing in [0, ring_length). Unit masses unless given.
struct InitialCondition {
    double ring_length = 0.0;
    std::vector<double> position;
    std::vector<double> velocity;
    std::vector<double> mass;

    std::int64_t size() const { return static_cast<std::int64_t>(position.size()); }
};

// A generated initial condition: N particles on a ring of length L, unit
// masses, positions and velocities from `law` (default: the paper's, equally
// spaced x_i = i L / N with velocities i.i.d. uniform on [-1, 1)).
// Realization k of seed s draws from std::mt19937_64 seeded with
// splitmix64(s, k): first the N velocities, then (uniform positions only) the
// N positions, so a seed gives the same velocities whatever the position law.
// Every variate is built from the generator's 64-bit outputs by our own code
// (not std::uniform_real_distribution or std::normal_distribution, whose
// algorithms differ between standard libraries, nor std::log), so a seed means
// the same start on every platform with IEEE double arithmetic.
InitialCondition generate_initial_condition(std::int64_t particles, double ring_length, std::uint64_t seed,
                                            std::int64_t realization, const InitialLaw& law = {});

// Standard deviation of both velocity laws: uniform on [-1, 1) has variance
// 1/3, and the Gaussian law is given the same, so T(0) = 1/3 either way.
inline constexpr double initial_velocity_sigma = 0.57735026918962576451;  // 1/sqrt(3)

// Uniform variate on [0, 1) from the top 53 bits of one 64-bit output.
double unit_uniform(std::mt19937_64& engine);
// Standard normal variates, two at a time: Marsaglia's polar method (Marsaglia
// & Bray, SIAM Review 6, 260 (1964)) with portable_log, so the values are
// identical on every platform. Consumes an even, seed-determined number of
// outputs (the rejection loop); the second variate is returned through second.
double standard_normal_pair(std::mt19937_64& engine, double& second);
// log x for finite x > 0 from +, -, *, / and frexp only (IEEE-exact
// operations, hence the same bits everywhere), accurate to a few ulp:
// log x = e ln 2 + 2 atanh(z), z = (m - 1)/(m + 1), m in [1/sqrt 2, sqrt 2).
double portable_log(double x);

// The seed stream: a well-mixed 64-bit seed for realization k of run seed s.
std::uint64_t realization_seed(std::uint64_t seed, std::int64_t realization);

void validate(const InitialCondition& initial);  // throws InputError
// Throws InputError if the start's speeds would carry positions beyond what
// doubles hold by t_max: max |v| t_max, which bounds the distance any particle
// and the frame (frame_velocity) travel, at most largest_travel
// (parameters.hpp). For an --init file; generated starts are bounded by
// generated_speed_bound.
void validate_travel(const InitialCondition& initial, double t_max);

// The run's own time unit: the mean spacing L/N over the velocity unit (the
// initial velocity scale, 1, in which delta and the collapse speed are
// given). Space and time scale together (x -> lambda x, t -> lambda t is an
// exact symmetry of the model), so every time tolerance of the engines is a
// multiple of this, never of an absolute time. 1 for the paper's L = N.
inline double time_unit(const InitialCondition& initial) {
    return initial.ring_length / static_cast<double>(initial.size());
}

// The engines' frame (docs/model.md, "The engines' frame"): a velocity V near
// the centre-of-mass velocity of the start. Every engine advances the
// velocities v - V and positions in the frame moving at V, and reports V
// beside them (ClusterState::frame_velocity), so a Galilean shift of the
// start costs no precision: the common motion is not carried in each
// velocity. V = q round(V_cm / q), q the power of two at or above the
// velocity spread max v - min v, or V = 0 while |V_cm| is below the velocity
// unit (1). So
//  * for the paper's start (|v| <= 1, hence |V_cm| < 1) V = 0 and the
//    engines' arithmetic is unchanged, bit for bit; below the unit the common
//    motion costs at most ulp(1) per velocity, the resolution every default
//    run has;
//  * for a start shifted by u (|u| >= 1 and a multiple of q, as any
//    |u| >= 2^53 q is), V moves by u, and v + u - V is exact whenever v + u
//    is (Sterbenz: |v + u - V| <= spread + q/2 <= 1.5 q, so v + u and V are
//    within a factor 2 of each other once |V| >= 3 q): the engines run the
//    unshifted velocities bit for bit.
// All velocities equal: V is that velocity (if at least 1 in size).
double frame_velocity(const std::vector<double>& velocity, const std::vector<double>& mass);

// Clusters at one time, in ring order starting from the cluster whose slot
// (index of its leftmost particle) is smallest. Positions wrapped into [0, L),
// in the lab. Velocities are relative to frame_velocity: cluster k moves at
// frame_velocity + velocity[k] in the lab. Galilean-invariant quantities
// (the temperature, velocity differences) are computed from `velocity`
// alone, to full precision; lab velocities (lab_velocity) are rounded once.
struct ClusterState {
    double time = 0.0;
    double frame_velocity = 0.0;
    std::vector<double> position;
    std::vector<double> velocity;
    std::vector<double> mass;
    std::vector<std::int64_t> first_particle;

    std::size_t size() const { return velocity.size(); }
    double lab_velocity(std::size_t k) const { return frame_velocity + velocity[k]; }
    void clear() {
        position.clear();
        velocity.clear();
        mass.clear();
        first_particle.clear();
    }
};

// Positions of a state computed in the frame moving at V (positions at
// `time` in the frame, wrapped into [0, L)) moved into the lab: each x
// becomes x + V t mod L. V t is reduced mod L before it is rounded (its
// exact product hi + lo by fma, fmod exact), so the shift carries one
// rounding of a number below L, however large V t. Nothing changes for V = 0.
void frame_to_lab_positions(ClusterState& state, double ring_length);

// The physical state of an equal-or-unequal-mass ring in the middle of a run,
// for handing a realization from one engine to another (HybridEngine): one
// entry per particle in ring order from particle 0, positions unwrapped
// (non-decreasing up to contact rounding, the last at most the first + L),
// the time they hold at, and the collisions counted so far.
struct MidRunState {
    double ring_length = 0.0;
    double time = 0.0;
    double frame_velocity = 0.0;  // positions and velocities are in the frame moving at this (frame_velocity())
    std::uint64_t collisions = 0;
    std::uint64_t inelastic_collisions = 0;  // of those, at or above delta (a diagnostic)
    std::vector<double> position;
    std::vector<double> velocity;
    std::vector<double> mass;
};

// Wraps x into [0, L).
double wrap_position(double x, double ring_length);

// Where the ring closes in a list of positions in ring order, each wrapped
// into [0, L) (walk_ring's output): going once round, the differences
// x[k+1] - x[k] fall by L exactly once, at the pair k that crosses x = L -> 0.
// That is the most negative difference (the first, on a tie); any other
// negative one is an overlap. Not "difference < -L/2": a cooled gas clusters
// and leaves voids longer than L/2. The gap after k is the difference, plus L
// at the closing pair. Needs at least one position.
inline std::size_t closing_pair(const std::vector<double>& position) {
    const std::size_t n = position.size();
    std::size_t closing = 0;
    double most_negative = position[1 % n] - position[0];
    for (std::size_t k = 1; k < n; ++k) {
        const double d = position[(k + 1) % n] - position[k];
        if (d < most_negative) {
            most_negative = d;
            closing = k;
        }
    }
    return closing;
}

}  // namespace shockgas
