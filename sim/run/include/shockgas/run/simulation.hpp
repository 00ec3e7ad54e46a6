// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-sim as a library call: what the program's options ask for
// (SimulationRequest), and the run that carries it out (run_simulation): read
// and check the start, refuse what cannot run, resume or set aside
// checkpoints, plan memory, run the ensemble (over MPI ranks when launched so),
// write the output and clear the checkpoints. The program
// (sim/app/shockgas_sim.cpp) only binds its options to these fields and shows
// the outcome; every default and everything done with the values is here, in
// the simulator's stamp, so editing the program's help text reruns nothing.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "shockgas/model/parameters.hpp"
#include "shockgas/model/records.hpp"
#include "shockgas/run/distributed.hpp"
#include "shockgas/run/ensemble.hpp"

namespace shockgas {

struct SimulationRequest {
    SimulationParameters parameters;
    std::string output = "shockgas.h5";
    std::string subthreshold = "elastic";          // elastic | sticky
    std::string positions = "lattice";             // lattice | uniform
    std::string velocity_distribution = "uniform"; // uniform | gaussian
    // Also snapshot every this much time (0: only parameters.snapshot_times).
    double snapshot_interval = 0.0;
    bool snapshot_interval_given = false;
    // Given on the command line: with an --init file they must agree with it.
    bool particles_given = false;
    bool ring_length_given = false;
    // Checkpoint file; empty: checkpoint_path_for(output).
    std::string checkpoint_file;
    // interval_seconds and resume from the options; note from the program.
    CheckpointOptions checkpoint;
    bool set_aside_other_runs = false;
    // Memory the run may use ("8G"); empty: what the machine leaves free.
    std::string max_memory;
};

// What the program needs from around the run: a flag the signal handlers raise,
// a hook called just before the ensemble starts (the program installs its
// signal handlers there, once the run is known to start), and where progress
// reports go (rank 0 only).
struct SimulationHooks {
    const std::atomic<bool>* stop = nullptr;
    std::function<void()> before_run;
    ProgressCallback progress;
};

struct SimulationOutcome {
    // Set on rank 0 when it wrote the output; empty on other ranks and when
    // there was nothing to do.
    std::optional<EnsembleResult> result;
    // Rank 0's one line when there was nothing to run (the output is already
    // this run's, complete).
    std::string nothing_to_do;
    // The program's exit status: 0, or 130 for an interrupted run.
    int exit_status = 0;
};

// Runs the request. Throws InputError for anything the user must change (one
// line saying what), h5::Error for files that cannot be read or written.
SimulationOutcome run_simulation(SimulationRequest& request, DistributedSession& session,
                                 const SimulationHooks& hooks);

}  // namespace shockgas
