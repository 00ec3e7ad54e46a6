// shockgas-analyze: one subcommand per estimator of the analysis library.
// Parses arguments, calls the library, writes the results file and the
// gnuplot data files; no analysis happens here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/analysis/collapse.hpp"
#include "shockgas/analysis/compare.hpp"
#include "shockgas/analysis/far_tail.hpp"
#include "shockgas/analysis/results.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"
#include "shockgas/cli.hpp"
#include "shockgas/h5.hpp"
#include "shockgas/output.hpp"
#include "shockgas/provenance.hpp"

namespace {

using namespace shockgas;
using namespace shockgas::analysis;

struct RunParameters {
    double restitution, velocity_threshold, particles, t_max;
};
RunParameters run_parameters(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    return {root.attribute_double("restitution"), root.attribute_double("velocity_threshold"),
            static_cast<double>(root.attribute_integer("particles")), root.attribute_double("t_max")};
}

std::string restitution_label(double restitution) {
    std::ostringstream out;
    out << "r=" << restitution;
    return out.str();
}

void write_temperature_data(const std::string& data, const std::string& input, const TemperatureHistory& history) {
    DataFile file(data, "T(t) ensemble mean, " + input, {"time", "temperature", "temperature_sigma"});
    for (std::size_t k = 0; k < history.time.size(); ++k)
        file.row({history.time[k], history.mean(k), history.standard_error(k)});
}

void run_decay(const std::string& input, const std::string& output, const std::string& data, const std::string& scan,
               double t_lo, double t_hi, const WindowRule& rule, double scan_width, double scan_step, bool data_only) {
    const auto series = read_timeseries(input);
    const auto history = TemperatureHistory::from(series);
    if (history.time.empty()) throw InsufficientData("no sample time reached by every realization");
    if (data_only) {
        // Runs stopped by collapse (delta = 0) are drawn, not fitted.
        write_temperature_data(data, input, history);
        return;
    }
    const auto run = run_parameters(input);
    // A window given in full needs no rule; a fully automatic one explains itself when empty.
    DecayWindow window = t_lo > 0.0 || t_hi > 0.0
                             ? decay_window_bounds(run.restitution, run.velocity_threshold, run.particles,
                                                   history.time.back(), rule)
                             : automatic_decay_window(run.restitution, run.velocity_threshold, run.particles,
                                                      history.time.back(), rule, series.status);
    if (t_lo > 0.0) window.t_lo = t_lo;
    if (t_hi > 0.0) window.t_hi = t_hi;
    const DecayFit fit = fit_temperature_decay(history, window.t_lo, window.t_hi);
    const auto windows = scan_decay_windows(history, scan_width, scan_step);
    const double systematic = window_systematic(history, fit.t_lo, fit.t_hi);
    ResultsFile results(output, "shockgas-analyze decay", {input});
    auto group = results.section("decay");
    group.set_attribute("exponent", fit.exponent);
    group.set_attribute("exponent_sigma", fit.exponent_sigma);  // NaN for one realization
    if (!std::isfinite(fit.exponent_sigma))
        group.set_attribute("exponent_sigma_note", "one realization: the jackknife has nothing to leave out");
    group.set_attribute("exponent_fit_sigma", fit.fit_sigma);
    group.set_attribute("exponent_window_systematic", systematic);
    group.set_attribute("chi2_per_dof", fit.chi2_per_dof);
    group.set_attribute("prefactor", fit.prefactor);
    group.set_attribute("t_lo", fit.t_lo);
    group.set_attribute("t_hi", fit.t_hi);
    group.set_attribute("points", static_cast<std::int64_t>(fit.points));
    group.set_attribute("window_rule", t_lo > 0.0 || t_hi > 0.0 ? "manual" : "automatic");
    std::vector<double> centre, exponent, sigma;
    for (const auto& w : windows) {
        centre.push_back(std::sqrt(w.t_lo * w.t_hi));
        exponent.push_back(w.exponent);
        sigma.push_back(w.exponent_sigma);
    }
    auto scan_group = results.section("window_scan");
    scan_group.set_attribute("width_decades", scan_width);
    scan_group.write("window_centre", centre);
    scan_group.write("exponent", exponent);
    scan_group.write("exponent_sigma", sigma);
    results.commit();
    if (!data.empty()) write_temperature_data(data, input, history);
    if (!scan.empty()) {
        DataFile file(scan, "decay exponent in moving windows of " + std::to_string(scan_width) + " decades",
                      {"t_centre", "t_lo", "t_hi", "exponent", "exponent_sigma", "chi2_per_dof", "points"});
        for (const auto& w : windows)
            file.row({std::sqrt(w.t_lo * w.t_hi), w.t_lo, w.t_hi, w.exponent, w.exponent_sigma, w.chi2_per_dof,
                      static_cast<double>(w.points)});
    }
    // One realization: nothing to leave out, so no jackknife sigma; say so
    // rather than print nan.
    const std::string jackknife = std::isfinite(fit.exponent_sigma)
                                      ? fmt::format("+- {:.4f} (jackknife)", fit.exponent_sigma)
                                      : "+- n/a (jackknife: one realization, nothing to leave out; run -R 2 or more)";
    fmt::print("decay exponent {:.4f} {} +- {:.4f} (window), chi2/dof {:.2f}, window [{:g}, {:g}], {} points\n",
               fit.exponent, jackknife, systematic, fit.chi2_per_dof, fit.t_lo, fit.t_hi, fit.points);
}

void run_crossover(const std::vector<std::string>& inputs, const std::string& output, const std::string& data,
                   const CrossoverRule& rule) {
    std::vector<double> inelasticity;
    std::vector<Estimate> t_dissip, t_stick, temperature;
    ResultsFile results(output, "shockgas-analyze crossover", inputs);
    std::unique_ptr<DataFile> file;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "crossovers per inelasticity",
                                          std::vector<std::string>{"eps", "t_dissip", "t_dissip_sigma", "t_stick",
                                                                   "t_stick_sigma", "T_stick", "T_stick_sigma",
                                                                   "haff_rate", "haff_rate_sigma"});
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        const auto run = run_parameters(inputs[k]);
        const double eps = (1.0 - run.restitution) / 2.0;
        const auto crossovers = find_crossovers(TemperatureHistory::from(read_timeseries(inputs[k])), rule);
        inelasticity.push_back(eps);
        t_dissip.push_back(crossovers.t_dissip);
        t_stick.push_back(crossovers.t_stick);
        temperature.push_back(crossovers.temperature_at_stick);
        auto group = results.section("crossover" + std::to_string(k));
        group.set_attribute("inelasticity", eps);
        set_estimate(group, "t_dissip", crossovers.t_dissip);
        set_estimate(group, "t_stick", crossovers.t_stick);
        set_estimate(group, "temperature_at_stick", crossovers.temperature_at_stick);
        set_estimate(group, "haff_rate", crossovers.haff_rate);
        if (file)
            file->row({eps, crossovers.t_dissip.value, crossovers.t_dissip.sigma, crossovers.t_stick.value,
                       crossovers.t_stick.sigma, crossovers.temperature_at_stick.value,
                       crossovers.temperature_at_stick.sigma, crossovers.haff_rate.value, crossovers.haff_rate.sigma});
        std::printf("eps %-8g t_dissip %.4g +- %.2g  t_stick %.4g +- %.2g  T(t_stick) %.4g +- %.2g\n", eps,
                    crossovers.t_dissip.value, crossovers.t_dissip.sigma, crossovers.t_stick.value,
                    crossovers.t_stick.sigma, crossovers.temperature_at_stick.value,
                    crossovers.temperature_at_stick.sigma);
    }
    if (inputs.size() >= 2) {
        auto group = results.section("scaling_in_eps");
        const auto dissip_fit = fit_against_inelasticity(inelasticity, t_dissip);
        const auto stick_fit = fit_against_inelasticity(inelasticity, t_stick);
        const auto temperature_fit = fit_against_inelasticity(inelasticity, temperature);
        set_power_law(group, "t_dissip", dissip_fit);
        set_power_law(group, "t_stick", stick_fit);
        set_power_law(group, "temperature_at_stick", temperature_fit);
        std::printf("t_dissip ~ eps^(%.3f +- %.3f), t_stick ~ eps^(%.3f +- %.3f), T(t_stick) ~ eps^(%.3f +- %.3f)\n",
                    dissip_fit.slope, dissip_fit.slope_sigma(), stick_fit.slope, stick_fit.slope_sigma(),
                    temperature_fit.slope, temperature_fit.slope_sigma());
    }
    results.commit();
}

void run_scaling(const std::vector<std::string>& inputs, const std::string& output, const std::string& data,
                 const TailRule& tail_rule) {
    std::vector<VelocityHistogram> histograms;
    for (const auto& input : inputs) {
        const auto these = read_histograms(input, restitution_label(run_parameters(input).restitution));
        histograms.insert(histograms.end(), these.begin(), these.end());
    }
    if (histograms.empty()) throw InsufficientData("no /histograms in the inputs (run with --histogram-times)");
    ResultsFile results(output, "shockgas-analyze scaling", inputs);
    std::unique_ptr<DataFile> file;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "Phi(z) = t^(-1/3) P(v,t), z = v t^(1/3); one block per histogram",
                                          std::vector<std::string>{"z", "Phi"});
    for (std::size_t h = 0; h < histograms.size(); ++h) {
        const auto& histogram = histograms[h];
        auto group = results.section("histogram" + std::to_string(h));
        group.set_attribute("label", histogram.label);
        group.set_attribute("time", histogram.time);
        set_estimate(group, "kurtosis", velocity_kurtosis(histogram));
        try {
            const TailFit tail = fit_tail(histogram, tail_rule);
            set_estimate(group, "tail_gamma", tail.gamma);
            group.set_attribute("tail_gamma_fit_sigma", tail.gamma_fit_sigma);
            group.set_attribute("tail_chi2_per_dof", tail.chi2_per_dof);
            group.set_attribute("tail_bins", static_cast<std::int64_t>(tail.bins));
            group.set_attribute("tail_range_lo", tail.z_lo);
            group.set_attribute("tail_range_hi", tail.z_hi);
            std::printf("%-16s tail gamma %.3f +- %.3f (chi2/dof %.2f, %zu bins, |z|/rms in [%.2f, %.2f])",
                        histogram.label.c_str(), tail.gamma.value, tail.gamma.sigma, tail.chi2_per_dof, tail.bins,
                        tail.z_lo, tail.z_hi);
        } catch (const InsufficientData& error) {
            group.set_attribute("tail_error", error.what());
            std::printf("%-16s tail: %s", histogram.label.c_str(), error.what());
        }
        const auto kurtosis = velocity_kurtosis(histogram);
        std::printf("  kurtosis %.3f +- %.3f\n", kurtosis.value, kurtosis.sigma);
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
        group.set_attribute("distance_at_best", collapse.distance_at_best);
        group.set_attribute("distance_at_one_third", collapse.distance_at_one_third);
        group.set_attribute("max_deviation_at_one_third", collapse.max_deviation_at_one_third);
        std::printf("scaling exponent %.4f +- %.4f; collapse distance %.3g at 1/3, max |dG| %.3g\n",
                    collapse.beta.value, collapse.beta.sigma, collapse.distance_at_one_third,
                    collapse.max_deviation_at_one_third);
    }
    results.commit();
}

void run_shocks(const std::string& input, const std::string& output, const std::string& data,
                const ShockRule& rule) {
    const auto snapshots = read_snapshots(input);
    if (snapshots.empty()) throw InsufficientData("no /snapshots (run with --snapshot-times)");
    ResultsFile results(output, "shockgas-analyze shocks", {input});
    // Group snapshots by time.
    std::vector<double> times;
    for (const auto& s : snapshots)
        if (std::find(times.begin(), times.end(), s.time) == times.end()) times.push_back(s.time);
    for (std::size_t k = 0; k < times.size(); ++k) {
        std::vector<Snapshot> at_time;
        for (const auto& s : snapshots)
            if (s.time == times[k]) at_time.push_back(s);
        const auto summary = summarize_shocks(at_time, rule);
        auto group = results.section("shocks" + std::to_string(k));
        group.set_attribute("time", summary.time);
        set_estimate(group, "shock_count", summary.shocks);
        group.set_attribute("expected_shock_count", summary.expected_shocks);
        set_estimate(group, "slope_times_t", summary.slope_times_t);
        set_estimate(group, "density_corrected_slope_times_t", summary.density_corrected_slope_times_t);
        group.set_attribute("segments", static_cast<std::int64_t>(summary.segments));
        group.set_attribute("dense_segments", static_cast<std::int64_t>(summary.dense_segments));
        std::printf("t %g: %.2f +- %.2f shocks (N t^-2/3 = %.2f); segment slope x t = %.3f +- %.3f (%zu sparse "
                    "segments; %zu dense runs left out)\n",
                    summary.time, summary.shocks.value, summary.shocks.sigma, summary.expected_shocks,
                    summary.slope_times_t.value, summary.slope_times_t.sigma, summary.segments,
                    summary.dense_segments);
    }
    results.commit();
    if (!data.empty()) {
        const auto& first = snapshots.front();
        const auto profile = find_shocks(first, rule);
        DataFile file(data, "velocity profile of the first snapshot (t = " + std::to_string(first.time) +
                                "); block 1: shocks; block 2: fitted segments",
                      {"position", "velocity", "mass"});
        for (std::size_t i = 0; i < first.velocity.size(); ++i)
            file.row({first.position[i], first.velocity[i], first.mass[i]});
        file.blank_line();
        file.comment("shock_position shock_drop");
        for (std::size_t i = 0; i < profile.shock_position.size(); ++i)
            file.row({std::fmod(profile.shock_position[i], first.ring_length), profile.shock_drop[i]});
        file.blank_line();
        file.comment("x_lo x_hi points slope slope_sigma");
        for (const auto& segment : profile.segments)
            file.row({segment.x_lo, segment.x_hi, static_cast<double>(segment.points), segment.slope,
                      segment.slope_sigma});
    }
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
        group.set_attribute("exponent_sigma_scaled", form.exponent_sigma_scaled);
        group.set_attribute("parameters", static_cast<std::int64_t>(form.fit.parameters));
        group.set_attribute("points", static_cast<std::int64_t>(form.fit.points));
        group.set_attribute("chi2", form.fit.chi2);
        group.set_attribute("chi2_per_dof", form.fit.chi2_per_dof());
        group.set_attribute("aic", form.fit.aic());
        group.set_attribute("bic", form.fit.bic());
        group.set_attribute("delta_aic", form.fit.aic() - best_aic);
        group.set_attribute("delta_bic", form.fit.bic() - best_bic);
        std::printf("  %-15s %-28s exponent %8.4f +- %.4f (scaled %.4f)  chi2/dof %6.2f  dAIC %6.2f  dBIC %6.2f\n",
                    form.name.c_str(), form.formula.c_str(), form.exponent.value, form.exponent.sigma,
                    form.exponent_sigma_scaled, form.fit.chi2_per_dof(), form.fit.aic() - best_aic,
                    form.fit.bic() - best_bic);
    }
}

// Collapse time and cluster mass per input; with --vs eps the competing forms
// against eps, with --vs N the first-collapse statistics across N.
void run_collapse(const std::vector<std::string>& inputs, const std::string& output, const std::string& data,
                  const std::string& versus, const std::string& hazard_data) {
    ResultsFile results(output, "shockgas-analyze collapse", inputs);
    std::vector<CollapseEvents> runs;
    std::vector<double> inelasticity;
    std::vector<Estimate> time, mass;
    std::unique_ptr<DataFile> file;
    if (!data.empty())
        file = std::make_unique<DataFile>(data, "inelastic collapse per input (mean and SE over realizations)",
                                          std::vector<std::string>{"eps", "particles", "collapse_time",
                                                                   "collapse_time_sigma", "cluster_mass",
                                                                   "cluster_mass_sigma", "collapsed", "realizations",
                                                                   "collapse_time_spread"});
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        runs.push_back(read_collapse_events(inputs[k]));
        const auto summary = summarize_collapse(runs.back());
        inelasticity.push_back(summary.inelasticity);
        time.push_back(summary.time);
        mass.push_back(summary.cluster_mass);
        auto group = results.section("collapse" + std::to_string(k));
        group.set_attribute("inelasticity", summary.inelasticity);
        group.set_attribute("particles", summary.particles);
        set_estimate(group, "collapse_time", summary.time);
        set_estimate(group, "cluster_mass", summary.cluster_mass);
        group.set_attribute("collapse_time_spread", summary.time_spread);
        group.set_attribute("collapsed", static_cast<std::int64_t>(summary.collapsed));
        if (file)
            file->row({summary.inelasticity, static_cast<double>(summary.particles), summary.time.value,
                       summary.time.sigma, summary.cluster_mass.value, summary.cluster_mass.sigma,
                       static_cast<double>(summary.collapsed), static_cast<double>(summary.realizations),
                       summary.time_spread});
        std::printf("eps %-8g N %-8lld collapse time %.4g +- %.2g (spread %.2g), cluster mass %.4g +- %.2g "
                    "(%zu/%zu collapsed)\n",
                    summary.inelasticity, static_cast<long long>(summary.particles), summary.time.value,
                    summary.time.sigma, summary.time_spread, summary.cluster_mass.value, summary.cluster_mass.sigma,
                    summary.collapsed, summary.realizations);
    }
    if (versus == "eps" && inputs.size() >= 2) {
        std::printf("collapse time against eps:\n");
        set_collapse_forms(results, "time_forms", fit_collapse_forms(CollapseQuantity::time, inelasticity, time));
        std::printf("cluster mass against eps:\n");
        set_collapse_forms(results, "mass_forms",
                           fit_collapse_forms(CollapseQuantity::cluster_mass, inelasticity, mass));
    }
    if (versus == "N" && inputs.size() >= 2) {
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
        if (scaling.gumbel_runs >= 2) {
            group.set_attribute("gumbel_intercept", scaling.gumbel.intercept);
            group.set_attribute("gumbel_chi2_per_dof", scaling.gumbel.chi2_per_dof());
            set_estimate(group, "gumbel_tau", scaling.gumbel_tau);
            set_estimate(group, "gumbel_predicted_spread", scaling.gumbel_predicted_spread);
            set_estimate(group, "gumbel_measured_spread", scaling.gumbel_measured_spread);
            std::printf("%zu runs with N/<m> >= %g: <t_collapse> = %.4g - (%.4g +- %.2g) ln N (chi2/dof %.2f); Gumbel "
                        "spread pi tau/sqrt 6 = %.4g +- %.2g, measured %.4g +- %.2g\n",
                        scaling.gumbel_runs, gumbel_min_regions, scaling.gumbel.intercept, scaling.gumbel_tau.value,
                        scaling.gumbel_tau.sigma, scaling.gumbel.chi2_per_dof(), scaling.gumbel_predicted_spread.value,
                        scaling.gumbel_predicted_spread.sigma, scaling.gumbel_measured_spread.value,
                        scaling.gumbel_measured_spread.sigma);
        }
        std::printf("<t_collapse> ~ N^(%.4f +- %.4f) (chi2/dof %.2f); hazard per particle ~ t^(%.3f +- %.3f), "
                    "which predicts N^(%.4f +- %.4f); <m> ~ N^(%.4f +- %.4f)\n",
                    scaling.mean_time.slope, scaling.mean_time.slope_sigma(), scaling.mean_time.chi2_per_dof(),
                    scaling.hazard.slope, scaling.hazard.slope_sigma(), scaling.predicted_mean_time_exponent.value,
                    scaling.predicted_mean_time_exponent.sigma, scaling.cluster_mass.slope,
                    scaling.cluster_mass.slope_sigma());
        if (!hazard_data.empty()) {
            DataFile curves(hazard_data,
                            "Nelson-Aalen cumulative collapse hazard per particle H(t)/N, one block per input",
                            {"time", "hazard_per_particle", "hazard_per_particle_sigma", "particles"});
            for (const auto& run : runs) {
                const auto curve = cumulative_hazard_per_particle(run);
                curves.comment("N = " + std::to_string(run.particles));
                for (std::size_t i = 0; i < curve.time.size(); ++i)
                    curves.row({curve.time[i], curve.per_particle[i], curve.per_particle_sigma[i],
                                static_cast<double>(run.particles)});
                curves.blank_line();
                curves.blank_line();
            }
        }
    }
    results.commit();
}

// The speed/accuracy trade: each input against the reference run (P5).
void run_compare(const std::string& reference_path, const std::vector<std::string>& inputs, const std::string& output,
                 const std::string& data, const std::string& curves) {
    const auto reference = TemperatureHistory::from(read_timeseries(reference_path));
    std::vector<std::string> all{reference_path};
    all.insert(all.end(), inputs.begin(), inputs.end());
    ResultsFile results(output, "shockgas-analyze compare", all);
    std::unique_ptr<DataFile> table, deviation_curves;
    if (!data.empty())
        table = std::make_unique<DataFile>(
            data, "cost and deviation of T(t) from the reference " + reference_path,
            std::vector<std::string>{"delta", "sticky", "collisions_per_particle", "cpu_seconds", "max_abs_deviation",
                                     "time_of_max", "departure_time", "t_valid_delta_cubed"});
    if (!curves.empty())
        deviation_curves = std::make_unique<DataFile>(curves, "<T>/<T_ref> - 1 per input, one block each",
                                                      std::vector<std::string>{"time", "deviation", "sigma"});
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const auto series = read_timeseries(inputs[i]);
        const auto comparison = compare_temperatures(TemperatureHistory::from(series), reference);
        const auto file = h5::File::open_read(inputs[i]);
        const auto root = file.root();
        const double delta = root.attribute_double("velocity_threshold");
        const bool sticky = root.attribute_string("subthreshold") == "sticky";
        const double cpu = root.attribute_double("cpu_seconds");
        // Collisions per particle at the last sample every realization reached.
        double collisions = 0.0;
        std::int64_t counted = 0;
        for (std::int64_t r = 0; r < series.realizations; ++r) {
            const double value = series.at(series.collisions_per_particle, r, series.time.size() - 1);
            if (std::isfinite(value)) collisions += value, ++counted;
        }
        collisions = counted > 0 ? collisions / static_cast<double>(counted) : 0.0;
        const double t_valid = delta > 0.0 ? std::pow(delta, -3.0) : INFINITY;
        auto group = results.section("compare" + std::to_string(i));
        group.set_attribute("input", inputs[i]);
        group.set_attribute("velocity_threshold", delta);
        group.set_attribute("subthreshold", sticky ? "sticky" : "elastic");
        group.set_attribute("collisions_per_particle", collisions);
        group.set_attribute("cpu_seconds", cpu);
        group.set_attribute("max_abs_deviation", comparison.max_abs_deviation);
        group.set_attribute("time_of_max", comparison.time_of_max);
        group.set_attribute("departure_time", comparison.departure_time);
        group.set_attribute("t_valid", t_valid);
        std::printf("%-40s delta %-8g %-7s %10.4g coll/particle %8.2f s CPU  max |dT/T| %.3g at t = %g, departs at %g "
                    "(delta^-3 = %g)\n",
                    inputs[i].c_str(), delta, sticky ? "sticky" : "elastic", collisions, cpu,
                    comparison.max_abs_deviation, comparison.time_of_max, comparison.departure_time, t_valid);
        if (table)
            table->row({delta, sticky ? 1.0 : 0.0, collisions, cpu, comparison.max_abs_deviation, comparison.time_of_max,
                        comparison.departure_time, t_valid});
        if (deviation_curves) {
            deviation_curves->comment(inputs[i]);
            for (std::size_t k = 0; k < comparison.time.size(); ++k)
                deviation_curves->row({comparison.time[k], comparison.relative_deviation[k], comparison.relative_sigma[k]});
            deviation_curves->blank_line();
        }
    }
    results.commit();
}

// gamma of the far tail (Eq. (5)) from shockgas-tail output, and ln Phi for gnuplot.
void run_far_tail(const std::string& input, const std::string& output, const std::string& data, double z_lo,
                  double z_hi, double window_shift, bool free_linear) {
    const FarTail tail = read_far_tail(input);
    const std::optional<double> linear_coefficient =
        free_linear ? std::nullopt : std::optional<double>(exact_tail_linear_coefficient);
    const TailExponent gamma = estimate_tail_exponent(tail, z_lo, z_hi, window_shift, linear_coefficient);
    ResultsFile results(output, "shockgas-analyze far-tail", {input});
    auto group = results.section("far_tail");
    set_estimate(group, "gamma", gamma.gamma);
    group.set_attribute("gamma_window_systematic", gamma.window_systematic);
    group.set_attribute("gamma_fit_sigma", gamma.fit.gamma_fit_sigma);
    group.set_attribute("a", gamma.fit.a);
    group.set_attribute("b", gamma.fit.b);
    group.set_attribute("c", gamma.fit.c);
    group.set_attribute("chi2_per_dof", gamma.fit.chi2_per_dof);
    group.set_attribute("b_fitted", static_cast<std::int64_t>(free_linear));
    group.set_attribute("z_lo", gamma.fit.z_lo);
    group.set_attribute("z_hi", gamma.fit.z_hi);
    group.set_attribute("time", tail.time);
    results.commit();
    std::printf("%s: t = %g, gamma = %.3f +- %.3f (jackknife over chains) +- %.3f (window), fit over z in [%.2f, %.2f], "
                "%zu bins, chi2/dof = %.2f; a = %.3f, b = %.3f (%s)\n",
                input.c_str(), tail.time, gamma.gamma.value, gamma.gamma.sigma, gamma.window_systematic, gamma.fit.z_lo,
                gamma.fit.z_hi, gamma.fit.points, gamma.fit.chi2_per_dof, gamma.fit.a, gamma.fit.b,
                free_linear ? "fitted" : "EB9");
    if (data.empty()) return;
    DataFile table(data, "ln Phi(z) from " + input + " (shockgas-tail), with the fitted Eq. (5) form",
                   {"z", "log_phi", "log_phi_sigma", "fitted_log_phi", "local_exponent"});
    for (std::size_t i = 0; i < tail.z.size(); ++i) {
        if (!std::isfinite(tail.log_phi[i])) continue;
        const double z = tail.z[i];
        const double fitted = gamma.fit.c - 2.0 * std::log(z) - gamma.fit.a * std::pow(z, gamma.fit.gamma) - gamma.fit.b * z;
        const double local = z >= 1.0 ? local_tail_exponent(tail.z, tail.log_phi, z) : NAN;
        table.row({z, tail.log_phi[i], tail.log_phi_sigma[i], z > 0.0 ? fitted : NAN, local});
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"shockgas-analyze: estimators on shockgas-sim output (see analysis/README.md)"};
    app.set_version_flag("--version", "shockgas-analyze " + build_info().version);
    app.set_help_all_flag("--help-all", "print the options of every subcommand");
    app.require_subcommand(1);

    std::string input, output = "analysis.h5", data, scan;
    bool data_only = false;
    std::vector<std::string> inputs;
    double t_lo = 0.0, t_hi = 0.0, scan_width = 1.0, scan_step = 0.1;
    WindowRule window_rule;
    auto* decay = app.add_subcommand("decay", "T ~ t^-alpha: exponent +- jackknife sigma over the automatic window");
    decay->add_option("input", input, "shockgas-sim output")->required()->check(CLI::ExistingFile);
    decay->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    decay->add_option("--data", data, "T(t) data file for gnuplot");
    decay->add_option("--scan", scan, "window-scan data file for gnuplot");
    decay->add_flag("--data-only", data_only, "write the T(t) data file only, no fit (for runs stopped by collapse)");
    decay->add_option("--t-lo", t_lo, "override the window start");
    decay->add_option("--t-hi", t_hi, "override the window end");
    decay->add_option("--start-factor", window_rule.start_factor,
                      fmt::format("t_lo = factor * max({:g}, eps^-3/2), eps = (1 - r)/2", window_rule.scaling_onset))
        ->capture_default_str();
    decay->add_option("--end-factor", window_rule.end_factor, "t_hi <= factor * N^3/2")->capture_default_str();
    decay->add_option("--scan-width", scan_width, "scan window width, decades")->capture_default_str();
    decay->add_option("--scan-step", scan_step, "scan window step, decades")->capture_default_str();

    CrossoverRule crossover_rule;
    auto* crossover = app.add_subcommand("crossover", "t_dissip, t_stick, T(t_stick) per file and their powers of eps");
    crossover->add_option("inputs", inputs, "shockgas-sim outputs, one per eps")->required()->check(CLI::ExistingFile);
    crossover->add_option("-o,--output", output, "results HDF5 file")->capture_default_str();
    crossover->add_option("--data", data, "crossover table for gnuplot");
    crossover->add_option("--haff-floor", crossover_rule.haff_floor, "Haff fit on T >= floor * T0")
        ->capture_default_str();
    crossover->add_option("--stick-ratio", crossover_rule.stick_ratio, "t_stick: T / T_Haff reaches this")
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
        ->capture_default_str();
    shocks->add_option("--merge-gap", shock_rule.merge_gap_points,
                       "compressive runs at most this many expanding pairs apart are one shock")
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
    far_tail->add_option("--z-lo", z_lo, "fit window start")->capture_default_str();
    far_tail->add_option("--z-hi", z_hi, "fit window end")->capture_default_str();
    far_tail->add_option("--window-shift", window_shift, "window systematic: both ends moved by +- this")
        ->capture_default_str();
    far_tail->add_flag("--free-linear", free_linear, "fit the linear term b too (default: b from EB9)");

    if (const int status = cli::parse(app, argc, argv, "shockgas-analyze"); status >= 0) return status;
    return cli::run("shockgas-analyze", [&] {
        try {
            // Refuse an unwritable output before the work, naming it (not a temporary file).
            h5::check_writable(output);
            if (*decay) run_decay(input, output, data, scan, t_lo, t_hi, window_rule, scan_width, scan_step, data_only);
            if (*crossover) run_crossover(inputs, output, data, crossover_rule);
            if (*scaling) run_scaling(inputs, output, data, tail_rule);
            if (*shocks) run_shocks(input, output, data, shock_rule);
            if (*collapse) run_collapse(inputs, output, data, versus, hazard);
            if (*compare) run_compare(reference, inputs, output, data, curves);
            if (*far_tail) run_far_tail(input, output, data, z_lo, z_hi, window_shift, free_linear);
        } catch (const InsufficientData& error) {
            // Estimator messages say what is missing; add which file it is missing from.
            std::vector<std::string> files = inputs;
            if (!input.empty()) files.insert(files.begin(), input);
            if (!reference.empty()) files.insert(files.begin(), reference);
            throw InputError(fmt::format("{}, in '{}'", error.what(), fmt::join(files, "', '")));
        }
        return 0;
    });
}
