// What the ensemble driver reports while it runs (run_ensemble's progress
// callback); how a program shows it is shockgas/cli/progress.hpp's business.
#pragma once

#include <cstdint>
#include <functional>

namespace shockgas {

// What the driver reports while running, about once a second.
struct Progress {
    double fraction_done = 0.0;    // estimated share of the work done, in [0, 1]
    double latest_time = 0.0;      // simulated time of the most advanced running realization
    double collisions_per_second = 0.0;
    double elapsed_seconds = 0.0;
    double eta_seconds = 0.0;      // negative when not yet estimable
    std::int64_t realizations_done = 0;
    std::int64_t realizations = 0;
};
using ProgressCallback = std::function<void(const Progress&)>;

}  // namespace shockgas
