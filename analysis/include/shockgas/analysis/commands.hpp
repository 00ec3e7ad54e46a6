// SPDX-License-Identifier: GPL-3.0-or-later
// The commands of shockgas-analyze, one per estimator. Each reads its inputs (shockgas-sim or
// shockgas-tail output), runs the estimators of this library on them, and writes the results file
// (HDF5, with the invocation and the inputs' provenance), the gnuplot data files it is given paths
// for (empty: none), and one summary line on stdout. An estimate the inputs cannot give throws
// InputError naming the input. The program parses the options and run_analyze (analyze_command.hpp)
// checks them; these do the rest, so a test can call them as the program does.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "shockgas/analysis/results.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"

namespace shockgas::analysis {

// What `shockgas-analyze decay` was asked for beyond its files (checked by the program).
struct DecayOptions {
    std::optional<double> t_lo, t_hi;  // window ends given by --t-lo, --t-hi
    WindowRule rule;
    double scan_width = 1.0, scan_step = 0.1;
    bool scan_required = false;        // --scan or --scan-width given: an empty scan is an error
    bool data_only = false;
};

// T ~ t^-alpha (Eq. 3, third regime): the exponent over the automatic window (or the one given), its
// jackknife sigma, the window systematic, and the exponent in moving windows (--scan).
void run_decay(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
               const std::string& data, const std::string& scan, const DecayOptions& options);

// t_dissip, t_stick and T(t_stick) per input (one per eps) and their powers of eps (Fig. 1 discussion).
void run_crossover(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                   const std::string& output, const std::string& data, const CrossoverRule& fit_rule,
                   bool derived_haff_constant);

// P(v,t) = t^(1/3) Phi(v t^(1/3)) (Eq. 4): the best collapse exponent beta, the collapse distance,
// the kurtosis of Phi and the tail exponent gamma (Eq. 5) over every histogram of the inputs.
void run_scaling(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                 const std::string& output, const std::string& data, const TailRule& tail_rule);

// Shock count and segment slopes (Eq. 7, Fig. 5) at every snapshot time of one run.
void run_shocks(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
                const std::string& data, const ShockRule& rule);

// Collapse time and cluster mass per input (delta = 0 runs); versus "eps": the competing forms
// against eps; versus "N": the first-collapse statistics across N (and the hazard, if hazard_data).
void run_collapse(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, const std::string& data, const std::string& versus,
                  const std::string& hazard_data);

// The speed/accuracy trade (P5): the deviation of each input's T(t) from the reference run, and its cost.
void run_compare(const AnalysisInvocation& invocation, const std::string& reference_path,
                 const std::vector<std::string>& inputs, const std::string& output, const std::string& data,
                 const std::string& curves);

// gamma of the far tail (Eq. 5) from shockgas-tail output, fitted on z in [z_lo, z_hi].
void run_far_tail(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
                  const std::string& data, double z_lo, double z_hi, double window_shift, bool free_linear);

}  // namespace shockgas::analysis
