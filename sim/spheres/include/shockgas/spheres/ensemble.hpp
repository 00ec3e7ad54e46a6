// SPDX-License-Identifier: GPL-3.0-or-later
// The ensemble driver of the disk and sphere gas: realizations in parallel,
// each sampled at the sample grid, and the HDF5 output that holds them
// (docs/spheres.md, "Output"). Realization k writes only its own rows and
// draws from seed stream first_realization + k, so any thread count gives the
// same datasets, bit for bit.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shockgas/run/progress.hpp"
#include "shockgas/spheres/engine.hpp"
#include "shockgas/spheres/parameters.hpp"

namespace shockgas::h5 {
class Group;
}

namespace shockgas::spheres {

// One snapshot time: realization 0's particles, and every realization's
// coarse-grained fields on field_cells^d cells of side L / field_cells:
// the number density relative to the mean, N_cell / (N / cells), and the
// mean velocity of each cell's particles (0 in an empty cell).
struct SphereSnapshot {
    double time = 0.0;
    std::vector<double> positions;        // N x d, realization 0
    std::vector<double> velocities;       // N x d, realization 0
    std::vector<double> density;          // R x cells
    std::vector<double> velocity_field;   // R x cells x d
};

// Histogram of the velocity components scaled by the temperature, u_k / sqrt(T)
// (u = v - V, V the mean velocity), over every realization and component:
// histogram_bins bins on [-range, range]; those outside are counted apart.
struct SphereHistogram {
    double time = 0.0;
    std::vector<double> counts;
    double outside = 0.0;
};

struct SphereResult {
    std::vector<double> time;                     // K sample times
    std::int64_t realizations = 0;                // R
    std::vector<double> temperature;              // R x K
    std::vector<double> collisions_per_particle;  // R x K: 2 (collisions) / N
    std::vector<double> velocity_kurtosis;        // R x K: <u_k^4> / <u_k^2>^2 over particles and components
    std::vector<SphereHistogram> histograms;
    std::vector<SphereSnapshot> snapshots;
    std::vector<std::string> status;              // per realization: complete | collapsed
    std::vector<double> end_time;                 // per realization: t reached (the collapse's, if collapsed)
    CollisionCounts counts;                       // summed over realizations
    double start_seconds = 0.0;                   // CPU spent making the starts (melting)
    double cpu_seconds = 0.0;
    double wall_seconds = 0.0;
    bool interrupted = false;                     // stopped (SphereRunOptions::stop); resume from the checkpoint
    double at(const std::vector<double>& table, std::int64_t realization, std::size_t k) const {
        return table[static_cast<std::size_t>(realization) * time.size() + k];
    }
};

// The CPU seconds this thread has used (what the ensemble's start_seconds and
// bench_spheres count).
double thread_cpu_seconds();

// <u^4> / <u^2>^2 over every particle and component, u = v - V (3 for Maxwell).
double velocity_kurtosis(const std::vector<double>& velocities, int dimension);

// Where and how often a run keeps a checkpoint, and the flag that stops it.
//  - Each realization saves its engine (EngineRecord) and its rows into the
//    checkpoint at least every checkpoint_interval_seconds of wall time, and
//    when stopped; the file is written whole, atomically, keeping the one it
//    replaces as CHECKPOINT.previous (the fallback if the newer is damaged).
//  - resume continues every realization from the checkpoint, bit for bit as an
//    uninterrupted run; a checkpoint of other parameters is refused, one of
//    another build of the engine (spheres_sha256) is passed over with a note
//    and the run starts anew. Without resume an existing checkpoint is refused.
//  - Once the output is written the checkpoint is removed (remove_spheres_checkpoint).
struct SphereRunOptions {
    std::string checkpoint;
    double checkpoint_interval_seconds = 600.0;
    bool resume = false;
    // Also save the checkpoint when the run ends: a rank of an MPI job whose
    // block finished while another rank was stopped keeps its realizations
    // for --resume (run_spheres_job).
    bool checkpoint_when_done = false;
    const std::atomic<bool>* stop = nullptr;  // raised by a signal handler: the run saves and returns
    std::function<void(const std::string&)> note;  // one-line notes (resumed, fell back to .previous)
};

// Runs the ensemble; progress gets a report about once a second (may be empty).
// A stopped run returns with interrupted set (and its checkpoint saved).
SphereResult run_spheres(const SphereParameters& parameters, const ProgressCallback& progress = {},
                         const SphereRunOptions& options = {});
// Removes both generations of a finished run's checkpoint.
void remove_spheres_checkpoint(const std::string& checkpoint);

// How an output was joined from blocks, recorded as root attributes with the
// names shockgas-sim's files use: mpi_ranks (an MPI job of more than one
// rank), and merged_by, merged_date, merged_from (shockgas-merge).
struct JoinRecord {
    std::int64_t mpi_ranks = 1;
    std::string merged_by;                 // program and version; empty: not merged
    std::vector<std::string> merged_from;  // each part, "NAME (realizations F to L)"
};

// Writes the result atomically with every parameter and the provenance as
// root attributes (schema in docs/spheres.md), and reads it back.
void write_spheres_output(const std::string& path, const SphereParameters& parameters, const SphereResult& result,
                          const JoinRecord& joined = {});
struct SphereOutput {
    SphereParameters parameters;
    SphereResult result;
    std::string version;
    std::string spheres_sha256;
};
SphereOutput read_spheres_output(const std::string& path);
// Whether the file is an output of shockgas-spheres (its root attribute schema).
bool is_spheres_output(const std::string& path);

// Ensemble parts (--first-realization k, or MPI ranks' blocks), in
// realization order, joined into the result one run of all their realizations
// gives, bit for bit: rows concatenated, histograms and counts summed, the
// particle snapshots of the first part (realization 0's). Refuses
// (InputError, naming the part) parts of other parameters, of another build
// of the engine, or that leave a gap or overlap in the realizations.
// merged_from gets a line per part: "NAME (realizations F to L)".
struct JoinedParts {
    SphereParameters parameters;
    SphereResult result;
    std::vector<std::string> merged_from;
};
JoinedParts join_spheres_parts(const std::vector<SphereOutput>& parts, const std::vector<std::string>& names);

// SHA-256 over what decides this simulation's numbers (sim/spheres with the
// model, the I/O layer and the progress record it uses; compiler and flags),
// recorded in every output as spheres_sha256 and the pipeline's stamp.
const std::string& spheres_sha256();

// Every parameter as root attributes, and back; what differs between two
// parameter sets, as "name a vs b" items (empty: the same run).
void write_parameter_attributes(shockgas::h5::Group& root, const SphereParameters& parameters);
SphereParameters read_parameter_attributes(const shockgas::h5::Group& root);
std::vector<std::string> parameter_differences(const SphereParameters& a, const SphereParameters& b);

}  // namespace shockgas::spheres
