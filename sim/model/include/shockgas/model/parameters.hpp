// SPDX-License-Identifier: GPL-3.0-or-later
// Parameters of one shockgas simulation: the physics (collision model), the
// system (ring, particles) and what to record. One struct, validated in one
// place, so the CLI, the parameter files and the tests cannot disagree.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace shockgas {

// What happens to a colliding pair whose relative speed is below the
// velocity threshold delta (the paper's two sub-threshold mechanisms).
enum class Subthreshold { elastic, sticky };

std::string to_string(Subthreshold mechanism);
Subthreshold subthreshold_from_string(const std::string& name);  // throws InputError

// The initial law of a generated start (docs/model.md, "Initial conditions").
// Positions: lattice x_i = i L / N (the paper's), or uniform: N i.i.d.
// uniform points on [0, L), sorted. Velocities: uniform on [-1, 1) (the
// paper's), or Gaussian with the same variance 1/3, so T(0) is the same.
enum class PositionLaw { lattice, uniform };
enum class VelocityLaw { uniform, gaussian };
struct InitialLaw {
    PositionLaw positions = PositionLaw::lattice;
    VelocityLaw velocities = VelocityLaw::uniform;
    bool is_paper() const { return positions == PositionLaw::lattice && velocities == VelocityLaw::uniform; }
};
std::string to_string(PositionLaw law);
std::string to_string(VelocityLaw law);
PositionLaw position_law_from_string(const std::string& name);  // throws InputError
VelocityLaw velocity_law_from_string(const std::string& name);  // throws InputError

// The collision model of the paper: restitution r = 1 - 2 eps above the
// threshold, the sub-threshold mechanism below it. r = 0 is the sticky gas:
// every collision merges, whatever the threshold.
struct CollisionModel {
    double restitution = 0.9;         // r in [0, 1]
    double velocity_threshold = 1e-2; // delta >= 0; 0 is the pure inelastic gas
    Subthreshold subthreshold = Subthreshold::elastic;
};

// Inelastic collapse (delta = 0, r > 0) is detected, not hung on. A run is
// declared collapsed at the first inelastic collision whose relative speed is
// below collapse_speed (geometric decay of relative speeds is the signature of
// collapse, McNamara & Young 1992) while three or more clusters are in contact
// (a slow pair alone is a cooled gas), or when max(stall_events_min, 10 N) consecutive events
// advance simulated time by less than stall_time_fraction * max(L/N, t): relative to t, and
// near t = 0 to the run's time unit L/N (time_unit, state.hpp), never to an absolute time, so
// that the criterion scales with the ring (x -> lambda x, t -> lambda t). Where collapse is
// impossible (delta > 0, or r = 0) a stall is a numerical failure instead (NumericalFailure).
struct CollapseCriterion {
    double collapse_speed = 1e-12;        // in units of the initial velocity scale (1)
    double stall_time_fraction = 1e-12;   // advance of t, relative to max(L/N, t), regarded as no advance
    std::uint64_t stall_events_min = 1000000;  // the stall window is max(this, 10 N) events
};

// Whether a run can collapse: r > 0 and a collision can be inelastic (g >= delta)
// while slower than the collapse speed, as in every delta = 0 run.
inline bool collapse_possible(const CollisionModel& model, const CollapseCriterion& criterion) {
    return model.restitution > 0.0 && !(criterion.collapse_speed <= model.velocity_threshold);
}

struct SimulationParameters {
    std::int64_t particles = 1000;    // N
    double ring_length = 0.0;         // L; 0 means L = N (unit spacing)
    CollisionModel collision;
    CollapseCriterion collapse;
    double t_max = 1000.0;
    int samples_per_decade = 10;
    std::vector<double> sample_times;     // extra times, merged with the log grid
    std::vector<double> snapshot_times;
    std::vector<double> histogram_times;
    int histogram_bins = 160;
    double histogram_range = 4.0;     // bins cover |v - V_cm| t^(1/3) <= range
    int realizations = 1;
    // Realization k of this run uses the seed stream of realization
    // first_realization + k, so an ensemble can be split into parts (resumable
    // figure runs, MPI ranks) and merged into exactly the single-run result.
    std::int64_t first_realization = 0;
    std::uint64_t seed = 1;
    int threads = 0;                  // 0: every hardware thread
    InitialLaw initial_law;           // for generated starts; an --init file replaces it
    std::string init_file;            // optional --init FILE.h5 (absolute path once read)
    std::string init_file_sha256;     // its SHA-256, so a result proves which start made it
    std::string engine = "event";     // event | reference | exact | passthrough | hybrid | auto (resolved before run)

    double effective_ring_length() const {
        return ring_length > 0.0 ? ring_length : static_cast<double>(particles);
    }
};

// Thrown for any input a user can get wrong: a parameter out of range, a
// malformed init file, an unwritable output path. The message is one line that
// names the problem; the CLI prints it and exits nonzero.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Thrown when a run meets what double precision cannot resolve although the
// model allows it, and no input check could have foreseen it (a stall where
// collapse is impossible: events crowding at one instant). The message is one
// line naming the limit and what to change; an InputError, since the remedy
// is a change of input.
struct NumericalFailure : InputError {
    using InputError::InputError;
};

// The largest coordinates a run may form. The engines form positions of up
// to a few ring lengths (the pass-through engine's lines lie within one ring
// length either side of the ring, and its sort margins add up to four) plus
// the distance travelled, |v| t. With L <= 2^1020 and |v| t <= 2^1021 all of
// them stay below 2^1023, under the largest double (2^1024 less an ulp).
inline constexpr double largest_ring_length = 0x1p1020;  // about 1.1e307
inline constexpr double largest_travel = 0x1p1021;       // max |v| t_max, about 2.2e307
// t_max for a generated start, whose speeds are below this: uniform
// velocities are within [-1, 1], and a Gaussian one (sigma = 1/sqrt 3)
// exceeds 8 with probability 1e-43 per particle.
inline constexpr double generated_speed_bound = 8.0;
inline constexpr double largest_t_max = largest_travel / generated_speed_bound;  // 2^1018, about 2.8e306

// Throws InputError naming the first problem found. Besides the ranges of
// the options, the scales a run must resolve: the spacing L/N a normal double
// (at least 2.2e-308; below it numbers lose significant bits, so gaps are no
// longer resolved to double precision), L at most largest_ring_length and
// t_max at most largest_t_max (an --init file's speeds: validate_travel).
void validate(const SimulationParameters& parameters);

// The sample grid: samples_per_decade log-spaced times from t = 1 to t_max
// (t_max always included), merged with the listed sample, snapshot and
// histogram times, sorted, duplicates removed.
std::vector<double> sample_grid(const SimulationParameters& parameters);

// The times interval, 2 interval, ... up to t_max (each computed as k * interval,
// so the list is exact and reproducible); used by --snapshot-interval.
std::vector<double> evenly_spaced_times(double interval, double t_max);

}  // namespace shockgas
