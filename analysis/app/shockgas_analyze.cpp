// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-analyze: one subcommand per estimator of the analysis library.
// Binds the arguments to a shockgas::analysis::AnalyzeRequest and runs it
// (run_analyze, shockgas/analysis/analyze_command.hpp), which checks the values
// and calls the library's command for the subcommand (commands.hpp).
#include <algorithm>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/analysis/analyze_command.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/io/provenance.hpp"

namespace {

using namespace shockgas;
using namespace shockgas::analysis;

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
        const bool number =
            !flag && (type.rfind("FLOAT", 0) == 0 || type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0);
        invocation.options.push_back({name, value, number});
    }
    return invocation;
}

// Whether the subcommand has the option and it was given.
bool given(const CLI::App& subcommand, const std::string& name) {
    const CLI::Option* option = subcommand.get_option_no_throw(name);
    return option != nullptr && option->count() > 0;
}

// The options of each subcommand, bound to the request's fields (their defaults are the request's).
void add_decay(CLI::App& app, AnalyzeRequest& r) {
    auto* decay = app.add_subcommand("decay", "T ~ t^-alpha: exponent +- jackknife sigma over the automatic window");
    decay->add_option("input", r.input, "shockgas-sim output")->required()->check(CLI::ExistingFile);
    decay->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    decay->add_option("--data", r.data, "T(t) data file for gnuplot");
    decay->add_option("--scan", r.scan, "window-scan data file for gnuplot");
    decay->add_flag("--data-only", r.decay.data_only,
                    "write the T(t) data file (--data) only, no fit (for runs stopped by collapse)");
    decay->add_option("--t-lo", r.t_lo, "override the window start (> 0)");
    decay->add_option("--t-hi", r.t_hi, "override the window end (> --t-lo)");
    decay
        ->add_option("--start-factor", r.decay.rule.start_factor,
                     fmt::format("t_lo = factor * max({:g}, eps^-3/2), eps = (1 - r)/2", r.decay.rule.scaling_onset))
        ->capture_default_str();
    decay->add_option("--end-factor", r.decay.rule.end_factor, "t_hi <= factor * N^3/2")->capture_default_str();
    decay->add_option("--scan-width", r.decay.scan_width, "scan window width, decades (> 0)")->capture_default_str();
    decay
        ->add_option("--scan-step", r.decay.scan_step,
                     fmt::format("scan window step, decades (>= {:g})", min_scan_step_decades))
        ->capture_default_str();
}

void add_crossover(CLI::App& app, AnalyzeRequest& r) {
    auto* crossover = app.add_subcommand("crossover", "t_dissip, t_stick, T(t_stick) per file and their powers of eps");
    crossover->add_option("inputs", r.inputs, "shockgas-sim outputs, one per eps")
        ->required()
        ->check(CLI::ExistingFile);
    crossover->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    crossover->add_option("--data", r.data, "crossover table for gnuplot");
    crossover->add_option("--haff-floor", r.crossover.haff_floor, "Haff fit on T >= floor * T0 (0 < floor < 1)")
        ->capture_default_str();
    crossover->add_option("--stick-ratio", r.crossover.stick_ratio, "t_stick: T / T_Haff reaches this (> 1)")
        ->capture_default_str();
    crossover
        ->add_option("--haff-constant", r.haff_constant,
                     "Haff curve's rate: fit (on T >= floor * T0) or derived (A = 6 sqrt(3)/5, no fit: free of the "
                     "lattice start's transient, which the fit's window reaches at eps >= 0.025)")
        ->check(CLI::IsMember({"fit", "derived"}))
        ->capture_default_str();
}

void add_scaling(CLI::App& app, AnalyzeRequest& r) {
    auto* scaling = app.add_subcommand("scaling", "P(v,t) collapse (beta, distance), kurtosis and tail gamma");
    scaling->add_option("inputs", r.inputs, "shockgas-sim outputs with /histograms")
        ->required()
        ->check(CLI::ExistingFile);
    scaling->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    scaling->add_option("--data", r.data, "rescaled Phi(z) data file for gnuplot");
    scaling->add_option("--tail-start", r.tail.tail_start, "tail starts at |z| = this * rms(z)")->capture_default_str();
    scaling->add_option("--tail-max-error", r.tail.max_relative_error, "largest relative error of a tail bin")
        ->capture_default_str();
}

void add_shocks(CLI::App& app, AnalyzeRequest& r) {
    auto* shocks = app.add_subcommand("shocks", "shock count and segment slopes of every snapshot time");
    shocks->add_option("input", r.input, "shockgas-sim output with /snapshots")->required()->check(CLI::ExistingFile);
    shocks->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    shocks->add_option("--data", r.data, "profile, shocks and segments of the first snapshot for gnuplot");
    shocks->add_option("--jump-fraction", r.shocks.jump_fraction, "counted shock: velocity drop >= this * v_rms")
        ->capture_default_str();
    shocks->add_option("--segment-break", r.shocks.segment_break_fraction, "segments end at drops >= this * v_rms")
        ->capture_default_str();
    shocks
        ->add_option("--coarse-grain", r.shocks.coarse_grain_mass,
                     "merge consecutive clusters into cells of at least this mass first (0: off)")
        ->check(cli::finite_non_negative)
        ->capture_default_str();
    shocks
        ->add_option("--merge-gap", r.merge_gap,
                     "compressive runs at most this many expanding pairs apart are one shock (UINT)")
        ->capture_default_str();
}

void add_collapse(CLI::App& app, AnalyzeRequest& r) {
    auto* collapse = app.add_subcommand(
        "collapse",
        "collapse time and cluster mass per input (delta = 0 runs); forms against eps, or statistics across N");
    collapse->add_option("inputs", r.inputs, "shockgas-sim outputs, one per eps (--vs eps) or per N (--vs N)")
        ->required()
        ->check(CLI::ExistingFile);
    collapse
        ->add_option("--vs", r.versus,
                     "what the inputs vary: eps (fit t ~ eps^x, eps^-3/2 (ln 1/eps)^y, eps^-3/2, McNamara-Young; "
                     "the same for the mass) or N (first-collapse statistics)")
        ->check(CLI::IsMember({"eps", "N"}))
        ->capture_default_str();
    collapse->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    collapse->add_option("--data", r.data, "collapse table for gnuplot");
    collapse->add_option("--hazard", r.hazard, "with --vs N: cumulative hazard per particle H(t)/N, one block per N");
}

void add_compare(CLI::App& app, AnalyzeRequest& r) {
    auto* compare =
        app.add_subcommand("compare", "deviation of T(t) from a reference run, with cost (the speed/accuracy trade)");
    compare->add_option("reference", r.reference, "the reference (most accurate) shockgas-sim output")
        ->required()
        ->check(CLI::ExistingFile);
    compare->add_option("inputs", r.inputs, "the runs to compare with it")->required()->check(CLI::ExistingFile);
    compare->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    compare->add_option("--data", r.data, "table: delta, cost, deviation, departure time");
    compare->add_option("--curves", r.curves, "deviation against time, one block per input");
}

void add_validity(CLI::App& app, AnalyzeRequest& r) {
    auto* validity = app.add_subcommand(
        "validity", "when each observable of the delta > 0 gas leaves the sticky gas: the validity map of delta");
    validity
        ->add_option("inputs", r.inputs,
                     "shockgas-sim outputs with snapshots: the sticky-gas references (r = 0, delta = 0) and the runs "
                     "compared with the reference of their N and seed")
        ->required()
        ->check(CLI::ExistingFile);
    validity->add_option("-o,--output", r.output, "results HDF5 file, holding /validity_map")->capture_default_str();
    validity->add_option("--data", r.data, "table: t* per run, observable and criterion, and the fitted mu");
    validity->add_option("--curves", r.curves, "each observable's deviation against t, one block per run and observable");
    validity->add_option("--fidelity", r.fidelity, "the map's label: the tier its runs belong to")->capture_default_str();
    validity
        ->add_option("--cluster-gap", r.validity.cluster_gap_fraction,
                     "clusters: neighbours closer than this fraction of the sticky gas's cluster spacing t^(2/3)/nu")
        ->capture_default_str();
    validity
        ->add_option("--small-gap", r.validity.small_gap_fraction,
                     "small_gap_fraction counts empty gaps shorter than this fraction of their mean")
        ->capture_default_str();
    validity
        ->add_option("--wavenumber", r.validity.structure_wavenumber,
                     "structure_function is S(k) t^(-2/3) at k = this / t^(2/3) (units of the spacing)")
        ->capture_default_str();
    validity->add_option("--k-sigma", r.validity.k_sigma, "the 3sigma criterion's number of paired jackknife sigmas")
        ->capture_default_str();
}

void add_cooling(CLI::App& app, AnalyzeRequest& r) {
    auto* cooling = app.add_subcommand(
        "cooling", "disk and sphere gases: T(t) against Haff's law, t0 fitted, the clustering index");
    cooling->add_option("inputs", r.inputs, "shockgas-spheres outputs")->required()->check(CLI::ExistingFile);
    cooling->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    cooling->add_option("--data", r.data, "table: T(t), T_Haff and their ratio, a block per input");
    cooling->add_option("--clustering", r.clustering, "table: the clustering index at each snapshot, a block per input");
    cooling->add_option("--picture", r.picture, "realization 0's disk centres at the last snapshot of the first 2D input");
}

void add_clusters(CLI::App& app, AnalyzeRequest& r) {
    auto* clusters = app.add_subcommand(
        "clusters", "disk and sphere gases: clusters of dense field cells, their masses and the largest");
    clusters->add_option("inputs", r.inputs, "shockgas-spheres outputs")->required()->check(CLI::ExistingFile);
    clusters->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    clusters->add_option("--threshold", r.threshold, "a cell is in a cluster at density >= this x the mean")
        ->capture_default_str();
    clusters->add_option("--data", r.data, "table: clusters, mean and largest mass against t, a block per input");
    clusters->add_option("--distribution", r.distribution,
                         "table: cluster masses in log bins, a block per input and snapshot");
    clusters->add_option("--maps", r.picture,
                         "table: realization 0's density field of the first 2D input at each snapshot (gnuplot image)");
}

void add_late_decay(CLI::App& app, AnalyzeRequest& r) {
    auto* late = app.add_subcommand(
        "late-decay", "disk and sphere gases: T ~ t^-theta after Haff's law, where the two meet, and Delta v / v");
    late->add_option("inputs", r.inputs, "shockgas-spheres outputs")->required()->check(CLI::ExistingFile);
    late->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    late->add_option("--window-start", r.late_decay.window_start, "fit from this x eps^(-4/(4-d)) / omega0")
        ->capture_default_str();
    late->add_option("--window-end", r.late_decay.window_end, "fit to this x N^(2/d) / omega0 (at most t_max)")
        ->capture_default_str();
    late->add_option("--data", r.data, "table: mean T, T t^theta and the kurtosis against t, a block per input");
    late->add_option("--slopes", r.slopes, "table: local slopes d ln T / d ln t, a block per input");
    late->add_option("--crossovers", r.crossovers, "table: tau_c against eps, a block per dimension");
    late->add_option("--fluctuations", r.fluctuations, "table: Delta v / v at each snapshot, a block per input");
    late->add_option("--tails", r.tails,
                     "table: velocity distribution P(u) at each histogram time, a block per input and time");
    late->add_option("--tail-fits", r.tail_fits,
                     "table: tail exponent gamma of ln P = a - c |u|^gamma at each histogram time, a block per input");
}

void add_far_tail(CLI::App& app, AnalyzeRequest& r) {
    auto* far_tail = app.add_subcommand("far-tail", "tail exponent gamma of Phi from shockgas-tail output");
    far_tail->add_option("input", r.input, "shockgas-tail output")->required()->check(CLI::ExistingFile);
    far_tail->add_option("-o,--output", r.output, "results HDF5 file")->capture_default_str();
    far_tail->add_option("--data", r.data, "ln Phi(z) and the fit for gnuplot");
    far_tail->add_option("--z-lo", r.z_lo, "fit window start")->check(cli::finite_non_negative)->capture_default_str();
    far_tail->add_option("--z-hi", r.z_hi, "fit window end")->capture_default_str();
    far_tail->add_option("--window-shift", r.window_shift, "window systematic: both ends moved by +- this")
        ->check(cli::finite_non_negative)
        ->capture_default_str();
    far_tail->add_flag("--free-linear", r.free_linear, "fit the linear term b too (default: b from EB9)");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-analyze: estimators on shockgas-sim and shockgas-spheres output (see analysis/README.md)"};
    app.set_version_flag("--version", "shockgas-analyze " + build_info().version);
    app.set_help_all_flag("--help-all", "print the options of every subcommand");
    app.require_subcommand(1);
    AnalyzeRequest request;
    for (const auto add : {add_decay, add_crossover, add_scaling, add_shocks, add_collapse, add_compare, add_validity,
                           add_far_tail, add_cooling, add_clusters, add_late_decay})
        add(app, request);
    if (const int status = cli::parse(app, argc, argv, "shockgas-analyze"); status >= 0) return status;
    const CLI::App& subcommand = *app.get_subcommands().front();
    request.command = subcommand.get_name();
    request.invocation = invocation_of(subcommand, argc, argv);
    request.t_lo_given = given(subcommand, "--t-lo");
    request.t_hi_given = given(subcommand, "--t-hi");
    request.scan_width_given = given(subcommand, "--scan-width");
    return cli::run("shockgas-analyze", [&] {
        run_analyze(request);
        return 0;
    });
}
