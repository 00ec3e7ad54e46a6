// SPDX-License-Identifier: GPL-3.0-or-later
// Memory planning: a run's need, estimated before anything is allocated, set
// against what the process may use, so that a run too large for the machine
// is refused with one line (or runs fewer realizations at once) instead of
// being killed by the kernel's OOM killer with nothing written.
#pragma once

#include <string>

#include "shockgas/io/memory_limits.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

struct MemoryPlan {
    double per_realization_bytes = 0.0;  // one realization running (engine, and its checkpoint copies)
    double shared_bytes = 0.0;           // the program, and what every realization keeps until the output
    double kept_bytes = 0.0;             // of shared_bytes, what each realization keeps (its records)
    int realizations_at_once = 0;        // at most `threads`; 0 if not even one fits
    double need_bytes(int at_once) const { return shared_bytes + at_once * per_realization_bytes; }
};

// The plan for `threads` realizations in flight under budget_bytes (see
// docs/reliability.md, "Memory", for the measured costs behind it).
MemoryPlan plan_memory(const SimulationParameters& parameters, int threads, bool checkpoints, double budget_bytes);

// Why a plan of which not even one realization fits is refused, as one line
// naming what does not fit: one realization (N, its snapshots, the histogram
// bins), or, where that alone would fit, the records that every one of many
// realizations keeps until the output is written (then: fewer realizations
// per run, the parts joined with shockgas-merge). source names the budget.
std::string memory_refusal(const SimulationParameters& parameters, const MemoryPlan& plan, double budget_bytes,
                           const std::string& source);

}  // namespace shockgas
