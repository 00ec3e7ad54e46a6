// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/run/memory_plan.hpp"

#include "shockgas/io/memory_limits.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace shockgas {

namespace {

// Peak resident memory of one realization at N = 10^6, every engine and
// collision mode (docs/reliability.md, "Memory"): 115-122 bytes per particle
// for a running realization's engine, 133 more while its state is copied into
// a checkpoint, about 15 MB for the program. Rounded up so the estimate stays
// an upper bound.
constexpr double engine_bytes_per_particle = 128.0;
// The pass-through engine (and the hybrid, which ends in it) holds more per
// line: spares, heat, and a kinetic block's copy and queue, which early on span
// nearly the whole ring: 229 bytes per particle beyond the program at its peak
// (N = 10^6, r = 0.9, delta = 1e-2 to t = 30); rounded up.
constexpr double passthrough_bytes_per_particle = 240.0;
// Where collapse is possible (r > 0, delta below --collapse-speed: every
// delta = 0 run) the event engine also keeps a copy of its 48-byte records to
// go back to (event_engine.hpp): 163 bytes per particle beyond the program at
// its peak (N = 10^6, r = 0.9, delta = 0 to t = 30); rounded up.
constexpr double collapsing_engine_bytes_per_particle = 176.0;
constexpr double checkpoint_bytes_per_particle = 136.0;
constexpr double program_bytes = 16.0 * (1 << 20);
// A stored ring state (snapshot or collapse record): position, velocity,
// mass, first particle, 8 bytes each per cluster, and at most N clusters.
constexpr double state_bytes_per_particle = 32.0;
// A histogram bin: 8 bytes in each realization's row while it runs and 8 more
// in the output's copy of that row, plus 16 once per histogram time (the edges,
// and HDF5's buffer while it writes): 31 bytes per bin at the peak with one
// realization, 70 with four (N = 1000, one histogram time, 10^7 bins).
constexpr double histogram_bytes_per_bin_per_realization = 16.0;
constexpr double histogram_bytes_per_bin_shared = 16.0;

}  // namespace

MemoryPlan plan_memory(const SimulationParameters& p, int threads, bool checkpoints, double budget_bytes) {
    const auto particles = static_cast<double>(p.particles);
    const auto realizations = static_cast<double>(p.realizations);
    MemoryPlan plan;
    const double engine_bytes = p.engine == "passthrough" || p.engine == "hybrid"
                                    ? passthrough_bytes_per_particle
                                : collapse_possible(p.collision, p.collapse) ? collapsing_engine_bytes_per_particle
                                                                             : engine_bytes_per_particle;
    plan.per_realization_bytes = particles * (engine_bytes + (checkpoints ? checkpoint_bytes_per_particle : 0.0));
    // Kept for every realization until the output is written: its snapshots,
    // a collapse record when δ = 0 (a run may collapse), its rows of the time
    // series (four tables of K samples) and of the histograms.
    const double samples = static_cast<double>(sample_grid(p).size());
    const double states = static_cast<double>(p.snapshot_times.size()) +
                          (p.collision.velocity_threshold == 0.0 ? 1.0 : 0.0);
    const double histogram_bins = static_cast<double>(p.histogram_times.size()) * (p.histogram_bins + 2.0);
    const double per_realization_kept = particles * state_bytes_per_particle * states + 4.0 * 8.0 * samples +
                                        histogram_bytes_per_bin_per_realization * histogram_bins;
    plan.kept_bytes = per_realization_kept;
    plan.shared_bytes = program_bytes + histogram_bytes_per_bin_shared * histogram_bins +
                        realizations * per_realization_kept;
    const double room = budget_bytes - plan.shared_bytes;
    const double fit = room > 0.0 ? std::floor(room / plan.per_realization_bytes) : 0.0;
    plan.realizations_at_once = static_cast<int>(std::min<double>(std::max(threads, 1), fit));
    return plan;
}

std::string memory_refusal(const SimulationParameters& p, const MemoryPlan& plan, double budget_bytes,
                           const std::string& source) {
    // A run of one realization needs the program, its engine and its own
    // records; each further realization adds only its records (time series,
    // snapshots, histogram rows), kept until the output is written. Where one
    // alone would fit, it is their number that does not: lowering N does not
    // help a million realizations of N = 1000.
    // The program itself is a fixed part that no N lowers: a budget below it
    // ("--max-memory 1K") is told to raise the budget, not to lower N.
    if (program_bytes >= budget_bytes)
        return fmt::format("not enough memory: any run needs more than {} (the program itself, whatever N), but {} "
                           "may be used ({}); {}",
                           format_bytes(program_bytes), format_bytes(budget_bytes), source,
                           source == "--max-memory" ? "raise --max-memory"
                                                    : "free memory or raise the limit, then set --max-memory");
    const double records = static_cast<double>(p.realizations) * plan.kept_bytes;
    const double one_alone = plan.need_bytes(1) - records + plan.kept_bytes;
    if (p.realizations > 1 && one_alone <= budget_bytes) {
        const double most = std::floor((budget_bytes - one_alone) / plan.kept_bytes) + 1.0;
        return fmt::format(
            "not enough memory: {} realizations need about {}, {} of it for their records (time series, snapshots, "
            "histograms), kept until the output is written, but {} may be used ({}); give each run at most {:.0f} "
            "realizations: split the ensemble into parts with -R and --first-realization and join them with "
            "shockgas-merge, or set --max-memory",
            p.realizations, format_bytes(plan.need_bytes(1)), format_bytes(records), format_bytes(budget_bytes),
            source, most);
    }
    return fmt::format(
        "not enough memory: one realization of N = {} needs about {} ({} of it the program itself, whatever N), but "
        "{} may be used ({}); lower N, the snapshots or the histogram bins, or set --max-memory",
        p.particles, format_bytes(one_alone), format_bytes(program_bytes), format_bytes(budget_bytes), source);
}

}  // namespace shockgas
