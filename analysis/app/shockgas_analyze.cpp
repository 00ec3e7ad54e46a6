// shockgas-analyze: one subcommand per estimator of the analysis library.
// Parses and checks the arguments and calls the library's command for the
// subcommand (shockgas/analysis/commands.hpp), which does the work.
#include <algorithm>
#include <cmath>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/analysis/commands.hpp"
#include "shockgas/analysis/results.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"

namespace {

using namespace shockgas;
using namespace shockgas::analysis;

// --- checks of what a user gives, made before any work (one line each) ---

// Option values that must be positive: written as !(x > 0) so that NaN fails
// too. (Values that may be 0 are checked at parsing, by every program's
// cli::finite_non_negative.) meaning: what the value is, e.g. " (a multiple of v_rms)".
void require_positive(const std::string& option, double value, const std::string& meaning = "") {
    if (!(value > 0.0) || !std::isfinite(value))
        throw InputError(fmt::format("{}{} must be positive and finite, not {}", option, meaning, value));
}

// An argument as a POSIX shell reads it back: bare when it holds only
// characters no shell treats specially, else in single quotes.
std::string shell_quoted(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
        return std::isalnum(c) || std::strchr("_-+=.,/:@%^", c) != nullptr;
    });
    if (plain) return word;
    std::string quoted = "'";
    for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// What the results file records of this run (AnalysisInvocation): the
// command line, and every named option of the subcommand that ran with the
// value it ran with, so that the file says how it was made (--jump-fraction 2
// and the default gave 104 and 416 shocks in files that did not say which);
// not the flags that print and exit, which are none of the run's settings.
AnalysisInvocation invocation_of(const CLI::App& subcommand, int argc, char** argv) {
    AnalysisInvocation invocation;
    invocation.program = "shockgas-analyze " + subcommand.get_name();
    std::vector<std::string> words;
    for (int i = 0; i < argc; ++i) words.push_back(shell_quoted(argv[i]));
    invocation.command_line = fmt::format("{}", fmt::join(words, " "));
    // --help and --help-all (every subcommand inherits both; --version is the
    // main program's only): --help-all was recorded as a setting of the run
    // (help_all = "false").
    const auto meta = [&subcommand](const CLI::Option* option) {
        return option == subcommand.get_help_ptr() || option == subcommand.get_help_all_ptr();
    };
    for (const CLI::Option* option : subcommand.get_options()) {
        if (option->get_lnames().empty() || meta(option)) continue;
        std::string name = option->get_lnames().front();
        std::replace(name.begin(), name.end(), '-', '_');
        const bool flag = option->get_expected_max() == 0;  // a flag takes no value
        std::string value;
        if (flag)
            value = option->count() > 0 ? "true" : "false";
        else if (option->count() > 0)
            value = fmt::format("{}", fmt::join(option->results(), ","));
        else
            value = option->get_default_str();
        if (value.empty()) continue;  // not given and no default (--t-lo, --data)
        const std::string type = option->get_type_name();
        const bool number = !flag && (type.rfind("FLOAT", 0) == 0 || type.rfind("INT", 0) == 0 ||
                                      type.rfind("UINT", 0) == 0);
        invocation.options.push_back({name, value, number});
    }
    return invocation;
}


}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-analyze: estimators on shockgas-sim output (see analysis/README.md)"};
    app.set_version_flag("--version", "shockgas-analyze " + build_info().version);
    app.set_help_all_flag("--help-all", "print the options of every subcommand");
    app.require_subcommand(1);

    std::string input, output = "analysis.h5", data, scan;
    std::vector<std::string> inputs;
    double t_lo = 0.0, t_hi = 0.0;
    DecayOptions decay_options;
    auto* decay = app.add_subcommand("decay", "T ~ t^-alpha: exponent +- jackknife sigma over the automatic window");
    decay->add_option("input", input, "shockgas-sim output")->required()->check(CLI::ExistingFile);
    decay->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    decay->add_option("--data", data, "T(t) data file for gnuplot");
    decay->add_option("--scan", scan, "window-scan data file for gnuplot");
    decay->add_flag("--data-only", decay_options.data_only,
                    "write the T(t) data file (--data) only, no fit (for runs stopped by collapse)");
    auto* t_lo_option = decay->add_option("--t-lo", t_lo, "override the window start (> 0)");
    auto* t_hi_option = decay->add_option("--t-hi", t_hi, "override the window end (> --t-lo)");
    decay->add_option("--start-factor", decay_options.rule.start_factor,
                      fmt::format("t_lo = factor * max({:g}, eps^-3/2), eps = (1 - r)/2", decay_options.rule.scaling_onset))
        ->capture_default_str();
    decay->add_option("--end-factor", decay_options.rule.end_factor, "t_hi <= factor * N^3/2")->capture_default_str();
    auto* scan_width_option =
        decay->add_option("--scan-width", decay_options.scan_width, "scan window width, decades (> 0)")
            ->capture_default_str();
    decay->add_option("--scan-step", decay_options.scan_step,
                      fmt::format("scan window step, decades (>= {:g})", min_scan_step_decades))
        ->capture_default_str();

    CrossoverRule crossover_rule;
    auto* crossover = app.add_subcommand("crossover", "t_dissip, t_stick, T(t_stick) per file and their powers of eps");
    crossover->add_option("inputs", inputs, "shockgas-sim outputs, one per eps")->required()->check(CLI::ExistingFile);
    crossover->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    crossover->add_option("--data", data, "crossover table for gnuplot");
    crossover->add_option("--haff-floor", crossover_rule.haff_floor, "Haff fit on T >= floor * T0 (0 < floor < 1)")
        ->capture_default_str();
    crossover->add_option("--stick-ratio", crossover_rule.stick_ratio, "t_stick: T / T_Haff reaches this (> 1)")
        ->capture_default_str();
    std::string haff_constant = "fit";
    crossover
        ->add_option("--haff-constant", haff_constant,
                     "Haff curve's rate: fit (on T >= floor * T0) or derived (A = 6 sqrt(3)/5, no fit: free of the "
                     "lattice start's transient, which the fit's window reaches at eps >= 0.025)")
        ->check(CLI::IsMember({"fit", "derived"}))
        ->capture_default_str();

    TailRule tail_rule;
    auto* scaling = app.add_subcommand("scaling", "P(v,t) collapse (beta, distance), kurtosis and tail gamma");
    scaling->add_option("inputs", inputs, "shockgas-sim outputs with /histograms")->required()->check(CLI::ExistingFile);
    scaling->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    scaling->add_option("--data", data, "rescaled Phi(z) data file for gnuplot");
    scaling->add_option("--tail-start", tail_rule.tail_start, "tail starts at |z| = this * rms(z)")
        ->capture_default_str();
    scaling->add_option("--tail-max-error", tail_rule.max_relative_error, "largest relative error of a tail bin")
        ->capture_default_str();

    ShockRule shock_rule;
    // Signed, so that a negative value is refused rather than wrapped around to 2^64 - 1.
    std::int64_t merge_gap = static_cast<std::int64_t>(shock_rule.merge_gap_points);
    auto* shocks = app.add_subcommand("shocks", "shock count and segment slopes of every snapshot time");
    shocks->add_option("input", input, "shockgas-sim output with /snapshots")->required()->check(CLI::ExistingFile);
    shocks->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    shocks->add_option("--data", data, "profile, shocks and segments of the first snapshot for gnuplot");
    shocks->add_option("--jump-fraction", shock_rule.jump_fraction, "counted shock: velocity drop >= this * v_rms")
        ->capture_default_str();
    shocks->add_option("--segment-break", shock_rule.segment_break_fraction, "segments end at drops >= this * v_rms")
        ->capture_default_str();
    shocks->add_option("--coarse-grain", shock_rule.coarse_grain_mass,
                       "merge consecutive clusters into cells of at least this mass first (0: off)")
        ->check(cli::finite_non_negative)
        ->capture_default_str();
    shocks->add_option("--merge-gap", merge_gap,
                       "compressive runs at most this many expanding pairs apart are one shock (UINT)")
        ->capture_default_str();

    std::string versus = "eps", hazard;
    auto* collapse = app.add_subcommand(
        "collapse", "collapse time and cluster mass per input (delta = 0 runs); forms against eps, or statistics across N");
    collapse->add_option("inputs", inputs, "shockgas-sim outputs, one per eps (--vs eps) or per N (--vs N)")
        ->required()
        ->check(CLI::ExistingFile);
    collapse->add_option("--vs", versus,
                         "what the inputs vary: eps (fit t ~ eps^x, eps^-3/2 (ln 1/eps)^y, eps^-3/2, McNamara-Young; "
                         "the same for the mass) or N (first-collapse statistics)")
        ->check(CLI::IsMember({"eps", "N"}))
        ->capture_default_str();
    collapse->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    collapse->add_option("--data", data, "collapse table for gnuplot");
    collapse->add_option("--hazard", hazard, "with --vs N: cumulative hazard per particle H(t)/N, one block per N");

    std::string reference, curves;
    auto* compare = app.add_subcommand("compare", "deviation of T(t) from a reference run, with cost (the speed/accuracy trade)");
    compare->add_option("reference", reference, "the reference (most accurate) shockgas-sim output")->required()
        ->check(CLI::ExistingFile);
    compare->add_option("inputs", inputs, "the runs to compare with it")->required()->check(CLI::ExistingFile);
    compare->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    compare->add_option("--data", data, "table: delta, cost, deviation, departure time");
    compare->add_option("--curves", curves, "deviation against time, one block per input");

    double z_lo = 2.0, z_hi = 5.5, window_shift = 0.25;
    bool free_linear = false;
    auto* far_tail = app.add_subcommand("far-tail", "tail exponent gamma of Phi from shockgas-tail output");
    far_tail->add_option("input", input, "shockgas-tail output")->required()->check(CLI::ExistingFile);
    far_tail->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    far_tail->add_option("--data", data, "ln Phi(z) and the fit for gnuplot");
    far_tail->add_option("--z-lo", z_lo, "fit window start")->check(cli::finite_non_negative)->capture_default_str();
    far_tail->add_option("--z-hi", z_hi, "fit window end")->capture_default_str();
    far_tail->add_option("--window-shift", window_shift, "window systematic: both ends moved by +- this")
        ->check(cli::finite_non_negative)
        ->capture_default_str();
    far_tail->add_flag("--free-linear", free_linear, "fit the linear term b too (default: b from EB9)");

    if (const int status = cli::parse(app, argc, argv, "shockgas-analyze"); status >= 0) return status;
    return cli::run("shockgas-analyze", [&] {
        // Every input the subcommand reads, for the checks of the outputs.
        std::vector<std::string> all_inputs = inputs;
        if (!input.empty()) all_inputs.insert(all_inputs.begin(), input);
        if (!reference.empty()) all_inputs.insert(all_inputs.begin(), reference);
        try {
            // An input that is a run in progress (a checkpoint), whatever the
            // subcommand; then option values, then every output path, before
            // any work: a bad value or an unwritable path never costs a long
            // analysis, and no output may replace an input or another output.
            check_inputs(all_inputs, *far_tail ? "a far-tail sampler file (made by shockgas-tail)"
                                               : "a shockgas-sim output");
            if (*decay) {
                if (t_lo_option->count() > 0) {
                    require_positive("--t-lo", t_lo);
                    decay_options.t_lo = t_lo;
                }
                if (t_hi_option->count() > 0) {
                    require_positive("--t-hi", t_hi);
                    decay_options.t_hi = t_hi;
                }
                if (decay_options.t_lo && decay_options.t_hi && !(t_hi > t_lo))
                    throw InputError(fmt::format("--t-hi ({:g}) must be larger than --t-lo ({:g})", t_hi, t_lo));
                require_positive("--start-factor", decay_options.rule.start_factor);
                require_positive("--end-factor", decay_options.rule.end_factor);
                require_positive("--scan-width", decay_options.scan_width, " (in decades)");
                if (!(decay_options.scan_step >= min_scan_step_decades) || !std::isfinite(decay_options.scan_step))
                    throw InputError(fmt::format("--scan-step must be finite and at least {:g} decades, not {} (a "
                                                 "smaller step repeats windows over the same samples, {:g} fits per "
                                                 "decade and more)",
                                                 min_scan_step_decades, decay_options.scan_step,
                                                 1.0 / min_scan_step_decades));
                decay_options.scan_required = !scan.empty() || scan_width_option->count() > 0;
                if (decay_options.data_only && data.empty())
                    throw InputError("--data-only needs --data FILE: it writes the T(t) table there and nothing else");
                if (decay_options.data_only && !scan.empty())
                    throw InputError("--data-only writes only the --data table: no fit, so no --scan");
                // --data-only writes no results file: -o is not an output then.
                check_outputs({{"-o", decay_options.data_only ? "" : output, false},
                               {"--data", data, true},
                               {"--scan", scan, true}},
                              all_inputs);
                run_decay(invocation_of(*decay, argc, argv), input, output, data, scan, decay_options);
            }
            if (*crossover) {
                require_positive("--haff-floor", crossover_rule.haff_floor, " (a fraction of T0)");
                if (!(crossover_rule.haff_floor < 1.0))
                    throw InputError(fmt::format("--haff-floor must be below 1 (a fraction of T0, which T only falls "
                                                 "from), not {}",
                                                 crossover_rule.haff_floor));
                if (!(crossover_rule.stick_ratio > 1.0) || !std::isfinite(crossover_rule.stick_ratio))
                    throw InputError(fmt::format("--stick-ratio must be finite and above 1 (T / T_Haff starts at 1 "
                                                 "and rises), not {}",
                                                 crossover_rule.stick_ratio));
                check_outputs({{"-o", output, false}, {"--data", data, true}}, all_inputs);
                run_crossover(invocation_of(*crossover, argc, argv), inputs, output, data, crossover_rule,
                              haff_constant == "derived");
            }
            if (*scaling) {
                require_positive("--tail-start", tail_rule.tail_start, " (in units of the rms of z)");
                require_positive("--tail-max-error", tail_rule.max_relative_error);
                check_outputs({{"-o", output, false}, {"--data", data, true}}, all_inputs);
                run_scaling(invocation_of(*scaling, argc, argv), inputs, output, data, tail_rule);
            }
            if (*shocks) {
                require_positive("--jump-fraction", shock_rule.jump_fraction, " (a multiple of v_rms)");
                require_positive("--segment-break", shock_rule.segment_break_fraction, " (a multiple of v_rms)");
                if (merge_gap < 0)
                    throw InputError(fmt::format("--merge-gap must be a whole number at least 0, not {}", merge_gap));
                shock_rule.merge_gap_points = static_cast<std::size_t>(merge_gap);
                check_outputs({{"-o", output, false}, {"--data", data, true}}, all_inputs);
                run_shocks(invocation_of(*shocks, argc, argv), input, output, data, shock_rule);
            }
            if (*collapse) {
                if (!hazard.empty() && versus != "N")
                    throw InputError("--hazard needs --vs N: the hazard per particle compares runs of different N at "
                                     "one eps");
                check_outputs({{"-o", output, false}, {"--data", data, true}, {"--hazard", hazard, true}},
                              all_inputs);
                run_collapse(invocation_of(*collapse, argc, argv), inputs, output, data, versus, hazard);
            }
            if (*compare) {
                check_outputs({{"-o", output, false}, {"--data", data, true}, {"--curves", curves, true}},
                              all_inputs);
                run_compare(invocation_of(*compare, argc, argv), reference, inputs, output, data, curves);
            }
            if (*far_tail) {
                if (!(z_hi > z_lo) || !std::isfinite(z_hi))
                    throw InputError(fmt::format("--z-hi must be finite and larger than --z-lo ({:g}), not {}", z_lo,
                                                 z_hi));
                check_outputs({{"-o", output, false}, {"--data", data, true}}, all_inputs);
                run_far_tail(invocation_of(*far_tail, argc, argv), input, output, data, z_lo, z_hi, window_shift,
                             free_linear);
            }
        } catch (const InsufficientData& error) {
            // Estimator messages say what is missing. Work on one input names
            // that input (on_input); what is left failed on all of them together.
            throw InputError(fmt::format("{}, in '{}'", error.what(), fmt::join(all_inputs, "', '")));
        }
        return 0;
    });
}
