// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-analyze's checks and dispatch (shockgas/analysis/analyze_command.hpp).
#include "shockgas/analysis/analyze_command.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {

namespace {

// Option values that must be positive: written as !(x > 0) so that NaN fails
// too. (Values that may be 0 are checked at parsing, by every program's
// cli::finite_non_negative.) meaning: what the value is, e.g. " (a multiple of v_rms)".
void require_positive(const std::string& option, double value, const std::string& meaning = "") {
    if (!(value > 0.0) || !std::isfinite(value))
        throw InputError(fmt::format("{}{} must be positive and finite, not {}", option, meaning, value));
}

void check_decay(AnalyzeRequest& request) {
    DecayOptions& options = request.decay;
    if (request.t_lo_given) {
        require_positive("--t-lo", request.t_lo);
        options.t_lo = request.t_lo;
    }
    if (request.t_hi_given) {
        require_positive("--t-hi", request.t_hi);
        options.t_hi = request.t_hi;
    }
    if (options.t_lo && options.t_hi && !(request.t_hi > request.t_lo))
        throw InputError(fmt::format("--t-hi ({:g}) must be larger than --t-lo ({:g})", request.t_hi, request.t_lo));
    require_positive("--start-factor", options.rule.start_factor);
    require_positive("--end-factor", options.rule.end_factor);
    require_positive("--scan-width", options.scan_width, " (in decades)");
    if (!(options.scan_step >= min_scan_step_decades) || !std::isfinite(options.scan_step))
        throw InputError(
            fmt::format("--scan-step must be finite and at least {:g} decades, not {} (a smaller step "
                        "repeats windows over the same samples, {:g} fits per decade and more)",
                        min_scan_step_decades, options.scan_step, 1.0 / min_scan_step_decades));
    options.scan_required = !request.scan.empty() || request.scan_width_given;
    if (options.data_only && request.data.empty())
        throw InputError("--data-only needs --data FILE: it writes the T(t) table there and nothing else");
    if (options.data_only && !request.scan.empty())
        throw InputError("--data-only writes only the --data table: no fit, so no --scan");
}

void check_crossover(const AnalyzeRequest& request) {
    const CrossoverRule& rule = request.crossover;
    require_positive("--haff-floor", rule.haff_floor, " (a fraction of T0)");
    if (!(rule.haff_floor < 1.0))
        throw InputError(
            fmt::format("--haff-floor must be below 1 (a fraction of T0, which T only falls from), "
                        "not {}",
                        rule.haff_floor));
    if (!(rule.stick_ratio > 1.0) || !std::isfinite(rule.stick_ratio))
        throw InputError(
            fmt::format("--stick-ratio must be finite and above 1 (T / T_Haff starts at 1 and rises), "
                        "not {}",
                        rule.stick_ratio));
}

void check_shocks(AnalyzeRequest& request) {
    require_positive("--jump-fraction", request.shocks.jump_fraction, " (a multiple of v_rms)");
    require_positive("--segment-break", request.shocks.segment_break_fraction, " (a multiple of v_rms)");
    if (request.merge_gap < 0)
        throw InputError(fmt::format("--merge-gap must be a whole number at least 0, not {}", request.merge_gap));
    request.shocks.merge_gap_points = static_cast<std::size_t>(request.merge_gap);
}

// The subcommand's checks of its values and outputs, then its command.
void check_and_run(AnalyzeRequest& request, const std::vector<std::string>& all_inputs) {
    const std::string& command = request.command;
    const AnalysisInvocation& invocation = request.invocation;
    if (command == "decay") {
        check_decay(request);
        // --data-only writes no results file: -o is not an output then.
        check_outputs({{"-o", request.decay.data_only ? "" : request.output, false},
                       {"--data", request.data, true},
                       {"--scan", request.scan, true}},
                      all_inputs);
        run_decay(invocation, request.input, request.output, request.data, request.scan, request.decay);
    } else if (command == "crossover") {
        check_crossover(request);
        check_outputs({{"-o", request.output, false}, {"--data", request.data, true}}, all_inputs);
        run_crossover(invocation, request.inputs, request.output, request.data, request.crossover,
                      request.haff_constant == "derived");
    } else if (command == "scaling") {
        require_positive("--tail-start", request.tail.tail_start, " (in units of the rms of z)");
        require_positive("--tail-max-error", request.tail.max_relative_error);
        check_outputs({{"-o", request.output, false}, {"--data", request.data, true}}, all_inputs);
        run_scaling(invocation, request.inputs, request.output, request.data, request.tail);
    } else if (command == "shocks") {
        check_shocks(request);
        check_outputs({{"-o", request.output, false}, {"--data", request.data, true}}, all_inputs);
        run_shocks(invocation, request.input, request.output, request.data, request.shocks);
    } else if (command == "collapse") {
        if (!request.hazard.empty() && request.versus != "N")
            throw InputError("--hazard needs --vs N: the hazard per particle compares runs of different N at one eps");
        check_outputs(
            {{"-o", request.output, false}, {"--data", request.data, true}, {"--hazard", request.hazard, true}},
            all_inputs);
        run_collapse(invocation, request.inputs, request.output, request.data, request.versus, request.hazard);
    } else if (command == "compare") {
        check_outputs(
            {{"-o", request.output, false}, {"--data", request.data, true}, {"--curves", request.curves, true}},
            all_inputs);
        run_compare(invocation, request.reference, request.inputs, request.output, request.data, request.curves);
    } else if (command == "validity") {
        require_positive("--cluster-gap", request.validity.cluster_gap_fraction, " (a fraction of the cluster spacing)");
        require_positive("--small-gap", request.validity.small_gap_fraction, " (a fraction of the mean gap)");
        require_positive("--wavenumber", request.validity.structure_wavenumber, " (k t^(2/3))");
        require_positive("--k-sigma", request.validity.k_sigma);
        check_outputs(
            {{"-o", request.output, false}, {"--data", request.data, true}, {"--curves", request.curves, true}},
            all_inputs);
        run_validity(invocation, request.inputs, request.output, request.data, request.curves, request.fidelity,
                     request.validity);
    } else if (command == "far-tail") {
        if (!(request.z_hi > request.z_lo) || !std::isfinite(request.z_hi))
            throw InputError(
                fmt::format("--z-hi must be finite and larger than --z-lo ({:g}), not {}", request.z_lo, request.z_hi));
        check_outputs({{"-o", request.output, false}, {"--data", request.data, true}}, all_inputs);
        run_far_tail(invocation, request.input, request.output, request.data, request.z_lo, request.z_hi,
                     request.window_shift, request.free_linear);
    } else if (command == "cooling") {
        check_outputs({{"-o", request.output, false},
                       {"--data", request.data, true},
                       {"--clustering", request.clustering, true},
                       {"--picture", request.picture, true}},
                      all_inputs);
        run_cooling(invocation, request.inputs, request.output, request.data, request.clustering, request.picture);
    } else if (command == "clusters") {
        require_positive("--threshold", request.threshold, " (a density relative to the mean)");
        check_outputs({{"-o", request.output, false},
                       {"--data", request.data, true},
                       {"--distribution", request.distribution, true},
                       {"--maps", request.picture, true}},
                      all_inputs);
        run_clusters(invocation, request.inputs, request.output, request.threshold, request.data,
                     request.distribution, request.picture);
    } else if (command == "late-decay") {
        require_positive("--window-start", request.late_decay.window_start, " (a multiple of eps^(-4/(4-d)) / omega0)");
        require_positive("--window-end", request.late_decay.window_end, " (a multiple of N^(2/d) / omega0)");
        check_outputs({{"-o", request.output, false},
                       {"--data", request.data, true},
                       {"--slopes", request.slopes, true},
                       {"--crossovers", request.crossovers, true},
                       {"--fluctuations", request.fluctuations, true},
                       {"--tails", request.tails, true},
                       {"--tail-fits", request.tail_fits, true}},
                      all_inputs);
        run_late_decay(invocation, request.inputs, request.output, request.late_decay,
                       {request.data, request.slopes, request.crossovers, request.fluctuations, request.tails,
                        request.tail_fits});
    } else {
        throw std::invalid_argument(fmt::format("shockgas-analyze has no subcommand '{}'", command));
    }
}

}  // namespace

void run_analyze(AnalyzeRequest request) {
    // Every input the subcommand reads, for the checks of the outputs.
    std::vector<std::string> all_inputs = request.inputs;
    if (!request.input.empty()) all_inputs.insert(all_inputs.begin(), request.input);
    if (!request.reference.empty()) all_inputs.insert(all_inputs.begin(), request.reference);
    try {
        // An input that is a run in progress (a checkpoint), whatever the
        // subcommand; then option values, then every output path, before
        // any work.
        // (cooling, clusters and late-decay read shockgas-spheres outputs, whose reader refuses anything else itself.)
        if (request.command != "cooling" && request.command != "clusters" && request.command != "late-decay")
            check_inputs(all_inputs, request.command == "far-tail" ? "a far-tail sampler file (made by shockgas-tail)"
                                                                   : "a shockgas-sim output");
        check_and_run(request, all_inputs);
    } catch (const InsufficientData& error) {
        // Estimator messages say what is missing. Work on one input names
        // that input (on_input); what is left failed on all of them together.
        throw InputError(fmt::format("{}, in '{}'", error.what(), fmt::join(all_inputs, "', '")));
    }
}

std::string shell_quoted(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
        return std::isalnum(c) || std::strchr("_-+=.,/:@%^", c) != nullptr;
    });
    if (plain) return word;
    std::string quoted = "'";
    for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

}  // namespace shockgas::analysis
