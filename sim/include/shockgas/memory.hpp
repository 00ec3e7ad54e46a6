// Memory planning: a run's need, estimated before anything is allocated, set
// against what the process may use, so that a run too large for the machine
// is refused with one line (or runs fewer realizations at once) instead of
// being killed by the kernel's OOM killer with nothing written.
#pragma once

#include <string>

#include "shockgas/parameters.hpp"

namespace shockgas {

// Bytes the process may still allocate: the smaller of MemAvailable
// (/proc/meminfo) and the room left under a cgroup limit (v2 memory.max
// minus memory.current, v1 memory.limit_in_bytes minus memory.usage_in_bytes).
// `source` says which bound it is. Negative if neither can be read.
double available_memory_bytes(std::string* source = nullptr);

// "8G", "500M", "1.5GiB", "123456" (bytes): powers of 1024. Throws InputError.
double parse_memory_size(const std::string& text);

// "1.2 GiB"
std::string format_bytes(double bytes);

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
