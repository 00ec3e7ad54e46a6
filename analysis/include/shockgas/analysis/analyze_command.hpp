// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-analyze as a library call: what the program's options ask for
// (AnalyzeRequest, whose defaults are the program's), and the checks that come
// before any work followed by the subcommand's command (run_analyze, calling
// commands.hpp). The program (analysis/app/shockgas_analyze.cpp) binds its
// options to these fields and records its command line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/analysis/clusters.hpp"
#include "shockgas/analysis/commands.hpp"
#include "shockgas/analysis/cooling.hpp"
#include "shockgas/analysis/late_decay.hpp"
#include "shockgas/analysis/results.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/validity.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"

namespace shockgas::analysis {

struct AnalyzeRequest {
    // The subcommand: decay, crossover, scaling, shocks, collapse, compare, validity, far-tail, cooling, clusters or late-decay.
    std::string command;
    // The command line and the subcommand's options as run, for the results file.
    AnalysisInvocation invocation;
    // Files: each subcommand reads input, inputs or reference and inputs, and
    // writes output and the data files it is given (empty: none).
    std::string input, reference;
    std::vector<std::string> inputs;
    std::string output = "analysis.h5";
    std::string data, scan, hazard, curves;
    // cooling (shockgas-spheres outputs): the clustering table and the 2D picture's positions;
    // clusters: picture is the density maps' table (--maps).
    std::string clustering, picture;
    // clusters (shockgas-spheres outputs): the density threshold (relative to the mean) and the mass table.
    double threshold = 2.0;
    std::string distribution;
    // late-decay (shockgas-spheres outputs): the fit window and the slope, crossover and Delta v / v tables.
    LateDecayRule late_decay;
    std::string slopes, crossovers, fluctuations, tails, tail_fits;
    // decay: the window ends when given, and whether --scan-width was given.
    DecayOptions decay;
    double t_lo = 0.0, t_hi = 0.0;
    bool t_lo_given = false, t_hi_given = false, scan_width_given = false;
    // crossover: the Haff curve's rate, "fit" or "derived".
    CrossoverRule crossover;
    std::string haff_constant = "fit";
    // scaling
    TailRule tail;
    // shocks: merge_gap is signed, so that a negative value is refused rather
    // than wrapped around to 2^64 - 1.
    ShockRule shocks;
    std::int64_t merge_gap = static_cast<std::int64_t>(ShockRule{}.merge_gap_points);
    // collapse: what the inputs vary, "eps" or "N".
    std::string versus = "eps";
    // far-tail: the fit window and its systematic.
    double z_lo = 2.0, z_hi = 5.5, window_shift = 0.25;
    bool free_linear = false;
    // validity: the definitions of its observables, and the map's fidelity label.
    ValidityRule validity;
    std::string fidelity = "quick";
};

// Checks, before any work, that no input is a run in progress (a checkpoint),
// the subcommand's option values, and every output path (none may replace an
// input or another output): a bad value or an unwritable path never costs a
// long analysis. Then runs the subcommand's command. InputError for anything
// the user must change; an estimate the inputs cannot give (InsufficientData)
// becomes an InputError naming the inputs.
void run_analyze(AnalyzeRequest request);

// An argument as a POSIX shell reads it back: bare when it holds only
// characters no shell treats specially, else in single quotes (a quote inside
// as '\''), for the command line a results file records.
std::string shell_quoted(const std::string& word);

}  // namespace shockgas::analysis
