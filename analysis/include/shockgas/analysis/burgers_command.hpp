// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-burgers as a library call: what the program's options ask for
// (BurgersRequest, whose defaults are the program's), and the work
// (run_burgers): the Burgers profile from a particle run's initial condition,
// the particles' shocks against the Burgers shocks, and the convergence study
// (docs/continuum.md). The program (analysis/app/shockgas_burgers.cpp) only
// binds its options to these fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shockgas::analysis {

struct BurgersRequest {
    // The start: a shockgas-sim output (its N, L, seed and law, or its init
    // file), an init file, or N, L and the seed as shockgas-sim draws them.
    std::string run_path, init_path;
    std::int64_t particles = 0;
    double ring_length = 0.0;  // 0: N
    std::uint64_t seed = 1;
    std::int64_t realization = 0;
    double time = 0.0;  // 0: the run's first snapshot time
    std::int64_t cells_per_particle = 4;
    std::vector<double> viscosities;  // viscous profiles (Hopf-Cole) at these nu
    std::int64_t points = 0;          // output points; 0: four per particle
    double jump_fraction = 1.0;       // a counted shock drops v by >= this x v_rms
    // The profile data file, and optionally the gnuplot variables and the
    // convergence tables.
    std::string output, summary, study;
};

// The bytes a solve of `particles` particles takes, measured with
// /usr/bin/time: about 150 per particle and cell per particle (the start and
// the grid), 45 per output point (points; 0 means four per particle) and 20
// more per point and viscous profile; rounded up to 200, 48 and 24.
double burgers_memory_bytes(std::int64_t particles, std::int64_t cells_per_particle, std::int64_t points,
                            std::size_t viscosities);

// Refuses, before the work, a solve of `particles` particles that needs more
// memory than the machine offers (as shockgas-sim refuses a run): InputError
// naming both.
void check_burgers_memory(const BurgersRequest& request, std::int64_t particles);

// Checks the request's values and outputs, builds the start, solves Burgers
// at the time, prints the shock counts (and, with a run's snapshot at that
// time, the particles-against-Burgers distances) on stdout, and writes the
// outputs, each beginning with the program's provenance and the start.
// InputError for anything the user must change.
void run_burgers(BurgersRequest request);

}  // namespace shockgas::analysis
