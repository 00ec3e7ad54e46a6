// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/temperature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "shockgas/model/exact_constants.hpp"
#include "shockgas/io/h5.hpp"

namespace shockgas::analysis {

namespace {

using exact::uniform_initial_temperature;

std::vector<std::size_t> indices_in_window(const std::vector<double>& time, double t_lo, double t_hi) {
    std::vector<std::size_t> inside;
    for (std::size_t k = 0; k < time.size(); ++k)
        if (time[k] >= t_lo * (1.0 - 1e-12) && time[k] <= t_hi * (1.0 + 1e-12)) inside.push_back(k);
    return inside;
}

}  // namespace

double TemperatureHistory::mean(std::size_t k, std::optional<std::size_t> left_out) const {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t r = 0; r < realizations; ++r) {
        if (left_out && *left_out == r) continue;
        sum += at(r, k);
        ++count;
    }
    return sum / static_cast<double>(count);
}

double TemperatureHistory::standard_error(std::size_t k, std::optional<std::size_t> left_out) const {
    std::vector<double> column;
    column.reserve(realizations);
    for (std::size_t r = 0; r < realizations; ++r)
        if (!left_out || *left_out != r) column.push_back(at(r, k));
    return mean_and_standard_error(column).sigma;
}

TemperatureHistory::FitPoints TemperatureHistory::fit_points(const std::vector<std::size_t>& indices,
                                                             std::optional<std::size_t> left_out,
                                                             double fallback_fraction) const {
    // A standard error this small relative to <T> is rounding in the mean of identical values, not
    // scatter: weighing by it gave chi2/dof 41 and a slope width of 1e-17 on synthetic data.
    constexpr double rounding_level = 1e-12;
    FitPoints points;
    points.mean.reserve(indices.size());
    points.sigma.reserve(indices.size());
    std::vector<double> column;
    column.reserve(realizations);
    for (std::size_t k : indices) {
        column.clear();
        for (std::size_t r = 0; r < realizations; ++r)
            if (!left_out || *left_out != r) column.push_back(at(r, k));
        // The same sum in the same order as mean(k, left_out), divided by the same count.
        const Estimate estimate = mean_and_standard_error(column);
        points.mean.push_back(estimate.value);
        points.sigma.push_back(estimate.sigma > rounding_level * estimate.value ? estimate.sigma
                                                                                : fallback_fraction * estimate.value);
    }
    return points;
}

TemperatureHistory TemperatureHistory::from(const std::vector<double>& time, std::int64_t realizations,
                                            const std::vector<double>& temperature) {
    const auto rows = static_cast<std::size_t>(realizations);
    if (temperature.size() != rows * time.size())
        throw std::invalid_argument("temperature table is not realizations x times");
    TemperatureHistory history;
    history.realizations = rows;
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < time.size(); ++k) {
        bool every_realization = rows > 0;
        for (std::size_t r = 0; r < rows; ++r) {
            const double value = temperature[r * time.size() + k];
            if (!std::isfinite(value) || value <= 0.0) every_realization = false;
        }
        // t = 0 (schema 4 stores the start) has no place on the log-log axes
        // every analysis of T(t) uses: kept out here, in one place.
        if (every_realization && time[k] > 0.0) kept.push_back(k);
    }
    history.time.reserve(kept.size());
    for (std::size_t k : kept) history.time.push_back(time[k]);
    history.temperature.resize(rows * kept.size());
    for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t j = 0; j < kept.size(); ++j)
            history.temperature[r * kept.size() + j] = temperature[r * time.size() + kept[j]];
    return history;
}

TemperatureRun read_temperature_run(const std::string& path) {
    TemperatureRun run{read_timeseries(path), {}};
    const TimeSeries& series = run.series;
    const auto rows = static_cast<std::size_t>(std::max<std::int64_t>(series.realizations, 0));
    // A damaged or hand-made file: tables that are not realizations x times
    // would be read past their end or mis-assigned to times.
    const std::pair<const char*, const std::vector<double>*> tables[] = {
        {"temperature", &series.temperature}, {"collisions_per_particle", &series.collisions_per_particle}};
    for (const auto& [name, table] : tables)
        if (table->size() != rows * series.time.size())
            throw h5::Error(fmt::format("/timeseries/{} holds {} values, not realizations x times = {} x {} in '{}'",
                                        name, table->size(), rows, series.time.size(), path));
    if (series.realizations <= 0) throw InsufficientData("the file holds no realization (/timeseries has 0 rows)");
    run.history = TemperatureHistory::from(series);
    // An interrupted run whose realizations stopped at different times (the
    // last ones perhaps before their first sample) is not finished, not
    // empty: say how to finish it.
    if (run.history.time.empty())
        throw InsufficientData(fmt::format(
            "no sample time t > 0 was reached with T > 0 by every realization{}",
            series.status == "interrupted"
                ? ": the run was interrupted; continue it with shockgas-sim --resume and the same options"
                : ""));
    return run;
}

TemperatureHistory TemperatureHistory::from(const TimeSeries& series) {
    return from(series.time, series.realizations, series.temperature);
}

TemperatureHistory TemperatureHistory::from(const EnsembleResult& result) {
    return from(result.times, result.realizations, result.temperature);
}

DecayWindow decay_window_bounds(double restitution, double velocity_threshold, double particles, double last_time,
                                const WindowRule& rule) {
    const double inelasticity = (1.0 - restitution) / 2.0;  // r = 1 - 2 eps
    // Eq. (3): the sticky regime starts at t_stick ~ eps^(-3/2). Even the
    // sticky gas itself (r = 0) reaches its scaling state only after t ~ 10:
    // with the exact engine (N = 10^6, 40 realizations) T t^(2/3)/kappa is
    // 1.013 at t = 10, 1.005 at 31.6 and 1.002 at 100, which biases a fit
    // starting at t = 28 by +0.002 in the exponent. Hence max(10, ...).
    const double t_stick = std::max(rule.scaling_onset, std::pow(inelasticity, -1.5));
    DecayWindow window;
    window.t_lo = rule.start_factor * t_stick;
    // Eq. (3): the ring ends in one cluster at t ~ N^(3/2); the threshold is
    // harmless while v ~ t^(-1/3) >> delta, i.e. t << delta^(-3) (the paper's
    // t_valid, without a prefactor: with T = kappa t^(-2/3) the rms velocity
    // reaches delta at 0.1 delta^(-3), so the window's last decade feels it;
    // analysis/README.md).
    window.t_hi = std::min(last_time, rule.end_factor * std::pow(particles, 1.5));
    if (velocity_threshold > 0.0) window.t_hi = std::min(window.t_hi, std::pow(velocity_threshold, -3.0));
    return window;
}

DecayWindow automatic_decay_window(double restitution, double velocity_threshold, double particles,
                                   double last_time, const WindowRule& rule, const std::string& run_status) {
    const DecayWindow window = decay_window_bounds(restitution, velocity_threshold, particles, last_time, rule);
    if (!(window.t_hi > window.t_lo)) {
        const std::string start = fmt::format("the automatic window is empty: t_lo = {:g} ({:g} max({:g}, eps^-3/2))",
                                              window.t_lo, rule.start_factor, rule.scaling_onset);
        // A run stopped by collapse (delta = 0) or by Ctrl-C: more time or
        // particles would not help; the data end before the scaling regime.
        if ((run_status == "collapsed" || run_status == "interrupted") && last_time <= window.t_lo)
            throw InsufficientData(fmt::format(
                "{}, but the last sample time that every realization reached is t = {:g}, before it: the run {}; "
                "draw T(t) without a fit with --data-only, or choose a window with --t-lo/--t-hi",
                start, last_time,
                run_status == "collapsed"
                    ? "stopped at inelastic collapse (delta = 0 runs stop there)"
                    : "was interrupted (continue it with shockgas-sim --resume and the same options)"));
        // Name the option that emptied the window when it was the user's
        // (--start-factor or --end-factor away from its default), not only
        // the run: a longer run does not help a window closed by an option.
        const WindowRule defaults;
        const double ring_end = rule.end_factor * std::pow(particles, 1.5);
        const bool end_factor_closes = rule.end_factor != defaults.end_factor && !(ring_end > window.t_lo);
        const bool start_factor_closes =
            rule.start_factor != defaults.start_factor &&
            !(window.t_hi > defaults.start_factor * std::max(rule.scaling_onset, std::pow((1.0 - restitution) / 2.0,
                                                                                           -1.5)));
        std::string advice = "run longer or with more particles";
        if (end_factor_closes)
            advice = fmt::format("--end-factor {:g} puts {:g} N^3/2 = {:g} before t_lo: raise --end-factor (default "
                                 "{:g}), or run with more particles",
                                 rule.end_factor, rule.end_factor, ring_end, defaults.end_factor);
        else if (start_factor_closes)
            advice = fmt::format("--start-factor {:g} puts t_lo after t_hi: lower --start-factor (default {:g}), or "
                                 "run longer",
                                 rule.start_factor, defaults.start_factor);
        throw InsufficientData(fmt::format("{}, but t_hi = {:g} (min of t_max, {:g} N^3/2, delta^-3); {}", start,
                                           window.t_hi, rule.end_factor, advice));
    }
    return window;
}

namespace {

// x to two significant digits, rounded up (or down): a bound to ask for, not one a hair short.
double two_digits(double x, bool up) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return (up ? std::ceil(x / unit * (1.0 - 1e-12)) : std::floor(x / unit * (1.0 + 1e-12))) * unit;
}

}  // namespace

std::string short_window_note(double t_lo, double t_hi, bool manual, double last_time, double particles,
                              double velocity_threshold, const WindowRule& rule) {
    constexpr double decade = 10.0;
    constexpr double rounding = 1e-9;  // a window of 10^k to 10^(k+1) is a decade
    if (!(t_hi < decade * t_lo * (1.0 - rounding))) return "";
    const double wanted = decade * t_lo;
    const std::string head = fmt::format("the fit window spans {:.2f} decades, under one: its exponent has no window "
                                         "systematic and may still carry the crossover; ",
                                         std::log10(t_hi / t_lo));
    if (manual)
        return head + (wanted <= last_time
                           ? fmt::format("--t-hi {:g} would give a decade", two_digits(wanted, true))
                           : fmt::format("a decade from --t-lo {:g} needs a run to t_max >= {:g}", t_lo,
                                         two_digits(wanted, true)));
    // The automatic t_hi is min(t_max, end_factor N^3/2, delta^-3): each bound below 10 t_lo is named.
    std::vector<std::string> needs;
    if (last_time < wanted) needs.push_back(fmt::format("t_max >= {:g}", two_digits(wanted, true)));
    if (rule.end_factor * std::pow(particles, 1.5) < wanted)
        needs.push_back(fmt::format("N >= {:g}", two_digits(std::pow(wanted / rule.end_factor, 2.0 / 3.0), true)));
    if (velocity_threshold > 0.0 && std::pow(velocity_threshold, -3.0) < wanted)
        needs.push_back(fmt::format("delta <= {:g}", two_digits(std::pow(wanted, -1.0 / 3.0), false)));
    return head + fmt::format("a run with {} would give the automatic window a decade", fmt::join(needs, " and "));
}

DecayFit fit_temperature_decay(const TemperatureHistory& history, double t_lo, double t_hi) {
    const auto inside = indices_in_window(history.time, t_lo, t_hi);
    if (inside.size() < 3)
        throw InsufficientData(fmt::format("the window [{:g}, {:g}] holds {} sample times; a decay fit needs at least 3",
                                           t_lo, t_hi, inside.size()));
    // One realization (or identical ones): no scatter to weigh by; equal weights (sigma of ln T = 1).
    constexpr double equal_weights = 1.0;
    // Two realizations are not weighed either. A standard error of <T> from two values has one degree
    // of freedom, so the weights swing by orders of magnitude between neighbouring times and the fit
    // follows a few of them: 0.879 (chi2/dof 182) on a run whose two realizations give 0.802 each.
    // And the jackknife's replicas, one realization each, have no weights
    // of their own, so its sigma belonged to another estimator.
    constexpr std::int64_t fewest_to_weigh = 3;
    const bool weighted = history.realizations >= fewest_to_weigh;
    std::vector<double> time;
    for (std::size_t k : inside) time.push_back(history.time[k]);
    // ln <T> = ln C - alpha ln t: the exponent is minus the log-log slope.
    auto points = history.fit_points(inside, std::nullopt, equal_weights);
    if (!weighted)
        for (std::size_t i = 0; i < points.sigma.size(); ++i) points.sigma[i] = equal_weights * points.mean[i];
    const LinearFit full = fit_power_law(time, points.mean, points.sigma);
    DecayFit result;
    result.t_lo = t_lo;
    result.t_hi = t_hi;
    result.points = inside.size();
    result.exponent = -full.slope;
    result.fit_sigma = full.slope_sigma();
    result.chi2_per_dof = full.chi2_per_dof();
    result.prefactor = std::exp(full.intercept);
    if (!weighted) {
        // The weights are the standard errors of <T>: with one realization
        // there are none (with two, none worth the name, above), and the equal
        // weights put in their place (sigma of ln T = 1) give a chi2 and a slope
        // width that measure nothing (chi2/dof ~ 0.00). The exponent itself (the
        // unweighted fit) stands. Its jackknife sigma is n/a too: one realization
        // has nothing to leave out, and the two replicas of two, one realization
        // each, spread with one degree of freedom (a one-sigma band of it covers
        // 50%, not 68%; n/a, as the histogram tail's sigma with R = 2).
        const bool one = history.realizations < 2;
        result.fit_sigma = std::numeric_limits<double>::quiet_NaN();
        result.chi2_per_dof = std::numeric_limits<double>::quiet_NaN();
        result.fit_note = one ? "one realization: no standard error of <T> to weigh the fit by; run -R 3 or more"
                              : "two realizations: the scatter of <T> over two is too rough to weigh the fit "
                                "by, so it is unweighted; run -R 3 or more";
        result.exponent_sigma = std::numeric_limits<double>::quiet_NaN();
        result.exponent_sigma_note =
            one ? "one realization: the jackknife has nothing to leave out; run -R 3 or more"
                : "two realizations: the jackknife's two replicas, one realization each, give a sigma with one "
                  "degree of freedom; run -R 3 or more";
        return result;
    }
    // Each replica is the whole estimator on R - 1 realizations, its weights included: with the full
    // sample's weights frozen the jackknife comes out 35-40% small at R = 3 ... 6 (coverage of alpha
    // +- sigma 0.42-0.55 where Student's t gives 0.58-0.64, against 0.64-0.67 with the weights
    // recomputed, over 200-400 synthetic ensembles per R).
    const Estimate jack = jackknife(history.realizations, [&](std::optional<std::size_t> left_out) {
        if (!left_out) return -full.slope;  // the full sample's fit, made above
        const auto replica = history.fit_points(inside, left_out, equal_weights);
        return -fit_power_law(time, replica.mean, replica.sigma).slope;
    });
    result.exponent_sigma = jack.sigma;
    result.exponent_sigma_note = jack.note;
    return result;
}

std::vector<DecayFit> scan_decay_windows(const TemperatureHistory& history, double width_decades,
                                         double step_decades) {
    // !(x > 0) also refuses NaN.
    if (!(width_decades > 0.0) || !std::isfinite(width_decades) || !(step_decades >= min_scan_step_decades) ||
        !std::isfinite(step_decades))
        throw std::invalid_argument(fmt::format("scan_decay_windows: width {} and step {} decades", width_decades,
                                                step_decades));
    std::vector<DecayFit> scan;
    if (history.time.empty()) return scan;
    const double first = std::log10(history.time.front());
    const double last = std::log10(history.time.back());
    constexpr double rounding = 1e-9;  // decades: a window ending at the last sample counts
    if (first + width_decades > last + rounding) return scan;
    // Window i starts at first + i step: counted, not accumulated, so that a
    // step below the spacing of doubles near `first` cannot loop forever.
    const auto windows = static_cast<std::size_t>(std::floor((last + rounding - first - width_decades) / step_decades));
    for (std::size_t i = 0; i <= windows; ++i) {
        const double start = first + static_cast<double>(i) * step_decades;
        try {
            scan.push_back(fit_temperature_decay(history, std::pow(10.0, start), std::pow(10.0, start + width_decades)));
        } catch (const InsufficientData&) {
            // A window between sparse samples: skip it, the scan shows the gap.
        }
    }
    return scan;
}

Measured window_systematic(const TemperatureHistory& history, double t_lo, double t_hi) {
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    std::size_t inside = 0;
    for (const auto& w : scan_decay_windows(history, 1.0, 0.1)) {
        if (w.t_lo < t_lo * (1.0 - 1e-9) || w.t_hi > t_hi * (1.0 + 1e-9)) continue;
        lowest = std::min(lowest, w.exponent);
        highest = std::max(highest, w.exponent);
        ++inside;
    }
    // No window inside: the spread of nothing is not 0, it is unknown. Nor is the
    // spread of one window (a fit window of 1 to 1.1 decades): it is reported
    // missing, never as 0.000.
    if (inside == 0)
        return Measured::missing(fmt::format("no one-decade window with 3 samples lies inside the fit window [{:g}, "
                                             "{:g}]",
                                             t_lo, t_hi));
    if (inside == 1)
        return Measured::missing(fmt::format("only one one-decade window lies inside the fit window [{:g}, {:g}]: no "
                                             "spread to measure",
                                             t_lo, t_hi));
    return {(highest - lowest) / 2.0, ""};
}

namespace {

// Log-log interpolation of the first time at which f(t_k) crosses level
// downwards (f decreasing through level) starting from index begin.
std::optional<double> first_crossing(const std::vector<double>& time, const std::vector<double>& value,
                                     double level, std::size_t begin, bool upwards) {
    for (std::size_t k = std::max<std::size_t>(begin, 1); k < time.size(); ++k) {
        const bool crossed = upwards ? (value[k - 1] < level && value[k] >= level)
                                     : (value[k - 1] > level && value[k] <= level);
        if (!crossed) continue;
        const double fraction = (std::log(level) - std::log(value[k - 1])) /
                                (std::log(value[k]) - std::log(value[k - 1]));
        return std::exp(std::log(time[k - 1]) + fraction * (std::log(time[k]) - std::log(time[k - 1])));
    }
    return std::nullopt;
}

// The Haff rate a fitted as sqrt(T0/<T>) = b + a t (intercept free: the
// lattice start delays the first crossings) on the samples with
// <T> >= haff_floor T0, weighted by <T>'s standard errors.
double fitted_haff_rate(const std::vector<double>& time, const std::vector<double>& mean,
                        const std::vector<double>& weights_sigma, const CrossoverRule& rule) {
    const double initial = uniform_initial_temperature;
    std::vector<double> haff_time, haff_y, haff_sigma;
    for (std::size_t k = 0; k < time.size() && mean[k] >= rule.haff_floor * initial; ++k) {
        haff_time.push_back(time[k]);
        haff_y.push_back(std::sqrt(initial / mean[k]));
        // d sqrt(T0/T) = -(1/2) sqrt(T0/T) dT / T
        haff_sigma.push_back(0.5 * std::sqrt(initial / mean[k]) * weights_sigma[k] / mean[k]);
    }
    if (haff_time.size() < 3)
        throw InsufficientData(fmt::format("fewer than 3 samples with T >= {:g} T0 (--haff-floor): the homogeneous "
                                           "(Haff) regime is not resolved; sample more densely (--samples-per-decade), "
                                           "use a smaller inelasticity or a lower floor",
                                           rule.haff_floor));
    return weighted_linear_fit(haff_time, haff_y, haff_sigma).slope;
}

struct CrossoverValues {
    double t_dissip, haff_rate, t_stick, temperature_at_stick;
};

// points: <T> and its fit sigmas at every sample, from the realizations the estimate uses.
CrossoverValues crossovers_of(const TemperatureHistory& history, const TemperatureHistory::FitPoints& points,
                              const CrossoverRule& rule) {
    const double initial = uniform_initial_temperature;
    const std::size_t samples = history.time.size();
    const std::vector<double>& mean = points.mean;
    const std::vector<double>& weights_sigma = points.sigma;
    const auto dissip = first_crossing(history.time, mean, initial / 2.0, 0, false);
    if (!dissip)
        throw InsufficientData("<T> never crosses T0/2 between the first and last sample; "
                               "t_dissip is outside the run (first sample too late or t_max too short)");
    // Eq. (2) rearranged: sqrt(T0 / T) = 1 + a t, linear in t with a = A eps.
    const double rate = rule.haff_rate ? *rule.haff_rate : fitted_haff_rate(history.time, mean, weights_sigma, rule);
    std::vector<double> ratio(samples);
    for (std::size_t k = 0; k < samples; ++k) {
        const double haff_temperature = initial / std::pow(1.0 + rate * history.time[k], 2.0);
        ratio[k] = mean[k] / haff_temperature;
    }
    std::size_t after_dissip = 0;
    while (after_dissip < samples && history.time[after_dissip] < *dissip) ++after_dissip;
    const auto stick = first_crossing(history.time, ratio, rule.stick_ratio, after_dissip, true);
    if (!stick)
        throw InsufficientData(fmt::format("<T> never exceeds the Haff curve by the factor {:g} (--stick-ratio) "
                                           "before the last sample; t_stick is beyond t_max",
                                           rule.stick_ratio));
    // <T> at t_stick, log-log interpolated.
    std::size_t k = 1;
    while (k + 1 < samples && history.time[k] < *stick) ++k;
    const double fraction = (std::log(*stick) - std::log(history.time[k - 1])) /
                            (std::log(history.time[k]) - std::log(history.time[k - 1]));
    const double temperature = std::exp(std::log(mean[k - 1]) + fraction * (std::log(mean[k]) - std::log(mean[k - 1])));
    return {*dissip, rate, *stick, temperature};
}

}  // namespace

Crossovers find_crossovers(const TemperatureHistory& history, const CrossoverRule& rule) {
    std::vector<std::size_t> every_sample(history.time.size());
    std::iota(every_sample.begin(), every_sample.end(), std::size_t{0});
    // Identical realizations: equal relative weights, 10^-3 of <T>.
    constexpr double equal_weights = 1e-3;
    // The full sample (entry 0) and each replica without realization i (entry i + 1), computed once
    // for the four quantities' jackknifes. Each replica recomputes the Haff fit's weights from its own
    // realizations, as the decay fit's do.
    std::vector<CrossoverValues> replicas;
    replicas.reserve(history.realizations + 1);
    auto values_without = [&](std::optional<std::size_t> left_out) {
        return crossovers_of(history, history.fit_points(every_sample, left_out, equal_weights), rule);
    };
    replicas.push_back(values_without(std::nullopt));
    // One realization has no replica (nothing to leave out): the values stand, their sigmas are n/a
    // (jackknife's note); the run is analysed, not refused.
    if (history.realizations >= 2)
        for (std::size_t i = 0; i < history.realizations; ++i) replicas.push_back(values_without(i));
    Crossovers result;
    result.initial_temperature = uniform_initial_temperature;
    auto component = [&](double CrossoverValues::*member) {
        return jackknife(history.realizations, [&](std::optional<std::size_t> left_out) {
            return replicas[left_out ? *left_out + 1 : 0].*member;
        });
    };
    result.t_dissip = component(&CrossoverValues::t_dissip);
    result.haff_rate = component(&CrossoverValues::haff_rate);
    result.t_stick = component(&CrossoverValues::t_stick);
    result.temperature_at_stick = component(&CrossoverValues::temperature_at_stick);
    return result;
}

double derived_haff_rate(double inelasticity, VelocityLaw law) {
    const double constant = law == VelocityLaw::uniform ? exact::haff_constant_uniform : haff_constant_gaussian;
    return constant * inelasticity * (1.0 - inelasticity) * std::sqrt(uniform_initial_temperature);
}

namespace {

// ln(g(t) / level) at t = e^log_time, g(t) = kappa t^(-2/3) (1 + a t)^2 / T0:
// T_ref / T_Haff on the reference's sticky branch (Eqs. (2) and (3)).
double log_sticky_over_haff(double log_time, double rate, double level) {
    return std::log(exact::sticky_gas_temperature_prefactor / uniform_initial_temperature) - 2.0 / 3.0 * log_time +
           2.0 * std::log1p(rate * std::exp(log_time)) - std::log(level);
}

struct StickyOverHaff {
    double rate, level;
};

double log_sticky_over_haff_at(double log_time, void* parameters) {
    const auto& p = *static_cast<const StickyOverHaff*>(parameters);
    return log_sticky_over_haff(log_time, p.rate, p.level);
}

}  // namespace

Measured reference_stick_time(double inelasticity, const CrossoverRule& rule) {
    const double rate = derived_haff_rate(inelasticity);
    // T_ref / T_Haff = max(1, g(t)); in ln t, g falls until t = 1/(2a) and rises after it.
    // The Haff fit sees only Haff's branch if T_Haff >= kappa t^(-2/3) up to
    // the floor's time, (1/sqrt(floor) - 1)/a.
    const double floor_time = (1.0 / std::sqrt(rule.haff_floor) - 1.0) / rate;
    if (floor_time > 0.5 / rate && log_sticky_over_haff(std::log(floor_time), rate, 1.0) > 0.0)
        return Measured::missing(fmt::format("at eps = {:g} Haff's law meets kappa t^(-2/3) above T = {:g} T0 "
                                             "(--haff-floor): no Haff regime to fit",
                                             inelasticity, rule.haff_floor));
    StickyOverHaff reference{rate, rule.stick_ratio};
    double low = std::log(0.5 / rate);
    if (log_sticky_over_haff_at(low, &reference) >= 0.0)
        return Measured::missing(fmt::format("at eps = {:g} kappa t^(-2/3) exceeds Haff's law by {:g} "
                                             "(--stick-ratio) throughout",
                                             inelasticity, rule.stick_ratio));
    double high = low + 1.0;
    while (log_sticky_over_haff_at(high, &reference) < 0.0) high += 1.0;  // g grows as t^(4/3): a few steps
    gsl_function function{log_sticky_over_haff_at, &reference};
    gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(solver, &function, low, high);
    int status = GSL_CONTINUE;
    for (int iteration = 0; iteration < 200 && status == GSL_CONTINUE; ++iteration) {
        gsl_root_fsolver_iterate(solver);
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 1e-14,
                                        0.0);
    }
    const double root = gsl_root_fsolver_root(solver);
    gsl_root_fsolver_free(solver);
    return {std::exp(root), ""};
}

}  // namespace shockgas::analysis
