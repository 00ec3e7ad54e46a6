// SPDX-License-Identifier: GPL-3.0-or-later
// What the ensemble driver reports while it runs (run_ensemble's progress
// callback): facts about each realization, not estimates. How long the rest
// will take, and how a program shows it, is shockgas/cli/progress.hpp's
// business (cli::ProgressEstimator), so that improving an estimate is no
// change to the simulator.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace shockgas {

// One realization of the running block, as the driver last saw it.
struct RealizationProgress {
    enum class State { waiting, running, finished };
    State state = State::waiting;
    double time = 0.0;             // simulated time reached
    std::uint64_t collisions = 0;  // collisions so far, including those before a resumed checkpoint
};

// What the driver reports, about once a second. fraction_done, shown_time and
// eta_seconds are left for an estimator to fill (cli::ProgressEstimator);
// programs that know their work otherwise (shockgas-tail) fill fraction_done
// themselves.
struct Progress {
    double elapsed_seconds = 0.0;
    double t_max = 0.0;
    std::int64_t realizations_done = 0;  // finished, not stopped by a signal
    std::int64_t realizations = 0;
    // Collisions this process has computed (not those before a resumed
    // checkpoint), and their rate over elapsed_seconds: the rate at which work
    // is being done now.
    std::uint64_t collisions_this_process = 0;
    double collisions_per_second = 0.0;
    std::vector<RealizationProgress> realization;  // one per realization of the block
    // Filled by an estimator:
    double fraction_done = 0.0;  // share of the work done, in [0, 1]
    double shown_time = 0.0;     // the slowest running realization's t (t_max once all are done)
    double eta_seconds = -1.0;   // negative when not yet estimable
};
using ProgressCallback = std::function<void(const Progress&)>;

}  // namespace shockgas
