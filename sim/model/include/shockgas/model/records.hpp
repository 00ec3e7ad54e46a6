// SPDX-License-Identifier: GPL-3.0-or-later
// What runs produce and keep, as plain data: the collapse report, an engine's
// saved state, and the ensemble's result tables. The engines fill them, the run
// collects them, the I/O layer writes and reads them, and the analysis reads
// them; none of those needs another's code to use them.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "shockgas/model/state.hpp"

namespace shockgas {

// Recorded when inelastic collapse stops a run (delta = 0).
struct CollapseReport {
    double time = 0.0;
    std::int64_t left_slot = 0;        // the pair whose collision triggered detection
    std::int64_t cluster_mass = 0;     // particles in the collapsing cluster (see engine docs)
    double relative_speed = 0.0;       // of the triggering collision
    std::string criterion;             // "relative_speed" or "stall"
};

// An engine's whole state between two events, for checkpoints: named arrays
// stored as they are (doubles bit for bit), so that an engine restored from it
// continues exactly as the one that made it would have. `kind` names the
// engine class that can read it.
struct EngineSnapshot {
    std::string kind;
    std::map<std::string, std::vector<double>> reals;
    std::map<std::string, std::vector<std::int64_t>> integers;
};

// in_progress appears only in checkpoints: a realization whose engine state
// the checkpoint holds.
enum class RealizationStatus : std::int64_t { complete = 0, collapsed = 1, interrupted = 2, not_run = 3, in_progress = 4 };

struct SnapshotRecord {
    std::int64_t realization = 0;
    ClusterState state;
};

struct HistogramRecord {
    double time = 0.0;
    std::vector<double> edges;   // bins + 1 edges of v - V (velocity units)
    std::vector<double> counts;  // R x (bins + 2): underflow, bins, overflow; mass-weighted
};

struct CollapseRecord {
    std::int64_t realization = 0;
    CollapseReport report;
    std::uint64_t collisions = 0;
    ClusterState state;  // the ring at the moment of collapse
};

struct EnsembleResult {
    std::vector<double> times;  // K sample times
    std::int64_t realizations = 0;
    // R x K, row-major; NaN where a realization did not reach the time.
    std::vector<double> temperature;
    std::vector<double> collisions_per_particle;
    std::vector<double> clusters;
    std::vector<double> kinetic_energy;
    std::vector<SnapshotRecord> snapshots;    // ordered by (realization, time)
    std::vector<HistogramRecord> histograms;  // ordered by time
    std::vector<CollapseRecord> collapses;    // ordered by realization
    std::vector<std::int64_t> realization_status;
    // R: Engine::switch_time() of each realization when it stopped (NaN for
    // engines that never switch, +infinity for a hybrid that had not).
    std::vector<double> engine_switch_time;
    std::string status;  // complete | interrupted | collapsed
    std::string engine;
    std::uint64_t total_collisions = 0;
    double cpu_seconds = 0.0;
    double wall_seconds = 0.0;
    double peak_memory_bytes = 0.0;  // resident set high-water mark of the process
};

// The R x K tables of EnsembleResult, for code that copies or joins rows.
using SampleTable = std::vector<double> EnsembleResult::*;
inline constexpr std::array<SampleTable, 4> sample_tables = {
    &EnsembleResult::temperature, &EnsembleResult::collisions_per_particle, &EnsembleResult::clusters,
    &EnsembleResult::kinetic_energy};

// Room for `realizations` realizations in r: the sample tables and histogram
// rows of the new ones are NaN and zero, their status not_run, their hand-over
// time NaN (what a realization that never ran records). Existing rows stay.
void grow_realizations(EnsembleResult& r, std::int64_t realizations);

// Realization j of `from` becomes realization k of `to` (which must have room
// for it, grow_realizations), replacing whatever `to` held for k: its rows of
// the sample tables and histograms, its status and hand-over time, and its
// snapshots and collapse records, renumbered and kept in the order
// EnsembleResult promises. If `to` has no histograms yet it takes `from`'s
// times and edges. The one way realizations move between results: joining
// parts (merge_outputs) and gathering a block from other blocks'
// checkpoints (gather_checkpoint).
void copy_realization(const EnsembleResult& from, std::int64_t j, EnsembleResult& to, std::int64_t k);

}  // namespace shockgas
