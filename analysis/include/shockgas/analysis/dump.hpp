// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-dump as a library call: parts of HDF5 files as plain text for
// gnuplot. The program (analysis/app/shockgas_dump.cpp) binds its options to a
// DumpRequest and calls run_dump.
//   snapshots     rows "time position velocity mass first_particle" of every
//                 snapshot of one realization, one block (blank lines) each
//   gnuplot-vars  each numeric attribute of a group as "P_name = value", each
//                 string attribute as P_name = "value"
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "shockgas/model/state.hpp"

namespace shockgas {

// The snapshots of one realization of a shockgas-sim output, in file order,
// each checked to hold one value per cluster in every dataset
// (read_cluster_state). InputError for a negative realization, one the file
// does not have, and a file without snapshots or without one of that
// realization, rather than print a header with nothing under it.
std::vector<ClusterState> read_realization_snapshots(const std::string& path, std::int64_t realization);

// The snapshots as text: a header naming path, then one block of rows
// "time position velocity mass first_particle" each, two newlines after it.
void write_snapshot_rows(std::FILE* out, const std::string& path, const std::vector<ClusterState>& states);

// The attributes of the group at group_path ("/decay", "" or "/" for the root)
// as gnuplot variables prefix_name, one a line: numbers to 10 digits (NaN for
// one that is not finite, which gnuplot does not read otherwise), strings in
// double quotes (a double quote or newline in one becomes '); other kinds
// skipped. recursive: every subgroup's too, as prefix_<subgroup>_name.
std::string gnuplot_variables(const std::string& path, const std::string& group_path, const std::string& prefix,
                              bool recursive);

struct DumpRequest {
    enum class Kind { snapshots, gnuplot_vars };
    Kind kind = Kind::snapshots;
    std::string input;
    std::string output;            // empty: standard output
    std::int64_t realization = 0;  // snapshots
    std::string group_path;        // gnuplot-vars
    std::string prefix = "fit";
    bool recursive = false;
};

// Reads and checks the input in full before the output is opened, and writes
// a file output beside its name, renamed into place when complete
// (TextFile): a bad input or a failed write (a full disk) leaves no output,
// nor an empty or partial one that a plot would take for the real thing. An
// output that names the input is refused.
void run_dump(const DumpRequest& request);

}  // namespace shockgas
