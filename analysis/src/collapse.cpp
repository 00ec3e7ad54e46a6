// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/collapse.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace shockgas::analysis {

namespace {

// What is wrong with /collapse/realization, if anything: each realization collapses at most once and
// is one of the run's R. A realization listed twice (a damaged or hand-made file) would count one
// collapse twice and pass the all-collapsed check with one missing.
std::optional<std::string> realization_index_problem(const h5::Group& group, std::size_t realizations) {
    if (!group.has("realization")) return std::nullopt;  // files without it: nothing to check
    std::vector<std::int64_t> index = group.read_integers("realization");
    for (const std::int64_t r : index)
        if (r < 0 || static_cast<std::size_t>(r) >= realizations)
            return fmt::format("realization holds {}, outside the run's 0 ... {}", r, realizations - 1);
    std::sort(index.begin(), index.end());
    const auto twice = std::adjacent_find(index.begin(), index.end());
    if (twice != index.end()) return fmt::format("realization {} collapses twice", *twice);
    return std::nullopt;
}

}  // namespace

CollapseEvents read_collapse_events(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    check_simulation_output(root, path);
    CollapseEvents events;
    events.inelasticity = (1.0 - root.attribute_double("restitution")) / 2.0;  // r = 1 - 2 eps
    events.particles = root.attribute_integer("particles");
    events.realizations = static_cast<std::size_t>(root.attribute_integer("realizations"));
    events.t_max = root.attribute_double("t_max");
    if (root.has_attribute("velocity_threshold")) events.velocity_threshold = root.attribute_double("velocity_threshold");
    if (!root.has("collapse")) return events;
    const auto group = root.open_group("collapse");
    events.time = group.read_doubles("time");
    events.cluster_mass = group.read_doubles("cluster_mass");
    // A damaged or hand-made /collapse would pair times with the wrong masses
    // or average impossible values: refused, named.
    std::string problem;
    if (events.cluster_mass.size() != events.time.size())
        problem = fmt::format("cluster_mass holds {} values but time {}", events.cluster_mass.size(), events.time.size());
    else if (events.time.size() > events.realizations)
        problem = fmt::format("{} collapses, more than the {} realizations", events.time.size(), events.realizations);
    else if (const auto index_problem = realization_index_problem(group, events.realizations))
        problem = *index_problem;
    else if (!std::all_of(events.time.begin(), events.time.end(), [](double t) { return t > 0.0 && std::isfinite(t); }))
        problem = "time holds a value that is not positive and finite";
    else if (!std::all_of(events.cluster_mass.begin(), events.cluster_mass.end(),
                          [](double m) { return m >= 1.0 && std::isfinite(m); }))
        problem = "cluster_mass holds a value below one particle";
    if (!problem.empty()) throw h5::Error(fmt::format("/collapse: {} in '{}'", problem, path));
    return events;
}

CollapseSummary summarize_collapse(const CollapseEvents& events) {
    CollapseSummary summary;
    summary.inelasticity = events.inelasticity;
    summary.particles = events.particles;
    summary.collapsed = events.time.size();
    summary.realizations = events.realizations;
    const std::string which = fmt::format("eps = {:g}, N = {}: ", events.inelasticity, events.particles);
    // A threshold delta > 0 makes every collision slower than delta elastic or
    // sticky: inelastic collapse cannot happen at all, and no N would help.
    if (events.time.size() < 2 && events.velocity_threshold > 0.0)
        throw InsufficientData(which + std::to_string(events.time.size()) +
                               fmt::format(" realizations collapsed: the run has the threshold delta = {:g} > 0, below "
                                           "which collisions are elastic or sticky, so inelastic collapse cannot "
                                           "happen; collapse needs runs with delta = 0 (shockgas-sim -d 0)",
                                           events.velocity_threshold));
    if (events.realizations == 1) {
        if (events.time.empty())
            throw InsufficientData(which + "the run's one realization did not collapse before t_max (raise t_max, or "
                                           "more particles: collapse needs N >~ ln(1/eps)/eps)");
        // One realization: its collapse time and mass stand, their errors and the spread are n/a
        // with the jackknife's reason, as crossover's times (the SE of a mean is the mean's
        // delete-one jackknife; for R >= 2 it is computed directly below). The run is analysed,
        // not refused.
        const auto alone = [](double value) {
            return jackknife(1, [value](std::optional<std::size_t>) { return value; });
        };
        summary.time = alone(events.time.front());
        summary.cluster_mass = alone(events.cluster_mass.front());
        summary.time_spread = std::numeric_limits<double>::quiet_NaN();
        return summary;
    }
    if (events.time.size() < 2)
        throw InsufficientData(which + std::to_string(events.time.size()) +
                               " realizations collapsed; an error bar needs 2 or more (more particles: collapse "
                               "needs N >~ ln(1/eps)/eps)");
    if (events.time.size() < events.realizations)
        throw InsufficientData(which + "only " + std::to_string(events.time.size()) + " of " +
                               std::to_string(events.realizations) +
                               " realizations collapsed before t_max; the mean of those would be biased early "
                               "(raise t_max)");
    summary.time = mean_and_standard_error(events.time);
    summary.cluster_mass = mean_and_standard_error(events.cluster_mass);
    // Masses are whole particles: when every realization gives the same mass
    // (eps = 0.25: always 10), the scatter says SE = 0, which no fit can weigh.
    // The counting resolution is one particle, a rounding error of variance
    // 1/12 per realization, so the SE is at least 1/sqrt(12 n).
    const double mass_resolution = 1.0 / std::sqrt(12.0 * static_cast<double>(events.cluster_mass.size()));
    summary.cluster_mass.sigma = std::max(summary.cluster_mass.sigma, mass_resolution);
    summary.time_spread = summary.time.sigma * std::sqrt(static_cast<double>(events.time.size()));
    return summary;
}

double paper_exponent(CollapseQuantity quantity) { return quantity == CollapseQuantity::time ? -1.5 : -1.0; }

double mcnamara_young_cluster(double inelasticity) {
    if (!(inelasticity > 0.0 && inelasticity < 0.5))
        throw std::invalid_argument("McNamara-Young's minimal cluster needs 0 < eps < 1/2");
    // PRE 50, R28 (1994): n_min ~ ln(1/(1 - r)) / (1 - r), with 1 - r = 2 eps.
    return std::log(1.0 / (2.0 * inelasticity)) / (2.0 * inelasticity);
}

namespace {

// Fits ln y = ln C + s u + offset: free s, or s fixed when `fixed_slope` is given.
CollapseForm fit_form(std::string name, std::string formula, const std::vector<double>& regressor,
                      const std::vector<double>& offset, const std::vector<double>& log_value,
                      const std::vector<double>& log_sigma, const double* fixed_slope) {
    std::vector<double> shifted(log_value.size());
    for (std::size_t i = 0; i < shifted.size(); ++i) shifted[i] = log_value[i] - offset[i];
    CollapseForm form;
    form.name = std::move(name);
    form.formula = std::move(formula);
    form.fit = fixed_slope ? fixed_slope_fit(regressor, shifted, log_sigma, *fixed_slope)
                           : weighted_linear_fit(regressor, shifted, log_sigma);
    form.prefactor = std::exp(form.fit.intercept);
    form.exponent = {form.fit.slope, form.fit.slope_sigma()};
    // The PDG scale factor needs chi2/dof; a form through every point (2
    // points, 2 parameters) has none, and its scaled sigma is not known.
    const Measured chi2_per_dof = form.fit.reduced_chi2();
    form.exponent_sigma_scaled = chi2_per_dof.known()
                                     ? form.exponent.sigma * (chi2_per_dof.value > 1.0 ? std::sqrt(chi2_per_dof.value) : 1.0)
                                     : std::numeric_limits<double>::quiet_NaN();
    return form;
}

}  // namespace

std::vector<CollapseForm> fit_collapse_forms(CollapseQuantity quantity, const std::vector<double>& inelasticity,
                                             const std::vector<Estimate>& values) {
    if (inelasticity.size() != values.size())
        throw std::invalid_argument("fit_collapse_forms: eps and values differ in length");
    const double paper = paper_exponent(quantity);
    const std::size_t n = inelasticity.size();
    std::vector<double> log_eps(n), log_log(n), log_my(n), log_value(n), log_sigma(n), zero(n, 0.0), paper_offset(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double eps = inelasticity[i];
        if (!(eps > 0.0 && eps < 0.5) || !(values[i].value > 0.0))
            throw InsufficientData("the collapse forms need 0 < eps < 1/2 and a positive value; point " +
                                   std::to_string(i) + " is not");
        log_eps[i] = std::log(eps);
        log_log[i] = std::log(std::log(1.0 / eps));
        log_my[i] = std::log(mcnamara_young_cluster(eps));
        log_value[i] = std::log(values[i].value);
        log_sigma[i] = values[i].sigma / values[i].value;  // d ln y = dy / y
        paper_offset[i] = paper * log_eps[i];
    }
    const bool time = quantity == CollapseQuantity::time;
    const double my_slope = -paper;  // t ~ m_MY^(3/2), m ~ m_MY
    std::vector<CollapseForm> forms;
    forms.push_back(fit_form("power", "C eps^x", log_eps, zero, log_value, log_sigma, nullptr));
    forms.push_back(fit_form("log_corrected", time ? "C eps^-3/2 (ln 1/eps)^y" : "C eps^-1 (ln 1/eps)^y", log_log,
                             paper_offset, log_value, log_sigma, nullptr));
    forms.push_back(fit_form("paper", time ? "C eps^-3/2" : "C eps^-1", log_eps, zero, log_value, log_sigma, &paper));
    forms.push_back(fit_form("mcnamara_young", time ? "C [ln(1/2eps)/(2eps)]^3/2" : "C ln(1/2eps)/(2eps)", log_my,
                             zero, log_value, log_sigma, &my_slope));
    return forms;
}

CumulativeHazard cumulative_hazard_per_particle(const CollapseEvents& events) {
    if (events.particles <= 0) throw InsufficientData("the hazard per particle needs N > 0");
    if (events.time.size() > events.realizations)
        throw InsufficientData("more collapses than realizations");
    std::vector<double> time = events.time;
    std::sort(time.begin(), time.end());
    const double particles = static_cast<double>(events.particles);
    CumulativeHazard out;
    double hazard = 0.0, variance = 0.0;
    for (std::size_t j = 0; j < time.size(); ++j) {
        // Nelson-Aalen: one event among the R - j realizations still at risk.
        const double at_risk = static_cast<double>(events.realizations - j);
        hazard += 1.0 / at_risk;
        variance += 1.0 / (at_risk * at_risk);
        out.time.push_back(time[j]);
        out.per_particle.push_back(hazard / particles);
        out.per_particle_sigma.push_back(std::sqrt(variance) / particles);
    }
    return out;
}

FirstCollapseScaling fit_first_collapse_scaling(const std::vector<CollapseEvents>& runs) {
    std::vector<double> particles, mean_time, mean_time_sigma, mass, mass_sigma;
    std::vector<double> log_time, log_hazard, log_hazard_sigma;
    std::vector<double> gumbel_log_n, gumbel_time, gumbel_sigma;
    double spread_weight = 0.0, spread_sum = 0.0;
    for (const auto& run : runs) {
        // Named here: a NaN sigma would otherwise reach the fits as "a non-finite sigma".
        if (run.realizations < 2)
            throw InsufficientData(fmt::format("eps = {:g}, N = {}: one realization: the fits across N weigh each "
                                               "run by its error bar, which needs 2 or more (shockgas-sim -R 2 or more)",
                                               run.inelasticity, run.particles));
        const auto summary = summarize_collapse(run);
        if (static_cast<double>(run.particles) / summary.cluster_mass.value >= gumbel_min_regions) {
            gumbel_log_n.push_back(std::log(static_cast<double>(run.particles)));
            gumbel_time.push_back(summary.time.value);
            gumbel_sigma.push_back(summary.time.sigma);
            // SE of a sample standard deviation of n Gaussian values: s / sqrt(2(n - 1)).
            const double n = static_cast<double>(summary.collapsed);
            const double spread_sigma = summary.time_spread / std::sqrt(2.0 * (n - 1.0));
            spread_weight += 1.0 / (spread_sigma * spread_sigma);
            spread_sum += summary.time_spread / (spread_sigma * spread_sigma);
        }
        particles.push_back(static_cast<double>(run.particles));
        mean_time.push_back(summary.time.value);
        mean_time_sigma.push_back(summary.time.sigma);
        mass.push_back(summary.cluster_mass.value);
        mass_sigma.push_back(summary.cluster_mass.sigma);
        const auto curve = cumulative_hazard_per_particle(run);
        // The weights need no floor (unlike the cluster mass's SE, which can be 0): every term of
        // var H is positive, and by Cauchy-Schwarz (sum_{j<=i} a_j)^2 <= i sum_{j<=i} a_j^2, so the i-th
        // point's relative error sqrt(var H)/H lies in [1/sqrt(i), 1] (exactly 1 at the first collapse).
        // Its weight is at most i times the first point's: the largest share of one curve's weight
        // that one point holds is 0.64, 0.46, 0.19, 0.03 for R = 2, 3, 8, 64, never an infinite weight.
        for (std::size_t i = 0; i < curve.time.size(); ++i) {
            log_time.push_back(std::log(curve.time[i]));
            log_hazard.push_back(std::log(curve.per_particle[i]));
            log_hazard_sigma.push_back(curve.per_particle_sigma[i] / curve.per_particle[i]);
        }
    }
    FirstCollapseScaling scaling;
    scaling.mean_time = fit_power_law(particles, mean_time, mean_time_sigma);
    scaling.cluster_mass = fit_power_law(particles, mass, mass_sigma);
    scaling.hazard = weighted_linear_fit(log_time, log_hazard, log_hazard_sigma, ErrorModel::scale_by_residuals);
    const double k = scaling.hazard.slope;
    // d(-1/k)/dk = 1/k^2.
    scaling.predicted_mean_time_exponent = {-1.0 / k, scaling.hazard.slope_sigma() / (k * k)};
    scaling.gumbel_runs = gumbel_log_n.size();
    // Runs of one N among those with many regions give no slope in ln N.
    const bool distinct_n = std::any_of(gumbel_log_n.begin(), gumbel_log_n.end(),
                                        [&](double log_n) { return log_n != gumbel_log_n.front(); });
    if (scaling.gumbel_runs >= 2 && !distinct_n)
        scaling.gumbel_note = fmt::format("the {} runs with N/<m> >= {:g} all have N = {:g}", scaling.gumbel_runs,
                                          gumbel_min_regions, std::exp(gumbel_log_n.front()));
    else if (scaling.gumbel_runs < 2)
        scaling.gumbel_note = fmt::format("{} run{} with N/<m> >= {:g}; the Gumbel fit needs 2 N", scaling.gumbel_runs,
                                          scaling.gumbel_runs == 1 ? "" : "s", gumbel_min_regions);
    if (scaling.gumbel_runs >= 2 && distinct_n) {
        scaling.gumbel = weighted_linear_fit(gumbel_log_n, gumbel_time, gumbel_sigma);
        scaling.gumbel_tau = {-scaling.gumbel.slope, scaling.gumbel.slope_sigma()};
        const double pi_over_root6 = std::acos(-1.0) / std::sqrt(6.0);  // s.d. of the standard Gumbel law
        scaling.gumbel_predicted_spread = {pi_over_root6 * scaling.gumbel_tau.value,
                                           pi_over_root6 * scaling.gumbel_tau.sigma};
        scaling.gumbel_measured_spread = {spread_sum / spread_weight, 1.0 / std::sqrt(spread_weight)};
    }
    return scaling;
}

LinearFit fit_against_inelasticity(const std::vector<double>& inelasticity, const std::vector<Estimate>& values) {
    std::vector<double> value, sigma;
    for (const auto& v : values) {
        value.push_back(v.value);
        sigma.push_back(v.sigma);
    }
    return fit_power_law(inelasticity, value, sigma);
}

}  // namespace shockgas::analysis
