// SPDX-License-Identifier: GPL-3.0-or-later
// The commands of shockgas-analyze, one per estimator (commands.hpp): each reads its inputs, runs
// the library's estimators on them, and writes the results file, the gnuplot data files and one
// summary line. The checks of option values come first (run_analyze, analyze_command.cpp); argument
// parsing stays in the program.
#include "shockgas/analysis/commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/analysis/collapse.hpp"
#include "shockgas/analysis/compare.hpp"
#include "shockgas/analysis/far_tail.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"

namespace shockgas::analysis {
namespace {

// Runs one input's part of the work: what it cannot estimate (InsufficientData)
// names that input alone. Failures of fits over all inputs are named by the
// catch in main, with every input.
template <class Work>
decltype(auto) on_input(const std::string& path, Work&& work) {
    try {
        return work();
    } catch (const InsufficientData& error) {
        throw InputError(fmt::format("{}, in '{}'", error.what(), path));
    }
}

// A fit against eps or N through inputs that all share one value has no
// slope (the fit refuses: "all x values are equal"); say which inputs and why.
void require_distinct(const std::vector<double>& values, const std::vector<std::string>& inputs,
                      const std::string& name, const std::string& purpose) {
    if (values.size() < 2 || std::any_of(values.begin(), values.end(), [&](double v) { return v != values.front(); }))
        return;
    throw InputError(fmt::format("every input has {} = {:g} ('{}'): {} against {} needs 2 or more different values",
                                 name, values.front(), fmt::join(inputs, "', '"), purpose, name));
}

// The first input whose estimates have no sigma (a run of one realization: the jackknife has nothing
// to leave out). Its values stand; the fits over the inputs, weighted by those sigmas, are then n/a
// with this input named, rather than stopping the command (crossover, collapse).
struct InputWithoutSigma {
    std::string reason;  // "'x.h5' has no error bar (<the estimate's note>)"; empty while every input has one
    // Records `input` when `estimate` has no sigma and no earlier input lacked one; true when it did
    // now (the caller says so once in its data file).
    bool record(const std::string& input, const Estimate& estimate) {
        if (!reason.empty() || !std::isnan(estimate.sigma)) return false;
        reason = fmt::format("'{}' has no error bar ({})", input, estimate.note);
        return true;
    }
    bool found() const { return !reason.empty(); }
    // Why `fits` are n/a: "the fits over eps are weighted by each input's sigma: 'x.h5' has no ...".
    std::string why_not(const std::string& fits) const {
        return fmt::format("{} are weighted by each input's sigma: {}", fits, reason);
    }
};

struct RunParameters {
    double restitution, velocity_threshold, particles, t_max;
    std::string init_file;                            // a start read from a file (--init), else empty
    VelocityLaw velocity_law = VelocityLaw::uniform;  // the drawn start's law (read_initial_law)
};
RunParameters run_parameters(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    // A far-tail sampler file passes check_inputs (far-tail reads it): named here for what it is, not by
    // the first attribute it lacks ("missing attribute /restitution").
    check_simulation_output(root, path);
    RunParameters run{root.attribute_double("restitution"), root.attribute_double("velocity_threshold"),
                      static_cast<double>(root.attribute_integer("particles")), root.attribute_double("t_max"),
                      "", VelocityLaw::uniform};
    if (root.has_attribute("init_file")) run.init_file = root.attribute_string("init_file");
    if (run.init_file.empty()) run.velocity_law = read_initial_law(root).velocities;
    return run;
}

std::string restitution_label(double restitution) {
    std::ostringstream out;
    out << "r=" << restitution;
    return out.str();
}

std::unique_ptr<DataFile> temperature_data(const std::string& data, const std::string& input,
                                           const TemperatureHistory& history) {
    auto file = std::make_unique<DataFile>(data, "T(t) ensemble mean, " + input,
                                           std::vector<std::string>{input}, std::vector<std::string>{"time", "temperature", "temperature_sigma"});
    if (history.realizations < 2) file->comment("temperature_sigma nan: one realization, no scatter to estimate it");
    for (std::size_t k = 0; k < history.time.size(); ++k)
        file->row({history.time[k], history.mean(k), history.standard_error(k)});
    return file;
}

// Why a run's realizations may not all reach a histogram time, for the notes
// of run_scaling: a complete run's all do.
std::string stopped_early(const std::string& run_status) {
    if (run_status == "interrupted")
        return "the run was interrupted: shockgas-sim --resume with the same options continues it";
    if (run_status == "collapsed") return "a realization stops at its inelastic collapse (delta = 0)";
    return "the run's status is " + run_status;
}

// "2 of 4 realizations reached it; the estimates at this time use only these (why)".
std::string realizations_note(const VelocityHistogram& histogram, const std::string& why) {
    return fmt::format("{} of {} realizations reached it; the estimates at this time use only these ({})",
                       histogram.realizations, histogram.recorded_realizations, why);
}

void set_collapse_forms(ResultsFile& results, const std::string& section, const std::vector<CollapseForm>& forms) {
    double best_aic = INFINITY, best_bic = INFINITY;
    for (const auto& form : forms) {
        best_aic = std::min(best_aic, form.fit.aic());
        best_bic = std::min(best_bic, form.fit.bic());
    }
    auto parent = results.section(section);
    for (const auto& form : forms) {
        auto group = parent.create_group(form.name);
        group.set_attribute("formula", form.formula);
        group.set_attribute("prefactor", form.prefactor);
        set_estimate(group, "exponent", form.exponent);
        const Measured chi2_per_dof = form.fit.reduced_chi2();
        const Measured scaled{form.exponent_sigma_scaled, chi2_per_dof.note};
        set_measured(group, "exponent_sigma_scaled", scaled);
        group.set_attribute("parameters", static_cast<std::int64_t>(form.fit.parameters));
        group.set_attribute("points", static_cast<std::int64_t>(form.fit.points));
        group.set_attribute("chi2", form.fit.chi2);
        set_measured(group, "chi2_per_dof", chi2_per_dof);
        group.set_attribute("aic", form.fit.aic());
        group.set_attribute("bic", form.fit.bic());
        group.set_attribute("delta_aic", form.fit.aic() - best_aic);
        group.set_attribute("delta_bic", form.fit.bic() - best_bic);
        // The reason is printed once, with chi2/dof; the scaled sigma needs it.
        fmt::print("  {:<15} {:<28} exponent {:8.4f} +- {:.4f} (scaled {})  chi2/dof {}  dAIC {:6.2f}  dBIC {:6.2f}\n",
                   form.name, form.formula, form.exponent.value, form.exponent.sigma,
                   scaled.known() ? fmt::format("{:.4f}", scaled.value) : "n/a",
                   format_measured(chi2_per_dof, "{:6.2f}"), form.fit.aic() - best_aic, form.fit.bic() - best_bic);
    }
}

}  // namespace

void run_decay(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
               const std::string& data, const std::string& scan, const DecayOptions& options) {
    const TemperatureRun temperature = on_input(input, [&] { return read_temperature_run(input); });
    const TimeSeries& series = temperature.series;
    const TemperatureHistory& history = temperature.history;
    if (options.data_only) {
        // Runs stopped by collapse (delta = 0) are drawn, not fitted.
        auto file = temperature_data(data, input, history);
        commit_outputs(nullptr, {file.get()});
        return;
    }
    const auto run = run_parameters(input);
    const bool manual = options.t_lo || options.t_hi;
    // A window given in full needs no rule; a fully automatic one explains itself when empty.
    DecayWindow window = on_input(input, [&] {
        return manual ? decay_window_bounds(run.restitution, run.velocity_threshold, run.particles,
                                            history.time.back(), options.rule)
                      : automatic_decay_window(run.restitution, run.velocity_threshold, run.particles,
                                               history.time.back(), options.rule, series.status);
    });
    if (options.t_lo) window.t_lo = *options.t_lo;
    if (options.t_hi) window.t_hi = *options.t_hi;
    const DecayFit fit = on_input(input, [&] { return fit_temperature_decay(history, window.t_lo, window.t_hi); });
    const auto windows = scan_decay_windows(history, options.scan_width, options.scan_step);
    const std::string no_scan =
        windows.empty() ? fmt::format("no window of {:g} decades (--scan-width) with 3 samples lies between t = {:g} "
                                      "and {:g}",
                                      options.scan_width, history.time.front(), history.time.back())
                        : "";
    if (windows.empty() && options.scan_required) throw InputError(fmt::format("{}, in '{}'", no_scan, input));
    const Measured systematic = window_systematic(history, fit.t_lo, fit.t_hi);
    const std::string window_note = short_window_note(fit.t_lo, fit.t_hi, manual, history.time.back(), run.particles,
                                                      run.velocity_threshold, options.rule);
    ResultsFile results(output, invocation, {input});
    auto group = results.section("decay");
    group.set_attribute("exponent", fit.exponent);
    set_measured(group, "exponent_sigma", {fit.exponent_sigma, fit.exponent_sigma_note});
    set_measured(group, "exponent_fit_sigma", {fit.fit_sigma, fit.fit_note});
    set_measured(group, "exponent_window_systematic", systematic);
    set_measured(group, "chi2_per_dof", {fit.chi2_per_dof, fit.fit_note});
    group.set_attribute("prefactor", fit.prefactor);
    group.set_attribute("t_lo", fit.t_lo);
    group.set_attribute("t_hi", fit.t_hi);
    group.set_attribute("points", static_cast<std::int64_t>(fit.points));
    group.set_attribute("window_rule", manual ? "manual" : "automatic");
    if (!window_note.empty()) group.set_attribute("window_note", window_note);
    std::vector<double> centre, exponent, sigma;
    for (const auto& w : windows) {
        centre.push_back(std::sqrt(w.t_lo * w.t_hi));
        exponent.push_back(w.exponent);
        sigma.push_back(w.exponent_sigma);
    }
    auto scan_group = results.section("window_scan");
    scan_group.set_attribute("width_decades", options.scan_width);
    scan_group.set_attribute("step_decades", options.scan_step);
    if (windows.empty()) scan_group.set_attribute("note", no_scan);
    scan_group.write("window_centre", centre);
    scan_group.write("exponent", exponent);
    scan_group.write("exponent_sigma", sigma);
    std::unique_ptr<DataFile> data_file, scan_file;
    if (!data.empty()) data_file = temperature_data(data, input, history);
    if (!scan.empty()) {
        scan_file = std::make_unique<DataFile>(
            scan, fmt::format("decay exponent in moving windows of {:g} decades, moved by {:g}", options.scan_width,
                              options.scan_step),
            std::vector<std::string>{input}, std::vector<std::string>{"t_centre", "t_lo", "t_hi", "exponent", "exponent_sigma", "chi2_per_dof",
                                     "points"});
        if (history.realizations < 3)
            scan_file->comment(history.realizations < 2
                                   ? "exponent_sigma, chi2_per_dof nan: one realization, no scatter to estimate them"
                                   : "exponent_sigma, chi2_per_dof nan: two realizations, too few to weigh the fit "
                                     "by their scatter (it is unweighted) or to give the jackknife more than one "
                                     "degree of freedom");
        for (const auto& w : windows)
            scan_file->row({std::sqrt(w.t_lo * w.t_hi), w.t_lo, w.t_hi, w.exponent, w.exponent_sigma, w.chi2_per_dof,
                            static_cast<double>(w.points)});
    }
    commit_outputs(&results, {data_file.get(), scan_file.get()});
    // One realization: nothing to leave out, so no jackknife sigma; say so
    // rather than print nan. Likewise a window too short for the systematic.
    fmt::print("decay exponent {:.4f} +- {} +- {}, chi2/dof {}, window [{:g}, {:g}], {} points\n", fit.exponent,
               format_measured({fit.exponent_sigma, fit.exponent_sigma_note}, "{:.4f}", "jackknife"),
               format_measured(systematic, "{:.4f}", "window"), format_measured({fit.chi2_per_dof, fit.fit_note}, "{:.2f}"),
               fit.t_lo, fit.t_hi, fit.points);
    if (!window_note.empty()) fmt::print("note: {}\n", window_note);
}

void run_crossover(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                   const std::string& output, const std::string& data, const CrossoverRule& fit_rule,
                   bool derived_haff_constant) {
    std::vector<double> inelasticity;
    std::vector<VelocityLaw> velocity_law;
    for (const auto& input : inputs) {
        const RunParameters run = run_parameters(input);
        // t_dissip is read at T0/2 and Haff's law has T0 = 1/3, the drawn starts' (both laws have variance
        // 1/3); a start from a file has its own T0 and its own Haff constant.
        if (!run.init_file.empty())
            throw InputError(fmt::format("'{}' starts from the initial-condition file '{}': crossover assumes a drawn "
                                         "start (T0 = 1/3, velocities uniform on [-1, 1] or Gaussian), whose T0 and "
                                         "Haff constant it knows",
                                         input, run.init_file));
        inelasticity.push_back((1.0 - run.restitution) / 2.0);
        velocity_law.push_back(run.velocity_law);
    }
    require_distinct(inelasticity, inputs, "eps", "fitting the crossovers");
    std::vector<Estimate> t_dissip, t_stick, temperature, reference_stick;
    ResultsFile results(output, invocation, inputs);
    results.root().set_attribute("haff_constant", std::string(derived_haff_constant ? "derived" : "fit"));
    std::unique_ptr<DataFile> file;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "crossovers per inelasticity",
                                          inputs, std::vector<std::string>{"eps", "t_dissip", "t_dissip_sigma", "t_stick",
                                                                   "t_stick_sigma", "T_stick", "T_stick_sigma",
                                                                   "haff_rate", "haff_rate_sigma",
                                                                   "t_stick_reference"});
    InputWithoutSigma without_sigma;
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        const double eps = inelasticity[k];
        CrossoverRule rule = fit_rule;
        if (derived_haff_constant) rule.haff_rate = derived_haff_rate(eps, velocity_law[k]);
        const auto crossovers = on_input(inputs[k], [&] {
            return find_crossovers(read_temperature_run(inputs[k]).history, rule);
        });
        if (without_sigma.record(inputs[k], crossovers.t_stick) && file)
            file->comment("*_sigma nan in " + without_sigma.reason);
        t_dissip.push_back(crossovers.t_dissip);
        t_stick.push_back(crossovers.t_stick);
        temperature.push_back(crossovers.temperature_at_stick);
        // The same rule on an exact eps^(-3/2) crossover: what t_stick would be
        // read at this eps without any physics beyond Haff's law and the sticky gas.
        const Measured reference = reference_stick_time(eps, fit_rule);
        // Weighted as the measured t_stick, so that the two exponents are fitted alike.
        reference_stick.push_back({reference.value, reference.value * crossovers.t_stick.sigma / crossovers.t_stick.value});
        auto group = results.section("crossover" + std::to_string(k));
        group.set_attribute("inelasticity", eps);
        set_estimate(group, "t_dissip", crossovers.t_dissip);
        set_estimate(group, "t_stick", crossovers.t_stick);
        set_estimate(group, "temperature_at_stick", crossovers.temperature_at_stick);
        set_estimate(group, "haff_rate", crossovers.haff_rate);
        set_measured(group, "t_stick_reference", reference);
        if (file)
            file->row({eps, crossovers.t_dissip.value, crossovers.t_dissip.sigma, crossovers.t_stick.value,
                       crossovers.t_stick.sigma, crossovers.temperature_at_stick.value,
                       crossovers.temperature_at_stick.sigma, crossovers.haff_rate.value, crossovers.haff_rate.sigma,
                       reference.value});
        fmt::print("eps {:<8g} t_dissip {}  t_stick {}  T(t_stick) {}\n", eps,
                   format_estimate(crossovers.t_dissip, "{:.4g}", "{:.2g}"),
                   format_estimate(crossovers.t_stick, "{:.4g}", "{:.2g}"),
                   format_estimate(crossovers.temperature_at_stick, "{:.4g}", "{:.2g}"));
    }
    if (inputs.size() < 2 || without_sigma.found()) {
        // The powers of eps are weighted fits: without an input's sigma there is no weight for it; one
        // input has no slope. The note says which and why (collapse says so too).
        auto group = results.section("scaling_in_eps");
        const std::string why = inputs.size() < 2 ? std::string("one input: give runs of 2 or more eps")
                                                  : without_sigma.why_not("the fits over eps");
        group.set_attribute("note", why);
        fmt::print("t_dissip, t_stick, T(t_stick) against eps: n/a ({})\n", why);
    } else {
        auto group = results.section("scaling_in_eps");
        const auto dissip_fit = fit_against_inelasticity(inelasticity, t_dissip);
        const auto stick_fit = fit_against_inelasticity(inelasticity, t_stick);
        const auto temperature_fit = fit_against_inelasticity(inelasticity, temperature);
        set_power_law(group, "t_dissip", dissip_fit);
        set_power_law(group, "t_stick", stick_fit);
        set_power_law(group, "temperature_at_stick", temperature_fit);
        // The three fits share their points: chi2/dof is there for all or for none.
        const std::string chi2 =
            dissip_fit.degrees_of_freedom() > 0
                ? fmt::format("{:.2f}, {:.2f}, {:.2f}", dissip_fit.chi2_per_dof(), stick_fit.chi2_per_dof(),
                              temperature_fit.chi2_per_dof())
                : format_measured(dissip_fit.reduced_chi2(), "{:.2f}");
        fmt::print("t_dissip ~ eps^({:.3f} +- {:.3f}), t_stick ~ eps^({:.3f} +- {:.3f}), T(t_stick) ~ eps^({:.3f} +- "
                   "{:.3f}); chi2/dof {}\n",
                   dissip_fit.slope, dissip_fit.slope_sigma(), stick_fit.slope, stick_fit.slope_sigma(),
                   temperature_fit.slope, temperature_fit.slope_sigma(), chi2);
        // The exponent an exact eps^(-3/2) crossover shows through the same rule at these eps
        // (reference_stick_time): finite eps tilts it, so the data's exponent is read against it.
        Measured reference_exponent;
        const auto missing = std::find_if(reference_stick.begin(), reference_stick.end(),
                                          [](const Estimate& e) { return std::isnan(e.value); });
        if (missing == reference_stick.end())
            reference_exponent = {fit_against_inelasticity(inelasticity, reference_stick).slope, ""};
        else
            reference_exponent = Measured::missing(
                fmt::format("no reference t_stick at eps = {:g}", inelasticity[missing - reference_stick.begin()]));
        set_measured(group, "t_stick_reference_exponent", reference_exponent);
        fmt::print("t_stick of an exact eps^(-3/2) crossover (Haff's law joined to kappa t^(-2/3)) read by the same rule "
                   "at these eps: eps^({}); the data minus it: {}\n",
                   format_measured(reference_exponent, "{:.3f}"),
                   reference_exponent.known()
                       ? fmt::format("{:.3f} +- {:.3f}", stick_fit.slope - reference_exponent.value, stick_fit.slope_sigma())
                       : std::string("n/a"));
    }
    commit_outputs(&results, {file.get()});
}

void run_scaling(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                 const std::string& output, const std::string& data, const TailRule& tail_rule) {
    std::vector<VelocityHistogram> histograms;
    // Histogram times that only some realizations reached (an interrupted
    // run) use those; times none reached are left out. Both are said on
    // stderr and stored, so that no number silently rests on fewer realizations.
    std::vector<std::string> left_out;
    std::vector<std::string> notes;  // per histogram: empty, or why it has fewer realizations than its run
    for (const auto& input : inputs) {
        const RunHistograms run = on_input(input, [&] {
            return read_histograms(input, restitution_label(run_parameters(input).restitution));
        });
        const std::string why = stopped_early(run.status);
        for (const double time : run.unreached_times) {
            left_out.push_back(fmt::format("'{}' t = {:g}: no realization of {} reached it ({})", input, time,
                                           run.realizations, why));
            fmt::print(stderr, "shockgas-analyze: note: {}; its histogram is left out\n", left_out.back());
        }
        for (const auto& histogram : run.histograms) {
            const bool fewer = histogram.realizations < histogram.recorded_realizations;
            notes.push_back(fewer ? realizations_note(histogram, why) : "");
            if (fewer)
                fmt::print(stderr, "shockgas-analyze: note: t = {:g} in '{}': {}\n", histogram.time, input,
                           notes.back());
        }
        histograms.insert(histograms.end(), run.histograms.begin(), run.histograms.end());
    }
    if (histograms.empty() && !left_out.empty())
        throw InsufficientData(fmt::format("no histogram time was reached by any realization ({})",
                                           fmt::join(left_out, "; ")));
    if (histograms.empty()) throw InsufficientData("no /histograms in the inputs (run with --histogram-times)");
    ResultsFile results(output, invocation, inputs);
    if (!left_out.empty())
        results.root().set_attribute("histograms_left_out", fmt::format("{}", fmt::join(left_out, "; ")));
    std::unique_ptr<DataFile> file;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "Phi(z) = t^(-1/3) P(v,t), z = v t^(1/3); one block per histogram",
                                          inputs, std::vector<std::string>{"z", "Phi"});
    for (std::size_t h = 0; h < histograms.size(); ++h) {
        const auto& histogram = histograms[h];
        auto group = results.section("histogram" + std::to_string(h));
        group.set_attribute("label", histogram.label);
        group.set_attribute("time", histogram.time);
        group.set_attribute("realizations", static_cast<std::int64_t>(histogram.realizations));
        group.set_attribute("recorded_realizations", static_cast<std::int64_t>(histogram.recorded_realizations));
        if (!notes[h].empty()) group.set_attribute("realizations_note", notes[h]);
        const auto kurtosis = velocity_kurtosis(histogram);
        set_estimate(group, "kurtosis", kurtosis);
        try {
            const TailFit tail = fit_tail(histogram, tail_rule);
            set_estimate(group, "tail_gamma", tail.gamma);
            set_measured(group, "tail_gamma_fit_sigma", {tail.gamma_fit_sigma, tail.gamma_fit_sigma_note});
            group.set_attribute("tail_chi2_per_dof", tail.chi2_per_dof);
            group.set_attribute("tail_bins", static_cast<std::int64_t>(tail.bins));
            group.set_attribute("tail_range_lo", tail.z_lo);
            group.set_attribute("tail_range_hi", tail.z_hi);
            fmt::print("{:<16} tail gamma {} (chi2/dof {:.2f}, {} bins, |z|/rms in [{:.2f}, {:.2f}])",
                       histogram.label, format_estimate(tail.gamma, "{:.3f}"), tail.chi2_per_dof, tail.bins, tail.z_lo,
                       tail.z_hi);
        } catch (const InsufficientData& error) {
            group.set_attribute("tail_error", error.what());
            fmt::print("{:<16} tail: n/a ({})", histogram.label, error.what());
        }
        fmt::print("  kurtosis {}\n", format_estimate(kurtosis, "{:.3f}"));
        if (file) {
            const auto phi = scaled_distribution(histogram);
            file->comment(histogram.label);
            for (std::size_t b = 0; b < phi.z.size(); ++b) file->row({phi.z[b], phi.density[b]});
            file->blank_line();
        }
    }
    if (histograms.size() >= 2) {
        const auto collapse = fit_scaling_collapse(histograms);
        auto group = results.section("collapse");
        set_estimate(group, "beta", collapse.beta);
        set_measured(group, "distance_at_best", collapse.distance_at_best);
        group.set_attribute("distance_at_one_third", collapse.distance_at_one_third);
        group.set_attribute("max_deviation_at_one_third", collapse.max_deviation_at_one_third);
        fmt::print("scaling exponent {}; collapse distance {:.3g} at 1/3, max |dG| {:.3g}\n",
                   format_estimate(collapse.beta, "{:.4f}"), collapse.distance_at_one_third,
                   collapse.max_deviation_at_one_third);
    } else {
        fmt::print("scaling exponent n/a (one histogram: a collapse needs histograms at 2 or more times)\n");
    }
    commit_outputs(&results, {file.get()});
}

void run_shocks(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
                const std::string& data, const ShockRule& rule) {
    const auto snapshots = on_input(input, [&] { return read_snapshots(input); });
    if (snapshots.empty()) throw InsufficientData("no /snapshots (run with --snapshot-times)");
    ResultsFile results(output, invocation, {input});
    // Group snapshots by time.
    std::vector<double> times;
    for (const auto& s : snapshots)
        if (std::find(times.begin(), times.end(), s.time) == times.end()) times.push_back(s.time);
    for (std::size_t k = 0; k < times.size(); ++k) {
        std::vector<Snapshot> at_time;
        for (const auto& s : snapshots)
            if (s.time == times[k]) at_time.push_back(s);
        const auto summary = on_input(input, [&] { return summarize_shocks(at_time, rule); });
        auto group = results.section("shocks" + std::to_string(k));
        group.set_attribute("time", summary.time);
        set_estimate(group, "shock_count", summary.shocks);
        group.set_attribute("expected_shock_count", summary.expected_shocks);
        set_estimate(group, "slope_times_t", summary.slope_times_t);
        set_estimate(group, "density_corrected_slope_times_t", summary.density_corrected_slope_times_t);
        group.set_attribute("segments", static_cast<std::int64_t>(summary.segments));
        group.set_attribute("dense_segments", static_cast<std::int64_t>(summary.dense_segments));
        // What a shock is, said where the count is: shockgas-burgers counts the same snapshot's shocks
        // by the same rule (ShockRule's; cells serve only the segment fits).
        fmt::print("t {:g}: shocks {} (velocity drops >= {:g} v_rms, one per cluster or bunch; N t^-2/3 = {:.2f}); "
                   "segment slope x t = {} ({} sparse segments; {} dense runs left out)\n",
                   summary.time, format_estimate(summary.shocks, "{:.2f}"), rule.jump_fraction, summary.expected_shocks,
                   format_estimate(summary.slope_times_t, "{:.3f}"), summary.segments, summary.dense_segments);
    }
    std::unique_ptr<DataFile> file;
    if (!data.empty()) {
        const auto& first = snapshots.front();
        const auto profile = find_shocks(first, rule);
        file = std::make_unique<DataFile>(data,
                                          fmt::format("velocity profile of the first snapshot (t = {:g}); block 1: "
                                                      "shocks; block 2: fitted segments",
                                                      first.time),
                                          std::vector<std::string>{input}, std::vector<std::string>{"position", "velocity", "mass"});
        for (std::size_t i = 0; i < first.velocity.size(); ++i)
            file->row({first.position[i], first.velocity[i], first.mass[i]});
        file->blank_line();
        file->comment("shock_position shock_drop");
        for (std::size_t i = 0; i < profile.shock_position.size(); ++i)
            file->row({std::fmod(profile.shock_position[i], first.ring_length), profile.shock_drop[i]});
        file->blank_line();
        file->comment("x_lo x_hi points slope slope_sigma");
        for (const auto& segment : profile.segments)
            file->row({segment.x_lo, segment.x_hi, static_cast<double>(segment.points), segment.slope,
                       segment.slope_sigma});
    }
    commit_outputs(&results, {file.get()});
}

// Collapse time and cluster mass per input; with --vs eps the competing forms
// against eps, with --vs N the first-collapse statistics across N.
void run_collapse(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, const std::string& data, const std::string& versus,
                  const std::string& hazard_data) {
    std::vector<CollapseEvents> runs;
    std::vector<double> inelasticity, particles;
    for (const auto& input : inputs) {
        runs.push_back(read_collapse_events(input));
        inelasticity.push_back(runs.back().inelasticity);
        particles.push_back(static_cast<double>(runs.back().particles));
    }
    if (versus == "eps") require_distinct(inelasticity, inputs, "eps", "fitting the collapse forms (--vs eps)");
    if (versus == "N") require_distinct(particles, inputs, "N", "fitting the first-collapse statistics (--vs N)");
    ResultsFile results(output, invocation, inputs);
    std::vector<Estimate> time, mass;
    std::unique_ptr<DataFile> file, curves;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "inelastic collapse per input (mean and SE over realizations)",
                                          inputs, std::vector<std::string>{"eps", "particles", "collapse_time",
                                                                   "collapse_time_sigma", "cluster_mass",
                                                                   "cluster_mass_sigma", "collapsed", "realizations",
                                                                   "collapse_time_spread"});
    InputWithoutSigma without_sigma;
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        const auto summary = on_input(inputs[k], [&] { return summarize_collapse(runs[k]); });
        if (without_sigma.record(inputs[k], summary.time) && file)
            file->comment("*_sigma and collapse_time_spread nan in " + without_sigma.reason);
        time.push_back(summary.time);
        mass.push_back(summary.cluster_mass);
        // The spread is the sample standard deviation behind the time's sigma: n/a when it is, and why.
        const Measured spread{summary.time_spread, summary.time.note};
        auto group = results.section("collapse" + std::to_string(k));
        group.set_attribute("inelasticity", summary.inelasticity);
        group.set_attribute("particles", summary.particles);
        set_estimate(group, "collapse_time", summary.time);
        set_estimate(group, "cluster_mass", summary.cluster_mass);
        set_measured(group, "collapse_time_spread", spread);
        group.set_attribute("collapsed", static_cast<std::int64_t>(summary.collapsed));
        if (file)
            file->row({summary.inelasticity, static_cast<double>(summary.particles), summary.time.value,
                       summary.time.sigma, summary.cluster_mass.value, summary.cluster_mass.sigma,
                       static_cast<double>(summary.collapsed), static_cast<double>(summary.realizations),
                       summary.time_spread});
        fmt::print("eps {:<8g} N {:<8} collapse time {} (spread {}), cluster mass {} ({}/{} collapsed)\n",
                   summary.inelasticity, summary.particles, format_estimate(summary.time, "{:.4g}", "{:.2g}"),
                   // n/a alone: its reason is the time's sigma's, printed just before.
                   spread.known() ? fmt::format("{:.2g}", spread.value) : std::string("n/a"),
                   format_estimate(summary.cluster_mass, "{:.4g}", "{:.2g}"), summary.collapsed, summary.realizations);
    }
    const bool against_eps = versus == "eps";
    const std::string across_inputs = against_eps ? "forms against eps" : "first-collapse statistics across N";
    // Stored where the fits would be, so that a reader of either (and the figure, which draws the
    // points alone when the note is there) finds the reason.
    const auto fits_not_available = [&](const std::string& why) {
        const std::vector<std::string> sections = against_eps ? std::vector<std::string>{"time_forms", "mass_forms"}
                                                              : std::vector<std::string>{"first_collapse"};
        for (const auto& section : sections) results.section(section).set_attribute("note", why);
        fmt::print("{}: n/a ({})\n", across_inputs, why);
    };
    if (inputs.size() < 2) {
        fits_not_available(fmt::format("one input: give runs of 2 or more {}", versus));
    } else if (without_sigma.found()) {
        // Every fit across the inputs weighs them by their sigmas (the Gumbel spread by their spreads).
        // The hazard fit has its own Nelson-Aalen sigmas but is stored and printed as one block with
        // the N statistics (fit_first_collapse_scaling), so it is left out with them, and says so.
        fits_not_available(against_eps ? without_sigma.why_not("the forms against eps")
                                       : without_sigma.why_not("the fits across N") +
                                             "; the hazard fit, which has sigmas of its own, is left out with them");
    } else if (against_eps) {
        fmt::print("collapse time against eps:\n");
        set_collapse_forms(results, "time_forms", fit_collapse_forms(CollapseQuantity::time, inelasticity, time));
        fmt::print("cluster mass against eps:\n");
        set_collapse_forms(results, "mass_forms",
                           fit_collapse_forms(CollapseQuantity::cluster_mass, inelasticity, mass));
    } else {
        const auto scaling = fit_first_collapse_scaling(runs);
        auto group = results.section("first_collapse");
        set_power_law(group, "mean_time", scaling.mean_time);
        set_power_law(group, "cluster_mass", scaling.cluster_mass);
        group.set_attribute("hazard_exponent", scaling.hazard.slope);
        group.set_attribute("hazard_exponent_sigma", scaling.hazard.slope_sigma());
        group.set_attribute("hazard_prefactor", std::exp(scaling.hazard.intercept));
        set_estimate(group, "predicted_mean_time_exponent", scaling.predicted_mean_time_exponent);
        group.set_attribute("gumbel_min_regions", gumbel_min_regions);
        group.set_attribute("gumbel_runs", static_cast<std::int64_t>(scaling.gumbel_runs));
        if (scaling.gumbel_note.empty()) {
            group.set_attribute("gumbel_intercept", scaling.gumbel.intercept);
            set_measured(group, "gumbel_chi2_per_dof", scaling.gumbel.reduced_chi2());
            set_estimate(group, "gumbel_tau", scaling.gumbel_tau);
            set_estimate(group, "gumbel_predicted_spread", scaling.gumbel_predicted_spread);
            set_estimate(group, "gumbel_measured_spread", scaling.gumbel_measured_spread);
            fmt::print("{} runs with N/<m> >= {:g}: <t_collapse> = {:.4g} - ({}) ln N (chi2/dof {}); Gumbel spread pi "
                       "tau/sqrt 6 = {}, measured {}\n",
                       scaling.gumbel_runs, gumbel_min_regions, scaling.gumbel.intercept,
                       format_estimate(scaling.gumbel_tau, "{:.4g}"),
                       format_measured(scaling.gumbel.reduced_chi2(), "{:.2f}"),
                       format_estimate(scaling.gumbel_predicted_spread, "{:.4g}"),
                       format_estimate(scaling.gumbel_measured_spread, "{:.4g}"));
        } else {
            group.set_attribute("gumbel_note", scaling.gumbel_note);
            fmt::print("Gumbel fit of <t_collapse> against ln N: n/a ({})\n", scaling.gumbel_note);
        }
        fmt::print("<t_collapse> ~ N^({:.4f} +- {:.4f}) (chi2/dof {}); hazard per particle ~ t^({:.3f} +- {:.3f}), "
                   "which predicts N^({}); <m> ~ N^({:.4f} +- {:.4f})\n",
                   scaling.mean_time.slope, scaling.mean_time.slope_sigma(),
                   format_measured(scaling.mean_time.reduced_chi2(), "{:.2f}"), scaling.hazard.slope,
                   scaling.hazard.slope_sigma(), format_estimate(scaling.predicted_mean_time_exponent, "{:.4f}"),
                   scaling.cluster_mass.slope, scaling.cluster_mass.slope_sigma());
    }
    // One curve per input; with several N they should coincide.
    if (!hazard_data.empty()) {
        curves = std::make_unique<DataFile>(
            hazard_data, "Nelson-Aalen cumulative collapse hazard per particle H(t)/N, one block per input",
            inputs, std::vector<std::string>{"time", "hazard_per_particle", "hazard_per_particle_sigma", "particles"});
        for (std::size_t k = 0; k < runs.size(); ++k) {
            const auto curve = on_input(inputs[k], [&] { return cumulative_hazard_per_particle(runs[k]); });
            curves->comment("N = " + std::to_string(runs[k].particles));
            for (std::size_t i = 0; i < curve.time.size(); ++i)
                curves->row({curve.time[i], curve.per_particle[i], curve.per_particle_sigma[i],
                             static_cast<double>(runs[k].particles)});
            curves->blank_line();
            curves->blank_line();
        }
    }
    commit_outputs(&results, {file.get(), curves.get()});
}

// The speed/accuracy trade: each input against the reference run (P5).
void run_compare(const AnalysisInvocation& invocation, const std::string& reference_path,
                 const std::vector<std::string>& inputs, const std::string& output, const std::string& data,
                 const std::string& curves) {
    // A deviation from a reference of another N, r or start measures that
    // difference, not the threshold's cost: refused before any work.
    for (const auto& input : inputs)
        if (const std::string differences = comparison_differences(reference_path, input); !differences.empty())
            throw InputError(fmt::format("'{}' is not comparable with the reference '{}': {} (compare takes runs that "
                                         "differ only in delta, the sub-threshold rule, t_max, the samples and R)",
                                         input, reference_path, differences));
    const auto reference = on_input(reference_path, [&] { return read_temperature_run(reference_path); }).history;
    std::vector<std::string> all{reference_path};
    all.insert(all.end(), inputs.begin(), inputs.end());
    ResultsFile results(output, invocation, all);
    std::unique_ptr<DataFile> table, deviation_curves;
    if (!data.empty())
        table = std::make_unique<DataFile>(
            data, "cost and deviation of T(t) from the reference " + reference_path,
            all, std::vector<std::string>{"delta", "sticky", "collisions_per_particle", "cpu_seconds", "max_abs_deviation",
                                     "time_of_max", "departure_time", "t_valid_delta_cubed"});
    if (!curves.empty())
        deviation_curves = std::make_unique<DataFile>(curves, "<T>/<T_ref> - 1 per input, one block each",
                                                      all, std::vector<std::string>{"time", "deviation", "sigma"});
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const auto [comparison, collisions] = on_input(inputs[i], [&] {
            const TemperatureRun run = read_temperature_run(inputs[i]);
            const TimeSeries& series = run.series;
            // Collisions per particle at the last sample every realization reached.
            const auto last = static_cast<std::size_t>(
                std::find(series.time.begin(), series.time.end(), run.history.time.back()) - series.time.begin());
            std::vector<double> counts;
            for (std::int64_t r = 0; r < series.realizations; ++r) {
                const double value = series.at(series.collisions_per_particle, r, last);
                if (std::isfinite(value)) counts.push_back(value);
            }
            Measured mean_count =
                counts.empty() ? Measured::missing(fmt::format("no realization recorded its collisions at t = {:g}",
                                                               run.history.time.back()))
                               : Measured{mean_and_standard_error(counts).value, ""};
            return std::pair{compare_temperatures(run.history, reference, Realizations::paired), mean_count};
        });
        const auto file = h5::File::open_read(inputs[i]);
        const auto root = file.root();
        const double delta = root.attribute_double("velocity_threshold");
        const bool sticky = root.attribute_string("subthreshold") == "sticky";
        const double cpu = root.attribute_double("cpu_seconds");
        const double t_valid = delta > 0.0 ? std::pow(delta, -3.0) : INFINITY;
        auto group = results.section("compare" + std::to_string(i));
        group.set_attribute("input", inputs[i]);
        group.set_attribute("velocity_threshold", delta);
        group.set_attribute("subthreshold", sticky ? "sticky" : "elastic");
        set_measured(group, "collisions_per_particle", collisions);
        group.set_attribute("cpu_seconds", cpu);
        group.set_attribute("max_abs_deviation", comparison.max_abs_deviation);
        group.set_attribute("time_of_max", comparison.time_of_max);
        group.set_attribute("departure_time", comparison.departure_time);  // inf: never departs
        if (!comparison.sigma_note.empty()) group.set_attribute("deviation_sigma_note", comparison.sigma_note);
        // The runs share their initial states (checked above), so the deviation's sigma is the paired one.
        group.set_attribute("deviation_sigma", "paired: delete-one-pair jackknife of sum T / sum T_ref");
        group.set_attribute("realizations_compared", static_cast<std::int64_t>(comparison.realizations_compared));
        if (!comparison.pairing_note.empty()) group.set_attribute("pairing_note", comparison.pairing_note);
        group.set_attribute("t_valid", t_valid);
        fmt::print("{:<40} delta {:<8g} {:<7} {} coll/particle {:8.2f} s CPU  max |dT/T| {:.3g} at t = {:g}, {} "
                   "(delta^-3 = {})\n",
                   inputs[i], delta, sticky ? "sticky" : "elastic", format_measured(collisions, "{:10.4g}"), cpu,
                   comparison.max_abs_deviation, comparison.time_of_max,
                   std::isinf(comparison.departure_time) ? std::string("never departs")
                                                         : fmt::format("departs at {:g}", comparison.departure_time),
                   delta > 0.0 ? fmt::format("{:g}", t_valid) : std::string("inf: delta = 0"));
        if (table)
            table->row({delta, sticky ? 1.0 : 0.0, collisions.value, cpu, comparison.max_abs_deviation,
                        comparison.time_of_max, comparison.departure_time, t_valid});
        if (deviation_curves) {
            deviation_curves->comment(inputs[i]);
            if (!comparison.sigma_note.empty()) deviation_curves->comment("sigma nan: " + comparison.sigma_note);
            if (!comparison.pairing_note.empty()) deviation_curves->comment(comparison.pairing_note);
            for (std::size_t k = 0; k < comparison.time.size(); ++k)
                deviation_curves->row(
                    {comparison.time[k], comparison.relative_deviation[k], comparison.relative_sigma[k]});
            deviation_curves->blank_line();
        }
    }
    commit_outputs(&results, {table.get(), deviation_curves.get()});
}

// gamma of the far tail (Eq. (6)) from shockgas-tail output, and ln Phi for gnuplot.
void run_far_tail(const AnalysisInvocation& invocation, const std::string& input, const std::string& output,
                  const std::string& data, double z_lo, double z_hi, double window_shift, bool free_linear) {
    const FarTail tail = read_far_tail(input);
    const std::optional<double> linear_coefficient =
        free_linear ? std::nullopt : std::optional<double>(exact_tail_linear_coefficient);
    const TailExponent gamma = on_input(input, [&] {
        return estimate_tail_exponent(tail, z_lo, z_hi, window_shift, linear_coefficient);
    });
    ResultsFile results(output, invocation, {input});
    auto group = results.section("far_tail");
    set_estimate(group, "gamma", gamma.gamma);
    set_measured(group, "gamma_window_systematic", gamma.window_systematic);
    set_measured(group, "gamma_fit_sigma", {gamma.fit.gamma_fit_sigma, gamma.fit.gamma_fit_sigma_note});
    group.set_attribute("a", gamma.fit.a);
    group.set_attribute("b", gamma.fit.b);
    group.set_attribute("c", gamma.fit.c);
    group.set_attribute("chi2_per_dof", gamma.fit.chi2_per_dof);
    group.set_attribute("b_fitted", static_cast<std::int64_t>(free_linear));
    group.set_attribute("z_lo", gamma.fit.z_lo);
    group.set_attribute("z_hi", gamma.fit.z_hi);
    group.set_attribute("time", tail.time);
    group.set_attribute("window_lo", z_lo);
    group.set_attribute("window_hi", z_hi);
    if (!gamma.window_note.empty()) group.set_attribute("window_note", gamma.window_note);
    std::unique_ptr<DataFile> table;
    if (!data.empty()) {
        table = std::make_unique<DataFile>(
            data, "ln Phi(z) from " + input + " (shockgas-tail), with the fitted Eq. (6) form",
            std::vector<std::string>{input}, std::vector<std::string>{"z", "log_phi", "log_phi_sigma", "fitted_log_phi", "local_exponent"});
        if (!gamma.fit.gamma_note.empty()) table->comment("fitted_log_phi nan: gamma " + gamma.fit.gamma_note);
        for (std::size_t i = 0; i < tail.z.size(); ++i) {
            if (!std::isfinite(tail.log_phi[i])) continue;
            const double z = tail.z[i];
            // Eq. (6) with EB9's prefactor and linear term: ln Phi = c - 2 ln z - a z^gamma - b z.
            const double fitted =
                gamma.fit.c - 2.0 * std::log(z) - gamma.fit.a * std::pow(z, gamma.fit.gamma) - gamma.fit.b * z;
            const double local = z >= 1.0 ? local_tail_exponent(tail.z, tail.log_phi, z) : NAN;
            table->row({z, tail.log_phi[i], tail.log_phi_sigma[i], z > 0.0 ? fitted : NAN, local});
        }
    }
    commit_outputs(&results, {table.get()});
    fmt::print("{}: t = {:g}, gamma = {} (jackknife over chains) +- {}, fit over z in [{:.2f}, {:.2f}], {} bins, "
               "chi2/dof = {:.2f}; a = {:.3f}, b = {:.3f} ({})\n",
               input, tail.time, format_estimate(gamma.gamma, "{:.3f}"),
               format_measured(gamma.window_systematic, "{:.3f}", "window"), gamma.fit.z_lo, gamma.fit.z_hi,
               gamma.fit.points, gamma.fit.chi2_per_dof, gamma.fit.a, gamma.fit.b, free_linear ? "fitted" : "EB9");
    if (!gamma.window_note.empty()) fmt::print("note: {}\n", gamma.window_note);
}

}  // namespace shockgas::analysis
