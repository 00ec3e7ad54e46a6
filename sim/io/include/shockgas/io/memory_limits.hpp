// SPDX-License-Identifier: GPL-3.0-or-later
// What the machine lets a process allocate, read from /proc and the cgroup
// files, and the one way sizes in bytes are written and read: shared by the
// run's memory plan (shockgas/run/memory_plan.hpp) and the programs that check
// a request against free memory before the work (shockgas-burgers).
#pragma once

#include <string>

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

}  // namespace shockgas
