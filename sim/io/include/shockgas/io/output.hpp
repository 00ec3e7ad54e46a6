// SPDX-License-Identifier: GPL-3.0-or-later
// The simulation output schema (documented in docs/cli-and-output.md, "Output files").
// Writer and reader live together so that the schema is defined once.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "shockgas/model/records.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace h5 {
class Group;
}

struct OutputFile;

// Writes the whole result atomically (temporary file, then rename): root
// attributes (every parameter, status, provenance) and the datasets
// /timeseries, /snapshots, /histograms, /collapse.
void write_output(const std::string& path, const SimulationParameters& parameters, const EnsembleResult& result);
// The output of shockgas-merge: as write_output, with the parts' provenance kept
// (program, version, and the date and host of the first part: when and where the
// run was made, not merged) and the merge's own beside it: merged_by (program
// and version), merged_date (UTC) and merged_from (merged.merged_from, one line each).
void write_merged_output(const std::string& path, const OutputFile& merged, const std::string& program);

// Root attributes naming every parameter; used by write_output and by any
// other writer of the same schema.
void write_parameter_attributes(h5::Group& root, const SimulationParameters& parameters);

// The part of an output file that analysis needs most: the time series.
struct TimeSeries {
    std::vector<double> time;                    // K
    std::int64_t realizations = 0;               // R
    std::vector<double> temperature;             // R x K, row-major
    std::vector<double> collisions_per_particle; // R x K
    std::vector<double> clusters;                // R x K
    std::vector<double> kinetic_energy;          // R x K
    std::string status;
    double at(const std::vector<double>& table, std::int64_t realization, std::size_t k) const {
        return table[static_cast<std::size_t>(realization) * time.size() + k];
    }
};
TimeSeries read_timeseries(const std::string& path);

// A whole output file read back: the parameters (from the root attributes)
// and every dataset, in the form the driver produced them.
struct OutputFile {
    SimulationParameters parameters;
    EnsembleResult result;
    std::string version;  // provenance: git describe of the program that wrote it
    std::string simulator_sha256;  // and its simulator's source hash (empty from builds that did not record it)
    std::string date;     // provenance: when the run was made (UTC; a merged file: its first part's)
    std::string host;     // provenance: where (a merged file: its first part's host)
    // Set by merge_outputs: the parts, in order, each "NAME (realizations F to L)"
    // followed by that part's own merged_from indented by two spaces (a merged
    // part), which write_merged_output records beside the merge's own provenance
    // and read_output reads back (empty for a file that was not merged).
    std::vector<std::string> merged_from;
};
// Refuses (InputError) a checkpoint, and (h5::Error, naming the file and
// the dataset) a file whose datasets disagree in shape or whose statuses are
// not an output's.
OutputFile read_output(const std::string& path);
// The one refusal of a checkpoint (a run in progress) given where an output
// is read: read_output's, and shockgas-analyze's check of every input.
InputError checkpoint_given_as_output(const std::string& path);
// What a file is when it says it is not a shockgas-sim output, from its root:
// its program attribute (an analysis results file, a far-tail sampler file,
// shockgas-drift's record), or an initial condition's datasets; empty for an
// output, and for a file that says nothing (one from before provenance, one
// made by hand), which the readers take as before.
std::string other_kind_of_file(const h5::Group& root);
// Whether root is a shockgas-tail far-tail file (its root attribute kind = far_tail, which the
// sampler writes): the one test for it, for other_kind_of_file and the analysis's readers.
bool is_far_tail_file(const h5::Group& root);
// Refuses, in one line, a file given where a shockgas-sim output is read that
// is something else: "'PATH' is not a shockgas-sim output: it is <what>" (a
// checkpoint: checkpoint_given_as_output). read_output and read_timeseries
// call it, and every analysis reader of a run through them or itself, so a
// wrong file is named for what it is rather than by the first attribute or
// group it lacks ("missing group /timeseries").
void check_simulation_output(const h5::Group& root, const std::string& path);

// The drawn start's law a run's root attributes record (positions,
// velocity_distribution); the paper's law for a file written before the laws
// existed. A start read from an init file (root attribute init_file) has no
// law: read_output leaves the default there, and so should every caller.
InitialLaw read_initial_law(const h5::Group& root);

// One stored ring state (a snapshot or a collapse state: time, position,
// velocity, mass, first_particle) from its group; throws h5::Error naming
// file and dataset if the four datasets do not have one value per cluster.
ClusterState read_cluster_state(const h5::Group& group, const std::string& file);

// Joins ensemble parts run with --first-realization k0, k0 + R0, ... into the
// result a single run of all realizations gives (identical datasets). Throws
// InputError naming the part that differs in parameters, engine, version, or
// leaves a gap in the realization sequence.
OutputFile merge_outputs(const std::vector<OutputFile>& parts, const std::vector<std::string>& names);

// A checkpoint of a run in progress (written by run_ensemble every
// CheckpointOptions::interval_seconds and when interrupted): the partial
// result in the output schema, with realization_status 4 (in progress) for
// the unfinished realizations, how many sample times each realization has
// done, and the engine state of each unfinished one.
struct Checkpoint {
    SimulationParameters parameters;
    EnsembleResult result;
    std::vector<std::int64_t> samples_done;          // per realization
    std::map<std::int64_t, EngineSnapshot> engines;  // realization index -> state
    std::string version;                             // provenance of the writer
    std::string simulator_sha256;                    // the writer's source hash (empty from builds that did not record it)
    std::string signature;                           // run_signature of the writer's parameters
    std::string source;                              // the file it was read from
};
// Written atomically; with keep_previous_as, an existing checkpoint at path is
// first renamed to that name (checkpoint.hpp keeps two generations).
void write_checkpoint(const std::string& path, const Checkpoint& checkpoint, const std::string& keep_previous_as = "");
Checkpoint read_checkpoint(const std::string& path);  // throws InputError / h5::Error naming the problem
// <output>.checkpoint: where shockgas-sim keeps the checkpoint of <output>.
std::string checkpoint_path_for(const std::string& output_path);
// Every parameter that decides a run's datasets (physics, sampling, seed,
// realization range), as one string: a checkpoint resumes only a run with
// the same signature.
std::string run_signature(const SimulationParameters& parameters);
// The same without the realization range: checkpoints of one run cut into
// other blocks (MPI ranks, --first-realization parts) share it.
std::string physics_signature(const SimulationParameters& parameters);
// Every parameter of physics_signature in which b differs from a, as
// "restitution 0.6 vs 0.5, seed 2 vs 1" (b's value first; long option names):
// the one wording of shockgas-merge's and --resume's refusals. Empty if none.
std::string parameter_differences(const SimulationParameters& a, const SimulationParameters& b);

}  // namespace shockgas
