// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace shockgas::analysis {

std::vector<double> VelocityHistogram::pooled(std::optional<std::size_t> left_out_group, std::size_t groups) const {
    const std::size_t width = bins() + 2;
    std::vector<double> sum(width, 0.0);
    for (std::size_t r = 0; r < realizations; ++r) {
        if (left_out_group && r % groups == *left_out_group) continue;
        for (std::size_t b = 0; b < width; ++b) sum[b] += counts[r * width + b];
    }
    return sum;
}

namespace {

std::string time_label(const std::string& prefix, double time) {
    std::ostringstream out;
    out << prefix << (prefix.empty() ? "" : " ") << "t=" << time;
    return out.str();
}

std::size_t jackknife_groups(const std::vector<VelocityHistogram>& histograms) {
    std::size_t groups = max_jackknife_groups;
    for (const auto& h : histograms) groups = std::min(groups, h.realizations);
    return groups;
}

// Piecewise-linear CDF F(v) of a pooled histogram at velocity v; below[b] is
// the mass below edges[b] (underflow included), so below[bins] + overflow = total.
double cumulative(const std::vector<double>& edges, const std::vector<double>& below, double total, double v) {
    if (v <= edges.front()) return below.front() / total;
    if (v >= edges.back()) return below.back() / total;
    const auto upper = std::upper_bound(edges.begin(), edges.end(), v);
    const auto bin = static_cast<std::size_t>(upper - edges.begin()) - 1;  // edges[bin] <= v < edges[bin+1]
    const double fraction = (v - edges[bin]) / (edges[bin + 1] - edges[bin]);
    return (below[bin] + fraction * (below[bin + 1] - below[bin])) / total;
}

// The rescaled CDFs G_t(z) = F_t(z t^-beta) of every histogram on a common z grid.
std::vector<std::vector<double>> rescaled_cdfs(const std::vector<VelocityHistogram>& histograms, double beta,
                                               std::optional<std::size_t> left_out_group, std::size_t groups) {
    constexpr std::size_t grid_points = 201;
    // The z range every curve resolves: inside each histogram's edges.
    double z_lo = -std::numeric_limits<double>::infinity();
    double z_hi = std::numeric_limits<double>::infinity();
    for (const auto& h : histograms) {
        const double scale = std::pow(h.time, beta);
        z_lo = std::max(z_lo, h.edges.front() * scale);
        z_hi = std::min(z_hi, h.edges.back() * scale);
    }
    std::vector<std::vector<double>> curves;
    for (const auto& h : histograms) {
        const auto pooled = h.pooled(left_out_group, groups);
        std::vector<double> below(h.edges.size());
        below[0] = pooled[0];
        for (std::size_t b = 1; b < h.edges.size(); ++b) below[b] = below[b - 1] + pooled[b];
        const double total = below.back() + pooled.back();
        const double scale = std::pow(h.time, -beta);
        std::vector<double> curve(grid_points);
        for (std::size_t i = 0; i < grid_points; ++i) {
            const double z = z_lo + (z_hi - z_lo) * static_cast<double>(i) / static_cast<double>(grid_points - 1);
            curve[i] = cumulative(h.edges, below, total, z * scale);
        }
        curves.push_back(std::move(curve));
    }
    return curves;
}


}  // namespace

namespace {

// What makes a stored histogram unusable as a whole (empty: nothing), before
// its rows are looked at: a damaged or hand-made one would give numbers that
// look measured.
std::string histogram_shape_problem(const HistogramRecord& record, std::size_t realizations) {
    const auto& edges = record.edges;
    if (edges.size() < 2) return fmt::format("edges holds {} values; a histogram needs at least 2", edges.size());
    if (record.counts.size() != realizations * (edges.size() + 1))
        return fmt::format("counts holds {} values, not realizations x (bins + 2) = {} x {}", record.counts.size(),
                           realizations, edges.size() + 1);
    if (!std::all_of(edges.begin(), edges.end(), [](double e) { return std::isfinite(e); }) ||
        std::adjacent_find(edges.begin(), edges.end(), std::greater_equal<>()) != edges.end())
        return "edges are not finite and increasing";
    if (!std::all_of(record.counts.begin(), record.counts.end(), [](double c) { return c >= 0.0 && std::isfinite(c); }))
        return "counts holds a value that is negative or not finite";
    if (!(record.time > 0.0) || !std::isfinite(record.time))
        return fmt::format("its time {} is not positive and finite (z = v t^(1/3) needs t > 0)", record.time);
    return "";
}

}  // namespace

RunHistograms histograms_of_run(const EnsembleResult& result, const std::string& label_prefix,
                                const std::string& path) {
    RunHistograms run;
    run.realizations = static_cast<std::size_t>(std::max<std::int64_t>(result.realizations, 0));
    run.status = result.status;
    const std::size_t rows = run.realizations;
    const std::size_t samples = result.times.size();
    const bool series_complete = result.temperature.size() == rows * samples;
    auto refuse = [&](std::size_t index, const std::string& problem) {
        // The group's name as stored (schemas 1-2 unpadded, 3 on zero-padded).
        std::string name = std::to_string(index);
        if (!path.empty()) {
            const auto names = h5::File::open_read(path).root().open_group("histograms").numbered_children();
            if (index < names.size()) name = names[index];
        }
        throw h5::Error(fmt::format("/histograms/{}: {}{}", name, problem, path.empty() ? "" : " in '" + path + "'"));
    };
    for (std::size_t index = 0; index < result.histograms.size(); ++index) {
        const auto& record = result.histograms[index];
        if (const std::string problem = histogram_shape_problem(record, rows); !problem.empty()) refuse(index, problem);
        const std::size_t width = record.edges.size() + 1;
        std::vector<double> mass(rows, 0.0);
        for (std::size_t r = 0; r < rows; ++r)
            for (std::size_t b = 0; b < width; ++b) mass[r] += record.counts[r * width + b];
        // Reached: T(t) recorded (finite) at the histogram's time; a time the
        // series does not hold (a hand-made file) falls back to a row with mass.
        const auto sample = std::find(result.times.begin(), result.times.end(), record.time);
        const bool in_series = series_complete && sample != result.times.end();
        const auto k = static_cast<std::size_t>(sample - result.times.begin());
        std::vector<bool> reached(rows);
        for (std::size_t r = 0; r < rows; ++r)
            reached[r] = in_series ? std::isfinite(result.temperature[r * samples + k]) : mass[r] > 0.0;
        const bool any_mass = std::any_of(mass.begin(), mass.end(), [](double m) { return m > 0.0; });
        if (std::none_of(reached.begin(), reached.end(), [](bool b) { return b; }) && !any_mass && in_series) {
            run.unreached_times.push_back(record.time);
            continue;
        }
        // A histogram of zeros would give a "scaling exponent" of the grid's edge.
        if (!any_mass) refuse(index, "every count is 0: no mass to form P(v,t) from");
        VelocityHistogram h;
        h.time = record.time;
        h.label = time_label(label_prefix, h.time);
        h.edges = record.edges;
        h.recorded_realizations = rows;
        for (std::size_t r = 0; r < rows; ++r) {
            if (reached[r] != (mass[r] > 0.0))
                refuse(index, fmt::format("realization {} {} t = {:g} (/timeseries/temperature) but its row of counts "
                                          "holds {}",
                                          r, reached[r] ? "reached" : "did not reach", record.time,
                                          reached[r] ? "no mass" : "mass"));
            if (!reached[r]) continue;
            const auto row = record.counts.begin() + static_cast<std::ptrdiff_t>(r * width);
            h.counts.insert(h.counts.end(), row, row + static_cast<std::ptrdiff_t>(width));
            ++h.realizations;
        }
        run.histograms.push_back(std::move(h));
    }
    return run;
}

std::vector<VelocityHistogram> histograms_from(const EnsembleResult& result, const std::string& label_prefix) {
    return histograms_of_run(result, label_prefix).histograms;
}

RunHistograms read_histograms(const std::string& path, const std::string& label_prefix) {
    // The schema is read in one place (shockgas::read_output).
    return histograms_of_run(read_output(path).result, label_prefix, path);
}

double collapse_distance(const std::vector<VelocityHistogram>& histograms, double beta,
                         std::optional<std::size_t> left_out_group, std::size_t groups) {
    if (histograms.size() < 2) throw InsufficientData("a scaling collapse needs at least 2 histograms");
    const auto curves = rescaled_cdfs(histograms, beta, left_out_group, groups);
    double sum = 0.0;
    std::size_t pairs = 0;
    for (std::size_t a = 0; a < curves.size(); ++a)
        for (std::size_t b = a + 1; b < curves.size(); ++b) {
            double squares = 0.0;
            for (std::size_t i = 0; i < curves[a].size(); ++i)
                squares += (curves[a][i] - curves[b][i]) * (curves[a][i] - curves[b][i]);
            sum += squares / static_cast<double>(curves[a].size());
            ++pairs;
        }
    return sum / static_cast<double>(pairs);
}

double collapse_max_deviation(const std::vector<VelocityHistogram>& histograms, double beta) {
    const auto curves = rescaled_cdfs(histograms, beta, std::nullopt, 1);
    double largest = 0.0;
    for (std::size_t a = 0; a < curves.size(); ++a)
        for (std::size_t b = a + 1; b < curves.size(); ++b)
            for (std::size_t i = 0; i < curves[a].size(); ++i)
                largest = std::max(largest, std::abs(curves[a][i] - curves[b][i]));
    return largest;
}

ScalingCollapse fit_scaling_collapse(const std::vector<VelocityHistogram>& histograms, double beta_min,
                                     double beta_max) {
    double t_min = std::numeric_limits<double>::infinity(), t_max = 0.0;
    for (const auto& h : histograms) {
        t_min = std::min(t_min, h.time);
        t_max = std::max(t_max, h.time);
    }
    if (!(t_max > t_min)) throw InsufficientData("the scaling exponent needs histograms at 2 or more distinct times");
    ScalingCollapse result;
    result.jackknife_groups = jackknife_groups(histograms);
    const std::size_t groups = result.jackknife_groups;
    result.beta = bounded_jackknife(groups, [&](std::optional<std::size_t> left_out) {
        return minimise([&](double beta) { return collapse_distance(histograms, beta, left_out, groups); }, beta_min,
                        beta_max);
    });
    result.distance_at_best = std::isnan(result.beta.value)
                                  ? Measured::missing("beta " + result.beta.note)
                                  : Measured{collapse_distance(histograms, result.beta.value), ""};
    result.distance_at_one_third = collapse_distance(histograms, 1.0 / 3.0);
    result.max_deviation_at_one_third = collapse_max_deviation(histograms, 1.0 / 3.0);
    return result;
}

ScaledDistribution scaled_distribution(const VelocityHistogram& histogram, double beta) {
    const auto pooled = histogram.pooled();
    double total = 0.0;
    for (double c : pooled) total += c;
    ScaledDistribution out;
    const double scale = std::pow(histogram.time, beta);
    // Eq. (4): Phi(z) = t^-beta P(v, t), z = v t^beta.
    for (std::size_t b = 0; b < histogram.bins(); ++b) {
        const double width = histogram.edges[b + 1] - histogram.edges[b];
        out.z.push_back(0.5 * (histogram.edges[b] + histogram.edges[b + 1]) * scale);
        out.density.push_back(pooled[b + 1] / (total * width) / scale);
    }
    out.outside_fraction = (pooled.front() + pooled.back()) / total;
    return out;
}

Estimate velocity_kurtosis(const VelocityHistogram& histogram) {
    const std::size_t groups = std::min(histogram.realizations, max_jackknife_groups);
    auto kurtosis = [&](std::optional<std::size_t> left_out) {
        const auto pooled = histogram.pooled(left_out, groups);
        double mass = 0.0, first = 0.0;
        for (std::size_t b = 0; b < histogram.bins(); ++b) {
            const double centre = 0.5 * (histogram.edges[b] + histogram.edges[b + 1]);
            mass += pooled[b + 1];
            first += pooled[b + 1] * centre;
        }
        const double mean = first / mass;
        double second = 0.0, fourth = 0.0;
        for (std::size_t b = 0; b < histogram.bins(); ++b) {
            const double deviation = 0.5 * (histogram.edges[b] + histogram.edges[b + 1]) - mean;
            second += pooled[b + 1] * deviation * deviation;
            fourth += pooled[b + 1] * deviation * deviation * deviation * deviation;
        }
        second /= mass;
        fourth /= mass;
        return fourth / (second * second);  // 3 for a Gaussian
    };
    return jackknife(groups, kurtosis);  // one realization: sigma n/a, with jackknife's note
}

namespace {

struct TailData {
    std::vector<double> u;           // |z| / rms(z) at folded bin centres
    std::vector<std::size_t> bin;    // the bin b (and its mirror bins + 1 - b) of each point
    std::vector<double> log_sigma;   // standard error of ln Phi
};

struct ChiSquared {
    double chi2;
    LinearFit fit;
};

ChiSquared tail_chi2(const TailData& data, const std::vector<double>& log_density, double gamma) {
    std::vector<double> power(data.u.size());
    for (std::size_t i = 0; i < data.u.size(); ++i) power[i] = std::pow(data.u[i], gamma);
    // Eq. (6) at fixed gamma: ln Phi = a - c u^gamma is a straight line in u^gamma.
    const LinearFit fit = weighted_linear_fit(power, log_density, data.log_sigma);
    return {fit.chi2, fit};
}

// Eq. (6) on the tail points: gamma minimising chi2 over [gamma_min, gamma_max]
// (grid then golden section), c and chi2/dof at it, and the Delta chi2 = 1
// half-width from the curvature of chi2(gamma). A minimum at either end of
// the range is not a measurement: gamma and its width are then missing, with
// the bound named. `search` is the minimum found, for the caller's jackknife.
constexpr double gamma_min = 0.5, gamma_max = 8.0;  // brackets Gaussian (2) and Eq. (6) (3) widely
SearchMinimum best_gamma(const TailData& points, const std::vector<double>& log_phi) {
    return minimise([&](double gamma) { return tail_chi2(points, log_phi, gamma).chi2; }, gamma_min, gamma_max, 150);
}
TailFit fit_tail_points(const TailData& data, const std::vector<double>& log_density, SearchMinimum& search,
                        const std::string& remedy) {
    if (data.u.size() < 4)
        throw InsufficientData("only " + std::to_string(data.u.size()) +
                               " tail bins have a relative error below the limit; the tail fit needs 4 or more " +
                               remedy);
    TailFit result;
    search = best_gamma(data, log_density);
    const double gamma = search.argmin;
    const ChiSquared best = tail_chi2(data, log_density, gamma);
    result.c = -best.fit.slope;
    result.bins = data.u.size();
    result.chi2_per_dof = best.chi2 / static_cast<double>(data.u.size() - 3);  // a, c and gamma fitted
    result.z_lo = *std::min_element(data.u.begin(), data.u.end());
    result.z_hi = *std::max_element(data.u.begin(), data.u.end());
    if (search.at_bound) {
        // Not a measurement: gamma and both its widths are n/a, with the bound.
        result.gamma = Estimate::missing(search.bound_note());
        result.gamma_fit_sigma = std::numeric_limits<double>::quiet_NaN();
        result.gamma_fit_sigma_note = "gamma " + search.bound_note();
        return result;
    }
    const double h = 1e-3 * gamma;
    const double curvature = (tail_chi2(data, log_density, gamma + h).chi2 - 2.0 * best.chi2 +
                              tail_chi2(data, log_density, gamma - h).chi2) / (h * h);
    result.gamma_fit_sigma = curvature > 0.0 ? std::sqrt(2.0 / curvature) : std::numeric_limits<double>::quiet_NaN();
    if (!(curvature > 0.0)) result.gamma_fit_sigma_note = "chi2(gamma) is not curved upwards at its minimum";
    return result;
}

}  // namespace

TailFit fit_tail(const VelocityHistogram& histogram, const TailRule& rule) {
    const std::size_t bins = histogram.bins();
    const std::size_t width = bins + 2;
    const std::size_t realizations = histogram.realizations;
    if (realizations < 2) throw InsufficientData("the tail fit weighs bins by realization scatter: needs R >= 2");
    const auto pooled = histogram.pooled();
    // rms of v over the resolved bins, to express the tail in units of the width.
    double mass = 0.0, second = 0.0;
    for (std::size_t b = 0; b < bins; ++b) {
        const double centre = 0.5 * (histogram.edges[b] + histogram.edges[b + 1]);
        mass += pooled[b + 1];
        second += pooled[b + 1] * centre * centre;
    }
    const double rms = std::sqrt(second / mass);
    // The folded count of bin b and its mirror in each realization, and its
    // mean with the standard error from their scatter, over the realizations
    // kept (every r % groups != left_out; all of them with none left out).
    const std::size_t groups = std::min(realizations, max_jackknife_groups);
    auto folded_mean = [&](std::size_t b, std::optional<std::size_t> left_out) {
        std::vector<double> per_realization;
        per_realization.reserve(realizations);
        for (std::size_t r = 0; r < realizations; ++r)
            if (!left_out || r % groups != *left_out)
                per_realization.push_back(histogram.counts[r * width + b + 1] + histogram.counts[r * width + bins - b]);
        return mean_and_standard_error(per_realization);
    };
    TailData data;
    std::vector<double> log_density;
    for (std::size_t b = 0; b < bins / 2; ++b) {
        const double centre = 0.5 * (histogram.edges[b] + histogram.edges[b + 1]);
        const double u = std::abs(centre) / rms;
        if (u < rule.tail_start) continue;
        const Estimate mean = folded_mean(b, std::nullopt);
        if (!(mean.value > 0.0) || !(mean.sigma > 0.0) || mean.sigma / mean.value > rule.max_relative_error) continue;
        const double width_b = histogram.edges[b + 1] - histogram.edges[b];
        data.u.push_back(u);
        data.bin.push_back(b);
        data.log_sigma.push_back(mean.sigma / mean.value);
        // Pooled over realizations (R times the mean), the normalisation the jackknife uses too.
        log_density.push_back(std::log(mean.value * static_cast<double>(realizations) / width_b));
    }
    SearchMinimum search;
    TailFit result = fit_tail_points(data, log_density, search,
                                     "(more realizations or particles)");
    for (double c : pooled) result.total_mass += c;
    if (search.at_bound) return result;
    const double gamma = search.argmin;
    // Group jackknife: each replica refits the same bins with its own density
    // and weights, both from the realizations it keeps, as the decay fit's
    // replicas do: with the full sample's weights in every replica sigma would
    // leave out the scatter of the weights themselves. The one-sigma coverage
    // of gamma on synthetic tails is 0.67, 0.65 and 0.72 at R = 3, 4 and 8
    // (Student's t: 0.58, 0.61, 0.65), against 0.32, 0.36 and 0.57 with the
    // full sample's weights (test AnalysisTail.JackknifeCoverageWithFourRealizations).
    if (realizations < 3) {
        result.gamma = {gamma, std::numeric_limits<double>::quiet_NaN(),
                        "two realizations: each jackknife replica keeps one, which has no scatter to weigh the bins "
                        "by (the Delta chi2 = 1 width is tail_gamma_fit_sigma); run -R 3 or more"};
        return result;
    }
    result.gamma = bounded_jackknife(groups, [&](std::optional<std::size_t> left_out) {
        if (!left_out) return search;
        TailData replica = data;
        std::vector<double> log_phi(data.u.size());
        for (std::size_t i = 0; i < data.u.size(); ++i) {
            const std::size_t b = data.bin[i];
            const Estimate mean = folded_mean(b, left_out);
            // A bin the replica empties, or whose kept counts are all equal, keeps
            // the full sample's value or weight (only possible at the tail's far
            // end, where weights are smallest).
            log_phi[i] = mean.value > 0.0 ? std::log(mean.value * static_cast<double>(realizations) /
                                                     (histogram.edges[b + 1] - histogram.edges[b]))
                                          : log_density[i];
            if (mean.value > 0.0 && mean.sigma > 0.0) replica.log_sigma[i] = mean.sigma / mean.value;
        }
        return best_gamma(replica, log_phi);
    });
    return result;
}

TailFit fit_pooled_tail(const std::vector<double>& edges, const std::vector<double>& counts, const TailRule& rule) {
    const std::size_t bins = counts.size();
    if (edges.size() != bins + 1)
        throw std::invalid_argument("fit_pooled_tail: " + std::to_string(edges.size()) + " edges for " +
                                    std::to_string(bins) + " bins");
    double mass = 0.0, second = 0.0;  // the rms over the bins, as fit_tail's
    for (std::size_t b = 0; b < bins; ++b) {
        const double centre = 0.5 * (edges[b] + edges[b + 1]);
        mass += counts[b];
        second += counts[b] * centre * centre;
    }
    if (!(mass > 0.0)) throw InsufficientData("an empty histogram has no tail");
    const double rms = std::sqrt(second / mass);
    TailData data;
    std::vector<double> log_density;
    for (std::size_t b = 0; b < bins / 2; ++b) {
        const double centre = 0.5 * (edges[b] + edges[b + 1]);
        const double u = std::abs(centre) / rms;
        const double folded = counts[b] + counts[bins - 1 - b];  // bin b and its mirror
        // Poisson: the standard error of ln n is 1 / sqrt(n).
        if (u < rule.tail_start || !(folded > 0.0) || 1.0 / std::sqrt(folded) > rule.max_relative_error) continue;
        data.u.push_back(u);
        data.bin.push_back(b);
        data.log_sigma.push_back(1.0 / std::sqrt(folded));
        log_density.push_back(std::log(folded / (edges[b + 1] - edges[b])));
    }
    SearchMinimum search;
    TailFit result = fit_tail_points(data, log_density, search, "(more particles or realizations)");
    result.total_mass = mass;
    if (!search.at_bound)
        result.gamma = {search.argmin, result.gamma_fit_sigma,
                        "Delta chi2 = 1 width with Poisson errors of the pooled counts: particles taken as "
                        "independent, so it understates the error from correlated motion"};
    return result;
}

}  // namespace shockgas::analysis
