// SPDX-License-Identifier: GPL-3.0-or-later
// Spreading one ensemble over processes: under `mpirun -np K shockgas-sim`
// (build option SHOCKGAS_MPI) each rank runs a contiguous block of the
// realizations and rank 0 joins the blocks into the file a single process
// writes. Realization k always uses seed stream first_realization + k, so the
// joined datasets are bit-identical to a one-process run with the same seeds.
//
// Two implementations of this one interface: distributed_mpi.cpp (MPI) and
// distributed_serial.cpp (one rank, no MPI), so shockgas-sim's main compiles
// the same calls in both builds.
//
// Failure rule: no rank is left waiting for another. A rank that fails before
// share() makes every rank's share() throw; a rank that leaves main between
// share() and reduce() (an exception during its run) aborts the whole job; a
// rank whose block cannot be sent makes rank 0's reduce() throw.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include "shockgas/run/ensemble.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

// Realizations [first, first + count) of an ensemble of `total` split evenly
// over `ranks` ranks: the first (total mod ranks) ranks take one more, ranks
// beyond `total` take none. Pure arithmetic, shared by both builds and tests.
struct RealizationBlock {
    std::int64_t first = 0;
    std::int64_t count = 0;
};
inline RealizationBlock realization_block(std::int64_t total, int rank, int ranks) {
    const std::int64_t base = total / ranks, extra = total % ranks;
    return {rank * base + std::min<std::int64_t>(rank, extra), base + (rank < extra ? 1 : 0)};
}

class DistributedSession {
public:
    // Initializes MPI when started by an MPI launcher (MPI build); must be the
    // first thing main does, since MPI_Init may consume arguments from argv.
    // Without a launcher the program is one rank and never touches MPI.
    DistributedSession(int& argc, char**& argv);
    // Finalizes MPI; see the failure rule above.
    ~DistributedSession();
    DistributedSession(const DistributedSession&) = delete;
    DistributedSession& operator=(const DistributedSession&) = delete;

    int rank() const { return rank_; }
    int ranks() const { return ranks_; }
    bool is_root() const { return rank_ == 0; }

    // Collective: every rank has parsed and validated its arguments. Returns
    // this rank's share of the ensemble (first_realization shifted, realizations
    // possibly 0 on idle ranks, threads = 0 resolved to the cores this rank may
    // use). Throws InputError when another rank failed before reaching here.
    // nothing_to_do is rank 0's decision (the other ranks' value is not read)
    // that the job has nothing to run (--resume of an output that is already
    // the run's): then every rank gets nullopt and may leave main at once.
    std::optional<SimulationParameters> share(const SimulationParameters& whole, bool nothing_to_do = false);

    // Collective: sends each rank's result (run with `mine` from share(), or
    // nothing when mine.realizations == 0) to rank 0, which returns the joined
    // result of the whole ensemble; other ranks return nullopt. Throws on rank
    // 0, naming the rank, when a block could not be joined.
    std::optional<EnsembleResult> reduce(const SimulationParameters& mine, EnsembleResult result);

    // After reduce(), on every rank: whether rank 0 joined the whole ensemble
    // and it ran to its end (not interrupted). Only then may a rank remove its
    // checkpoint: a rank whose own block finished cannot tell from that alone
    // whether the job will end interrupted (another rank stopped by Ctrl-C),
    // and with its checkpoint gone --resume would run its block again.
    bool job_complete() const { return job_complete_; }

    // Rank 0, after writing the output: records the number of ranks as the
    // root attribute mpi_ranks (provenance only; no dataset changes). Does
    // nothing in a one-rank run, so such files equal the serial build's.
    void record_provenance(const std::string& output_path) const;

private:
    enum class Phase { setup, running, reduced };
    int rank_ = 0;
    int ranks_ = 1;
    Phase phase_ = Phase::setup;
    bool launched_ = false;  // MPI initialized (started by an MPI launcher)
    bool job_complete_ = false;
};

}  // namespace shockgas
