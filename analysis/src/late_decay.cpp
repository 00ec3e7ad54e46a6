// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/late_decay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "shockgas/analysis/cooling.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/kinetic_theory.hpp"

namespace shockgas::analysis {

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// Mean and standard error of the finite values[j] (NaN after a collapse) but
// values[left_out] (keep_all: none); missing when none is left. The delete-one
// jackknife of a mean is its standard error.
constexpr std::size_t keep_all = std::numeric_limits<std::size_t>::max();
Estimate mean_without(const std::vector<double>& values, std::size_t left_out) {
    std::vector<double> kept;
    for (std::size_t j = 0; j < values.size(); ++j)
        if (j != left_out && std::isfinite(values[j])) kept.push_back(values[j]);
    return kept.empty() ? Estimate::missing("no realization reached this sample") : mean_and_standard_error(kept);
}

// Column k of an R x K table, over realizations.
Estimate column_mean(const spheres::SphereResult& r, const std::vector<double>& table, std::size_t k) {
    std::vector<double> column;
    for (std::int64_t i = 0; i < r.realizations; ++i) column.push_back(r.at(table, i, k));
    return mean_without(column, keep_all);
}

}  // namespace

LateDecayFit fit_late_decay(const spheres::SphereOutput& run, double t_a, double t_b) {
    const auto& p = run.parameters;
    const auto& r = run.result;
    const double t0 = spheres::haff_time(p.dimension, p.packing_fraction, p.collision.restitution);
    LateDecayFit out;
    const auto missing = [&out](const std::string& why) {
        out.theta = out.crossover_time = Estimate::missing(why);
        out.chi2_per_dof = Measured::missing(why);
        return out;
    };
    if (!(t_b > t_a)) return missing(fmt::format("window empty: t_a = {:.4g} > t_b = {:.4g}", t_a, t_b));
    std::vector<std::size_t> samples;
    for (std::size_t k = 0; k < r.time.size(); ++k)
        if (r.time[k] > 0.0 && r.time[k] >= t_a && r.time[k] <= t_b) samples.push_back(k);
    out.points = samples.size();
    if (samples.size() < min_window_samples)
        return missing(fmt::format("window empty: {} samples from t_a = {:.4g} to t_b = {:.4g}, the fit needs {}",
                                   samples.size(), t_a, t_b, min_window_samples));
    // Realizations finite over the whole window: a collapsed one is left out,
    // so that every point of one fit averages the same realizations.
    std::vector<std::int64_t> rows;
    for (std::int64_t i = 0; i < r.realizations; ++i)
        if (std::all_of(samples.begin(), samples.end(),
                        [&](std::size_t k) { return std::isfinite(r.at(r.temperature, i, k)); }))
            rows.push_back(i);
    out.realizations = rows.size();
    if (rows.size() < 3)
        return missing(fmt::format("{} realization(s) finite from t_a = {:.4g} to t_b = {:.4g}: the jackknife's "
                                   "refits need 2 left for their points' errors",
                                   rows.size(), t_a, t_b));
    std::vector<double> time;
    std::vector<std::vector<double>> temperatures;  // per sample, per row
    for (std::size_t k : samples) {
        time.push_back(r.time[k]);
        temperatures.emplace_back();
        for (std::int64_t i : rows) temperatures.back().push_back(r.at(r.temperature, i, k));
    }
    // Each fit weighs its points by the standard errors of its own means. Over
    // noise seeds (tests/unit/test_analysis_late_decay.cpp) sigma_theta is then
    // 1.0, 1.13 and 1.55 times theta's scatter at R = 16, 8 and 4: on the safe
    // side; with every refit weighted as the full fit it was 0.81, 0.7 and 0.5.
    std::vector<LinearFit> fits;  // [0]: every realization; [1 + j]: without rows[j]
    try {
        for (std::size_t j = 0; j <= rows.size(); ++j) {
            std::vector<double> mean, sigma;
            for (const auto& at : temperatures) {
                const Estimate point = mean_without(at, j == 0 ? keep_all : j - 1);
                mean.push_back(point.value), sigma.push_back(point.sigma);
            }
            fits.push_back(fit_power_law(time, mean, sigma));  // ln T = ln A - theta ln t
        }
    } catch (const InsufficientData& error) {
        return missing(error.what());
    }
    const auto jackknifed = [&](auto of) {
        return jackknife(rows.size(), [&](std::optional<std::size_t> left_out) {
            return of(fits[left_out ? *left_out + 1 : 0]);
        });
    };
    out.theta = jackknifed([](const LinearFit& fit) { return -fit.slope; });
    // Haff's asymptote (t0/t)^2 meets A t^-theta where t^(2 - theta) = t0^2 / A;
    // a law falling as fast as Haff's or faster (theta >= 2) never meets it.
    out.crossover_time = jackknifed([t0](const LinearFit& fit) {
        return 2.0 + fit.slope > 0.0 ? std::pow(t0 * t0 / std::exp(fit.intercept), 1.0 / (2.0 + fit.slope))
                                     : not_a_number;
    });
    if (std::isnan(out.crossover_time.value))
        out.crossover_time = Estimate::missing(
            fmt::format("theta = {:.3g} >= 2: the late law never meets Haff's t^-2", out.theta.value));
    out.chi2_per_dof = fits[0].reduced_chi2();
    return out;
}

double thermal_over_flow(std::span<const double> density, std::span<const double> velocity_field, int dimension,
                         double particles, double temperature) {
    const auto d = static_cast<std::size_t>(dimension);
    if (velocity_field.size() != density.size() * d)
        throw std::invalid_argument(fmt::format("a velocity field of {} values is not {} cells x {} components",
                                                velocity_field.size(), density.size(), d));
    const double per_cell = particles / static_cast<double>(density.size());  // n_c = density_c N / cells
    std::vector<double> mean(d, 0.0);  // V-bar = sum_c n_c V_c / N, the centre of mass's velocity
    for (std::size_t c = 0; c < density.size(); ++c)
        for (std::size_t k = 0; k < d; ++k) mean[k] += density[c] * per_cell * velocity_field[c * d + k] / particles;
    double flow = 0.0;  // sum_c n_c |V_c - V-bar|^2
    for (std::size_t c = 0; c < density.size(); ++c)
        for (std::size_t k = 0; k < d; ++k) {
            const double u = velocity_field[c * d + k] - mean[k];
            flow += density[c] * per_cell * u * u;
        }
    flow /= particles;
    // d T = sum |v - V-bar|^2 / N splits into the flow part and the spread
    // within cells (the law of total variance), so d T - E_flow >= 0.
    return flow > 0.0 ? std::sqrt(std::max(0.0, dimension * temperature - flow) / flow) : not_a_number;
}

std::vector<LocalSlope> local_slopes(std::span<const double> time, std::span<const double> temperature) {
    std::vector<double> x, y;  // ln t, ln T
    for (std::size_t k = 0; k < time.size(); ++k)
        if (time[k] > 0.0 && temperature[k] > 0.0 && std::isfinite(temperature[k]))
            x.push_back(std::log(time[k])), y.push_back(std::log(temperature[k]));
    const double half_width = slope_smoothing_decades / 2.0 * std::log(10.0);
    std::vector<LocalSlope> slopes;
    for (std::size_t j = 0; j + 1 < x.size(); ++j) {
        const double mid = (x[j] + x[j + 1]) / 2.0;
        // The chord over the samples within half_width of mid: sum of d ln T
        // over sum of d ln t, the local slopes' mean weighted by d ln t.
        std::size_t lo = j, hi = j + 1;
        while (lo > 0 && mid - x[lo - 1] <= half_width) --lo;
        while (hi + 1 < x.size() && x[hi + 1] - mid <= half_width) ++hi;
        slopes.push_back({std::exp(mid), (y[j + 1] - y[j]) / (x[j + 1] - x[j]), (y[hi] - y[lo]) / (x[hi] - x[lo])});
    }
    return slopes;
}

TailSample velocity_tail(const spheres::SphereOutput& run, std::size_t histogram) {
    const auto& p = run.parameters;
    const auto& h = run.result.histograms.at(histogram);
    const auto bins = static_cast<std::size_t>(p.histogram_bins);
    if (h.counts.size() != bins)
        throw InputError(fmt::format("histogram at t = {} has {} counts for {} bins", h.time, h.counts.size(), bins));
    std::vector<double> edges(bins + 1);
    for (std::size_t b = 0; b <= bins; ++b)
        edges[b] = p.histogram_range * (2.0 * static_cast<double>(b) / static_cast<double>(bins) - 1.0);
    double total = h.outside;
    for (double n : h.counts) total += n;
    TailSample tail;
    tail.time = h.time;
    tail.outside_fraction = total > 0.0 ? h.outside / total : not_a_number;
    for (std::size_t b = 0; b < bins; ++b) {
        const double width = edges[b + 1] - edges[b];
        tail.u.push_back(0.5 * (edges[b] + edges[b + 1]));
        tail.density.push_back(h.counts[b] / (total * width));
        tail.density_sigma.push_back(std::sqrt(h.counts[b]) / (total * width));  // Poisson
    }
    try {
        const TailFit fit = fit_pooled_tail(edges, h.counts);
        tail.gamma = fit.gamma;
        tail.c = fit.c;
        tail.u_lo = fit.z_lo, tail.u_hi = fit.z_hi;
    } catch (const InsufficientData& error) {
        tail.gamma = Estimate::missing(error.what());
        tail.c = not_a_number;
    }
    return tail;
}

LocalPlateau local_plateau(const spheres::SphereOutput& run) {
    const auto& p = run.parameters;
    const auto& r = run.result;
    const double t0 = spheres::haff_time(p.dimension, p.packing_fraction, p.collision.restitution);
    std::string why;
    const auto plateau_of = [&](std::size_t left_out) -> std::pair<double, double> {
        std::vector<double> mean(r.time.size());
        for (std::size_t k = 0; k < r.time.size(); ++k) {
            std::vector<double> column;
            for (std::int64_t i = 0; i < r.realizations; ++i) column.push_back(r.at(r.temperature, i, k));
            mean[k] = mean_without(column, left_out).value;
        }
        const auto slopes = local_slopes(r.time, mean);
        // The overshoot: the first local minimum of the smoothed slope after t0
        // that a later slope exceeds by plateau_rise. The global minimum can be the
        // finite-size steepening, and a local minimum without that rise can be
        // noise in Haff's law.
        std::vector<double> highest_after(slopes.size() + 1, -std::numeric_limits<double>::infinity());
        for (std::size_t j = slopes.size(); j-- > 0;)
            highest_after[j] = std::max(highest_after[j + 1], slopes[j].smoothed);
        for (std::size_t j = 0; j + 1 < slopes.size(); ++j) {
            if (!(slopes[j].time > t0 && slopes[j + 1].smoothed > slopes[j].smoothed &&
                  highest_after[j + 1] >= slopes[j].smoothed + plateau_rise))
                continue;
            std::size_t top = j + 1;
            for (std::size_t i = top; i < slopes.size(); ++i)
                if (slopes[i].smoothed > slopes[top].smoothed) top = i;
            return {-slopes[top].smoothed, slopes[top].time};
        }
        why = fmt::format("the local slope does not rise by {} after t0 = {:.4g}", plateau_rise, t0);
        return {not_a_number, not_a_number};
    };
    LocalPlateau plateau;
    const auto [theta, time] = plateau_of(keep_all);
    if (std::isnan(theta)) {
        plateau.theta = Estimate::missing(why);
        plateau.time = not_a_number;
        return plateau;
    }
    plateau.time = time;
    plateau.theta = jackknife(static_cast<std::size_t>(r.realizations), [&](std::optional<std::size_t> left_out) {
        return left_out ? plateau_of(*left_out).first : theta;
    });
    return plateau;
}

LateDecaySummary summarize_late_decay(const spheres::SphereOutput& run, const LateDecayRule& rule) {
    const auto& p = run.parameters;
    const auto& r = run.result;
    const int d = p.dimension;
    const auto particles = static_cast<double>(p.particles);
    LateDecaySummary s;
    s.eps = (1.0 - p.collision.restitution) / 2.0;
    s.collision_frequency = spheres::enskog_frequency(d, p.packing_fraction, 1.0);
    s.haff_time = spheres::haff_time(d, p.packing_fraction, p.collision.restitution);
    // Ben-Naim et al. (1999): the late decay from tau = eps^(-4/(4-d)) to the
    // finite-size time tau = N^(2/d), in collision times tau = omega0 t.
    s.predicted_crossover = std::pow(s.eps, -4.0 / (4.0 - d)) / s.collision_frequency;
    s.finite_size_time = std::pow(particles, 2.0 / d) / s.collision_frequency;
    const double t_last = r.time.empty() ? 0.0 : r.time.back();
    s.window_start = rule.window_start * s.predicted_crossover;
    s.window_end = std::min(t_last, rule.window_end * s.finite_size_time);
    s.field_cell_size = spheres::box_length(d, p.particles, p.packing_fraction) / p.field_cells;
    s.late = fit_late_decay(run, s.window_start, s.window_end);
    // The window error: each end moved a quarter decade either way (an end
    // pushed past the last sample stays there); variants too short to fit are skipped.
    s.theta_window_sigma = Measured::missing(s.late.theta.note);
    const double shift = std::pow(10.0, window_shift_decades);
    double largest = -1.0;
    for (const auto& [start, end] : {std::pair{shift, 1.0}, {1.0 / shift, 1.0}, {1.0, shift}, {1.0, 1.0 / shift}}) {
        const double theta =
            fit_late_decay(run, s.window_start * start, std::min(t_last, s.window_end * end)).theta.value;
        if (!std::isnan(theta)) largest = std::max(largest, std::abs(theta - s.late.theta.value));  // NaN if no theta
    }
    if (!std::isnan(s.late.theta.value))
        s.theta_window_sigma = largest >= 0.0 ? Measured{largest, ""}
                                              : Measured::missing("no shifted window holds enough samples");
    // From 3 t0, just after Haff's regime starts: how far the exponent drifts.
    s.theta_free = fit_late_decay(run, 3.0 * s.haff_time, s.window_end).theta;
    s.plateau = local_plateau(run);
    const Estimate& t_c = s.late.crossover_time;
    s.crossover_collisions = {s.collision_frequency * t_c.value, s.collision_frequency * t_c.sigma, t_c.note};
    for (std::size_t k = 0; k < r.time.size(); ++k) {
        const Estimate temperature = column_mean(r, r.temperature, k);
        s.temperature.push_back(temperature.value);
        s.temperature_sigma.push_back(temperature.sigma);
        s.kurtosis.push_back(column_mean(r, r.velocity_kurtosis, k).value);
    }
    // Delta v / v at each snapshot, per realization (NaN where not reached).
    const std::size_t cells = field_cell_count(p);
    std::vector<std::vector<double>> ratios;  // per snapshot, per realization
    for (const auto& snapshot : r.snapshots) {
        const auto at = std::find_if(r.time.begin(), r.time.end(), [&](double t) {
            return std::abs(t - snapshot.time) <= 1e-12 * snapshot.time;  // snapshot times are on the sample grid
        });
        if (at == r.time.end())
            throw InputError(fmt::format("snapshot time {} is not a sample time of /timeseries", snapshot.time));
        const auto k = static_cast<std::size_t>(at - r.time.begin());
        std::vector<double> values(static_cast<std::size_t>(r.realizations), not_a_number);
        for (std::int64_t i = 0; i < r.realizations; ++i) {
            const auto row = static_cast<std::size_t>(i);
            const std::span<const double> density(snapshot.density.data() + row * cells, cells);
            const std::size_t components = cells * static_cast<std::size_t>(d);
            const std::span<const double> field(snapshot.velocity_field.data() + row * components, components);
            if (std::isfinite(r.at(r.temperature, i, k)) && std::isfinite(density[0]))
                values[row] = thermal_over_flow(density, field, d, particles, r.at(r.temperature, i, k));
        }
        s.flow.push_back({snapshot.time, mean_without(values, keep_all)});
        ratios.push_back(std::move(values));
    }
    // Its exponent over the snapshots from t_a on (Nie et al. 2002: -1/4 in 2D).
    std::vector<std::size_t> late;
    std::vector<double> time;
    for (std::size_t j = 0; j < s.flow.size(); ++j)
        if (s.flow[j].time >= s.window_start && s.flow[j].dv_over_v.sigma > 0.0)
            late.push_back(j), time.push_back(s.flow[j].time);
    try {
        if (late.size() < 3)
            throw InsufficientData(fmt::format("{} snapshots with Delta v / v and its error at t >= t_a = {:.4g}, the "
                                               "fit needs 3", late.size(), s.window_start));
        // Each refit with its own standard errors, as theta's (fit_late_decay).
        const auto realization_count = static_cast<std::size_t>(r.realizations);
        s.dv_over_v_exponent = jackknife(realization_count, [&](std::optional<std::size_t> left_out) {
            std::vector<double> mean, sigma;
            for (std::size_t j : late) {
                const Estimate point = mean_without(ratios[j], left_out.value_or(keep_all));
                mean.push_back(point.value), sigma.push_back(point.sigma);
            }
            return fit_power_law(time, mean, sigma).slope;
        });
    } catch (const InsufficientData& error) {  // also: a refit left with one realization at a snapshot
        s.dv_over_v_exponent = Estimate::missing(error.what());
    }
    for (std::size_t h = 0; h < r.histograms.size(); ++h) s.tails.push_back(velocity_tail(run, h));
    return s;
}

LinearFit fit_crossover_exponent(const std::vector<CrossoverPoint>& points) {
    std::vector<double> eps, collisions, sigma;
    for (const auto& point : points)
        if (point.eps > 0.0 && point.collisions.value > 0.0 && point.collisions.sigma > 0.0)
            eps.push_back(point.eps), collisions.push_back(point.collisions.value),
                sigma.push_back(point.collisions.sigma);
    const auto [lo, hi] = std::minmax_element(eps.begin(), eps.end());
    if (eps.size() < 2 || *lo == *hi)
        throw InsufficientData(fmt::format("{} inputs with a measured tau_c, not of two eps: no crossover exponent",
                                           eps.size()));
    return fit_power_law(eps, collisions, sigma);  // tau_c ~ eps^x, x = -4/(4-d) predicted
}

void run_late_decay(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                    const std::string& output, const LateDecayRule& rule, const LateDecayTables& tables) {
    std::vector<spheres::SphereOutput> runs;
    for (const auto& input : inputs) runs.push_back(spheres::read_spheres_output(input));
    ResultsFile results(output, invocation, inputs);
    std::optional<DataFile> table, slope_table, crossover_table, flow_table, tail_table, tail_fit_table;
    const auto open = [&](std::optional<DataFile>& file, const std::string& path, const std::string& what,
                          std::vector<std::string> columns) {
        if (!path.empty()) file.emplace(path, what, inputs, std::move(columns));
    };
    open(table, tables.data, "late decay: mean T over realizations and T t^theta; a block per input",
         {"t", "tau", "T", "T_sigma", "T_t_theta", "kurtosis"});
    open(slope_table, tables.slopes,
         "local slope d ln T / d ln t between successive samples at their geometric mid-time, and the chord slope "
         "over the samples within a 1/2-decade window centred on it; a block per input",
         {"t_mid", "tau_mid", "slope", "slope_smoothed"});
    open(crossover_table, tables.crossovers,
         "crossover times tau_c = omega0 t_c per input; a block per dimension and phi",
         {"eps", "tau_c", "tau_c_sigma", "t_c", "restitution", "particles", "theta"});
    open(flow_table, tables.fluctuations,
         "Delta v / v = sqrt((d T - E_flow) / E_flow) at each snapshot; a block per input",
         {"t", "tau", "dv_over_v", "dv_over_v_sigma"});
    open(tail_table, tables.tails,
         "velocity distribution P(u), u = (v_k - V_k) / sqrt(T) over realizations and components, with its Poisson "
         "sigma; a block per input and histogram time",
         {"u", "P", "P_sigma"});
    open(tail_fit_table, tables.tail_fits,
         "tail fit ln P = a - c |u|^gamma over |u| >= 1.5 rms at each histogram time (gamma 2: Gaussian, 1: "
         "exponential; sigma the Delta chi2 = 1 width with Poisson weights); a block per input",
         {"t", "tau", "gamma", "gamma_sigma", "c", "u_lo", "u_hi", "outside_fraction"});
    std::map<std::pair<int, double>, std::vector<std::size_t>> groups;  // (d, phi) -> inputs
    std::vector<LateDecaySummary> summaries;
    for (std::size_t f = 0; f < runs.size(); ++f) {
        const auto& p = runs[f].parameters;
        const int d = p.dimension;
        const LateDecaySummary& s = summaries.emplace_back(summarize_late_decay(runs[f], rule));
        groups[{d, p.packing_fraction}].push_back(f);
        const std::string label = fmt::format("{}D phi = {} r = {} eps = {:.4g} delta = {} N = {}: theta = {}", d,
                                              p.packing_fraction, p.collision.restitution, s.eps,
                                              p.collision.velocity_threshold, p.particles,
                                              format_estimate(s.late.theta, "{:.4f}"));
        auto section = results.section(fmt::format("late_decay{}", f));
        for (const auto& [name, count] : {std::pair{"dimension", std::int64_t{d}}, {"particles", p.particles},
                                          {"field_cells", p.field_cells},
                                          {"theta_points", static_cast<std::int64_t>(s.late.points)},
                                          {"histograms", static_cast<std::int64_t>(s.tails.size())}})
            section.set_attribute(name, count);
        // theta_burgers = d/2 (Ben-Naim et al. 1999); theta_aggregation = 2d/(d+2), ballistic aggregation's.
        for (const auto& [name, value] : std::initializer_list<std::pair<const char*, double>>{
                 {"restitution", p.collision.restitution}, {"eps", s.eps}, {"packing_fraction", p.packing_fraction},
                 {"velocity_threshold", p.collision.velocity_threshold}, {"field_cell_size", s.field_cell_size},
                 {"collision_frequency", s.collision_frequency}, {"haff_time", s.haff_time},
                 {"t_pred", s.predicted_crossover}, {"t_finite_size", s.finite_size_time},
                 {"window_start", s.window_start}, {"window_end", s.window_end}, {"theta_burgers", d / 2.0},
                 {"theta_aggregation", 2.0 * d / (d + 2.0)}, {"plateau_time", s.plateau.time}})
            section.set_attribute(name, value);
        set_estimate(section, "theta", s.late.theta);
        set_measured(section, "theta_window_sigma", s.theta_window_sigma);
        set_measured(section, "theta_chi2_per_dof", s.late.chi2_per_dof);
        set_estimate(section, "theta_free", s.theta_free);
        set_estimate(section, "theta_plateau", s.plateau.theta);
        set_estimate(section, "crossover_time", s.late.crossover_time);
        set_estimate(section, "crossover_collisions", s.crossover_collisions);
        set_estimate(section, "dv_over_v_exponent", s.dv_over_v_exponent);
        if (!s.tails.empty()) {  // HDF5 has no empty attribute
            std::vector<double> times, gammas, sigmas;
            for (const TailSample& tail : s.tails)
                times.push_back(tail.time), gammas.push_back(tail.gamma.value), sigmas.push_back(tail.gamma.sigma);
            section.set_attribute("tail_times", times);
            section.set_attribute("tail_gamma", gammas);
            section.set_attribute("tail_gamma_sigma", sigmas);
        }
        const double omega0 = s.collision_frequency;
        const auto block = [&](std::optional<DataFile>& file, const std::string& comment) {
            if (!file) return false;
            if (f > 0) file->blank_line();  // two empty lines: gnuplot's next index
            file->comment(comment);
            return true;
        };
        const auto& r = runs[f].result;
        if (block(table, label))
            for (std::size_t k = 1; k < r.time.size(); ++k)
                table->row({r.time[k], omega0 * r.time[k], s.temperature[k], s.temperature_sigma[k],
                            s.temperature[k] * std::pow(r.time[k], s.late.theta.value), s.kurtosis[k]});
        if (block(slope_table, label + "; smoothed over 1/2 decade"))
            for (const LocalSlope& slope : local_slopes(r.time, s.temperature))
                slope_table->row({slope.time, omega0 * slope.time, slope.slope, slope.smoothed});
        if (block(flow_table,
                  fmt::format("{}; field cells of side L/{} = {:.4g}", label, p.field_cells, s.field_cell_size)))
            for (const FlowSample& at : s.flow)
                flow_table->row({at.time, omega0 * at.time, at.dv_over_v.value, at.dv_over_v.sigma});
        if (block(tail_fit_table, label))
            for (const TailSample& tail : s.tails)
                tail_fit_table->row({tail.time, omega0 * tail.time, tail.gamma.value, tail.gamma.sigma, tail.c,
                                     tail.u_lo, tail.u_hi, tail.outside_fraction});
        if (tail_table)
            for (std::size_t h = 0; h < s.tails.size(); ++h) {
                const TailSample& tail = s.tails[h];
                if (f > 0 || h > 0) tail_table->blank_line();
                tail_table->comment(fmt::format("{}; t = {:.6g} (tau = {:.4g}): tail gamma = {}", label, tail.time,
                                                omega0 * tail.time, format_estimate(tail.gamma, "{:.3f}")));
                for (std::size_t b = 0; b < tail.u.size(); ++b)
                    tail_table->row({tail.u[b], tail.density[b], tail.density_sigma[b]});
            }
        // What an empty window leaves out shares theta's note: said once.
        const std::string fitted = std::isnan(s.late.theta.value) ? "" : fmt::format(
            " +- {} (window), chi2/dof {}; t_c = {} (tau_c = {})", format_measured(s.theta_window_sigma, "{:.4f}"),
            format_measured(s.late.chi2_per_dof, "{:.3g}"), format_estimate(s.late.crossover_time, "{:.4g}", "{:.2g}"),
            format_estimate(s.crossover_collisions, "{:.4g}", "{:.2g}"));
        fmt::print("{}{}; t_a = {:.4g}, t_b = {:.4g}; from 3 t0: theta = {}; plateau of the local exponent {} at "
                   "t = {:.4g} ({:.3g} t_N); Delta v / v ~ t^{} (cells of side {:.4g})\n",
                   label, fitted, s.window_start, s.window_end, format_estimate(s.theta_free, "{:.4f}"),
                   format_estimate(s.plateau.theta, "{:.4f}"), s.plateau.time, s.plateau.time / s.finite_size_time,
                   format_estimate(s.dv_over_v_exponent, "{:.3f}"), s.field_cell_size);
    }
    // tau_c against eps per dimension (and packing fraction: tau_c's prefactor depends on it).
    std::map<int, int> fractions;  // packing fractions per dimension
    for (const auto& [key, members] : groups) ++fractions[key.first];
    bool first_block = true;
    for (const auto& [key, members] : groups) {
        const auto [d, phi] = key;
        std::vector<CrossoverPoint> points;
        for (std::size_t f : members) points.push_back({summaries[f].eps, summaries[f].crossover_collisions});
        const double predicted = -4.0 / (4.0 - d);  // Ben-Naim et al. 1999: tau_c ~ eps^(-4/(4-d))
        auto group = results.section(fractions[d] > 1 ? fmt::format("crossover_d{}_phi{}", d, phi)
                                                      : fmt::format("crossover_d{}", d));
        group.set_attribute("dimension", static_cast<std::int64_t>(d));
        group.set_attribute("packing_fraction", phi);
        group.set_attribute("predicted_exponent", predicted);
        std::string fitted;
        try {
            const LinearFit fit = fit_crossover_exponent(points);
            set_power_law(group, "crossover", fit);
            fitted = format_estimate({fit.slope, fit.slope_sigma()}, "{:.3f}");
        } catch (const InsufficientData& error) {
            set_measured(group, "crossover_exponent", Measured::missing(error.what()));
            fitted = format_measured(Measured::missing(error.what()), "");
        }
        const std::string label =
            fmt::format("{}D phi = {}: tau_c ~ eps^x, x = {} (predicted {:.3g})", d, phi, fitted, predicted);
        fmt::print("{}\n", label);
        if (!crossover_table) continue;
        if (!first_block) crossover_table->blank_line();
        first_block = false;
        crossover_table->comment(label);
        for (std::size_t f : members)
            crossover_table->row({summaries[f].eps, summaries[f].crossover_collisions.value,
                                  summaries[f].crossover_collisions.sigma, summaries[f].late.crossover_time.value,
                                  runs[f].parameters.collision.restitution,
                                  static_cast<double>(runs[f].parameters.particles), summaries[f].late.theta.value});
    }
    commit_outputs(&results, {table ? &*table : nullptr, slope_table ? &*slope_table : nullptr,
                              crossover_table ? &*crossover_table : nullptr, flow_table ? &*flow_table : nullptr,
                              tail_table ? &*tail_table : nullptr, tail_fit_table ? &*tail_fit_table : nullptr});
}

}  // namespace shockgas::analysis
