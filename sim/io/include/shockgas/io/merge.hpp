// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-merge as a library call: ensemble parts (shockgas-sim
// --first-realization k) joined into one file with the datasets a single run
// of all realizations writes. The program (sim/app/shockgas_merge.cpp) parses
// the paths, calls merge_parts and prints merge_summary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shockgas {

struct MergeOutcome {
    std::int64_t realizations = 0;  // in the merged file
    std::size_t parts = 0;
    std::string status;  // the merged run's status
};

// Joins the part files, in realization order, into output (written
// atomically). Its root attributes are the run's (the first part's date and
// host) and merged_by (program), merged_date and merged_from say that and how
// it was merged. Refuses (InputError) an output that cannot be written or that
// names a part, a part made by another simulator than this build (the merged
// file records this build's provenance), and parts that do not join
// (merge_outputs).
MergeOutcome merge_parts(const std::vector<std::string>& inputs, const std::string& output, const std::string& program);

// "5 realizations from 2 parts -> OUTPUT (complete)": what was merged, for the
// program's line on stderr.
std::string merge_summary(const MergeOutcome& outcome, const std::string& output);

}  // namespace shockgas
