// Initial conditions and the state of the ring at one time, shared by every
// engine (event-driven and exact) so that both read and report the same way.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

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

// The paper's initial condition: N particles equally spaced on a ring of
// length L (x_i = i L / N), velocities i.i.d. uniform on [-1, 1], unit masses.
// Realization k of seed s draws from std::mt19937_64 seeded with
// splitmix64(s, k); the uniform variate is built from the top 53 bits by hand
// (not std::uniform_real_distribution, whose algorithm differs between
// standard libraries), so a seed means the same velocities on every platform.
InitialCondition generate_initial_condition(std::int64_t particles, double ring_length, std::uint64_t seed,
                                            std::int64_t realization);

// The seed stream: a well-mixed 64-bit seed for realization k of run seed s.
std::uint64_t realization_seed(std::uint64_t seed, std::int64_t realization);

// Reads --init FILE.h5: datasets position, velocity, optional mass, and the
// root attribute ring_length. Throws InputError with a one-line message for
// any problem (missing dataset, length mismatch, unsorted or out-of-range
// positions, non-finite values, non-positive masses).
InitialCondition read_initial_condition(const std::string& path);
void write_initial_condition(const std::string& path, const InitialCondition& initial);
void validate(const InitialCondition& initial);  // throws InputError

// Clusters at one time, in ring order starting from the cluster whose slot
// (index of its leftmost particle) is smallest. Positions wrapped into [0, L).
struct ClusterState {
    double time = 0.0;
    std::vector<double> position;
    std::vector<double> velocity;
    std::vector<double> mass;
    std::vector<std::int64_t> first_particle;

    std::size_t size() const { return velocity.size(); }
    void clear() {
        position.clear();
        velocity.clear();
        mass.clear();
        first_particle.clear();
    }
};

// Wraps x into [0, L).
double wrap_position(double x, double ring_length);

}  // namespace shockgas
