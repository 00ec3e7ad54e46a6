// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit.h>

namespace shockgas::analysis {

double LinearFit::slope_sigma() const { return std::sqrt(slope_variance); }
double LinearFit::intercept_sigma() const { return std::sqrt(intercept_variance); }
Measured LinearFit::reduced_chi2() const {
    if (degrees_of_freedom() == 0)
        return Measured::missing("need at least " + std::to_string(parameters + 1) + " points for chi2, got " +
                                 std::to_string(points));
    return {chi2 / static_cast<double>(degrees_of_freedom()), ""};
}
double LinearFit::chi2_per_dof() const {
    const Measured reduced = reduced_chi2();
    if (!reduced.known()) throw InsufficientData(reduced.note);
    return reduced.value;
}
double LinearFit::aic() const { return chi2 + 2.0 * static_cast<double>(parameters); }
double LinearFit::bic() const {
    return chi2 + static_cast<double>(parameters) * std::log(static_cast<double>(points));
}

namespace {

// 1/sigma_i^2, after checking that every point is usable.
std::vector<double> fit_weights(std::span<const double> x, std::span<const double> y, std::span<const double> sigma) {
    std::vector<double> weight(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!(sigma[i] > 0.0) || !std::isfinite(sigma[i]) || !std::isfinite(x[i]) || !std::isfinite(y[i]))
            throw InsufficientData("fit point " + std::to_string(i) + " has a non-finite value or sigma <= 0");
        weight[i] = 1.0 / (sigma[i] * sigma[i]);  // gsl_fit_wlinear takes w_i = 1/sigma_i^2
    }
    return weight;
}

}  // namespace

LinearFit weighted_linear_fit(std::span<const double> x, std::span<const double> y, std::span<const double> sigma,
                              ErrorModel model) {
    if (x.size() != y.size() || x.size() != sigma.size())
        throw std::invalid_argument("weighted_linear_fit: x, y and sigma differ in length");
    if (x.size() < 2)
        throw InsufficientData("a straight-line fit needs at least 2 points, got " + std::to_string(x.size()));
    const std::vector<double> weight = fit_weights(x, y, sigma);
    // Equal x leave the slope undefined: the normal equations are singular,
    // and gsl_fit_wlinear divides by their zero determinant without an error.
    if (std::all_of(x.begin(), x.end(), [&](double value) { return value == x.front(); }))
        throw InsufficientData(fmt::format("all x values are equal ({:g}): a straight line through {} points at "
                                           "one x has no slope",
                                           x.front(), x.size()));
    if (model == ErrorModel::scale_by_residuals && x.size() < 3)
        throw InsufficientData("need at least 3 points for chi2: the error bars come from the scatter about the "
                               "line, and a line through 2 points has none");
    LinearFit fit;
    fit.points = x.size();
    const int status = gsl_fit_wlinear(x.data(), 1, weight.data(), 1, y.data(), 1, x.size(), &fit.intercept,
                                       &fit.slope, &fit.intercept_variance, &fit.covariance, &fit.slope_variance,
                                       &fit.chi2);
    if (status != GSL_SUCCESS)
        throw InsufficientData(std::string("gsl_fit_wlinear failed: ") + gsl_strerror(status) +
                               " (are all x equal?)");
    if (model == ErrorModel::scale_by_residuals) {
        // Unknown absolute errors: estimate them from the scatter about the line.
        const double residual_variance = fit.chi2 / static_cast<double>(fit.points - 2);
        fit.intercept_variance *= residual_variance;
        fit.slope_variance *= residual_variance;
        fit.covariance *= residual_variance;
    }
    return fit;
}

MultilinearFit weighted_multilinear_fit(std::span<const double> design, std::size_t parameters,
                                        std::span<const double> y, std::span<const double> sigma) {
    const std::size_t points = y.size();
    if (sigma.size() != points || design.size() != points * parameters)
        throw std::invalid_argument("weighted_multilinear_fit: design, y and sigma differ in size");
    if (points <= parameters)
        throw InsufficientData("a fit of " + std::to_string(parameters) + " parameters needs more points, got " +
                               std::to_string(points));
    gsl_matrix* x = gsl_matrix_alloc(points, parameters);
    gsl_vector* w = gsl_vector_alloc(points);
    gsl_vector* yv = gsl_vector_alloc(points);
    gsl_vector* c = gsl_vector_alloc(parameters);
    gsl_matrix* cov = gsl_matrix_alloc(parameters, parameters);
    gsl_multifit_linear_workspace* work = gsl_multifit_linear_alloc(points, parameters);
    MultilinearFit fit;
    fit.points = points;
    bool valid = true;
    for (std::size_t i = 0; i < points; ++i) {
        valid = valid && sigma[i] > 0.0 && std::isfinite(sigma[i]) && std::isfinite(y[i]);
        gsl_vector_set(w, i, 1.0 / (sigma[i] * sigma[i]));
        gsl_vector_set(yv, i, y[i]);
        for (std::size_t j = 0; j < parameters; ++j) gsl_matrix_set(x, i, j, design[i * parameters + j]);
    }
    const int status = valid ? gsl_multifit_wlinear(x, w, yv, c, cov, &fit.chi2, work) : GSL_EINVAL;
    if (status == GSL_SUCCESS) {
        for (std::size_t j = 0; j < parameters; ++j) fit.parameters.push_back(gsl_vector_get(c, j));
        for (std::size_t j = 0; j < parameters; ++j)
            for (std::size_t k = 0; k < parameters; ++k) fit.covariance.push_back(gsl_matrix_get(cov, j, k));
    }
    gsl_multifit_linear_free(work);
    gsl_matrix_free(cov);
    gsl_vector_free(c);
    gsl_vector_free(yv);
    gsl_vector_free(w);
    gsl_matrix_free(x);
    if (status != GSL_SUCCESS)
        throw InsufficientData(std::string("gsl_multifit_wlinear failed: ") + gsl_strerror(status) +
                               " (non-finite point or sigma <= 0?)");
    return fit;
}

LinearFit fixed_slope_fit(std::span<const double> x, std::span<const double> y, std::span<const double> sigma,
                          double slope) {
    if (x.size() != y.size() || x.size() != sigma.size())
        throw std::invalid_argument("fixed_slope_fit: x, y and sigma differ in length");
    if (x.empty()) throw InsufficientData("a fixed-slope fit needs at least 1 point");
    const std::vector<double> weight = fit_weights(x, y, sigma);
    // Minimising sum w (y - a - slope x)^2 over a alone: the weighted mean of
    // the residuals y - slope x.
    double weight_sum = 0.0, weighted_sum = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        weight_sum += weight[i];
        weighted_sum += weight[i] * (y[i] - slope * x[i]);
    }
    LinearFit fit;
    fit.points = x.size();
    fit.parameters = 1;
    fit.slope = slope;
    fit.intercept = weighted_sum / weight_sum;
    fit.intercept_variance = 1.0 / weight_sum;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double residual = y[i] - fit.intercept - slope * x[i];
        fit.chi2 += weight[i] * residual * residual;
    }
    return fit;
}

LinearFit fit_power_law(std::span<const double> x, std::span<const double> y, std::span<const double> y_sigma) {
    if (x.size() != y.size() || x.size() != y_sigma.size())
        throw std::invalid_argument("fit_power_law: x, y and sigma differ in length");
    std::vector<double> log_x(x.size()), log_y(x.size()), log_sigma(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!(x[i] > 0.0) || !(y[i] > 0.0))
            throw InsufficientData("a power-law fit needs positive x and y; point " + std::to_string(i) + " is not");
        log_x[i] = std::log(x[i]);
        log_y[i] = std::log(y[i]);
        log_sigma[i] = y_sigma[i] / y[i];  // d ln y = dy / y
    }
    return weighted_linear_fit(log_x, log_y, log_sigma);
}

Estimate jackknife(std::size_t samples, const std::function<double(std::optional<std::size_t>)>& estimator) {
    if (samples == 0) throw InsufficientData("the jackknife needs at least 1 realization, got none");
    Estimate result;
    result.value = estimator(std::nullopt);
    // One realization: the estimate is measured, its error is not. The value stands with sigma n/a
    // and the reason, so that every command (crossover, decay, the kurtosis, beta) treats a
    // one-realization run alike instead of each checking for it before calling here.
    if (samples < 2) {
        result.note = "one realization: the jackknife has nothing to leave out; run -R 2 or more";
        return result;
    }
    std::vector<double> left_out(samples);
    double mean = 0.0;
    for (std::size_t i = 0; i < samples; ++i) {
        left_out[i] = estimator(i);
        mean += left_out[i];
    }
    mean /= static_cast<double>(samples);
    double sum_squares = 0.0;
    for (double value : left_out) sum_squares += (value - mean) * (value - mean);
    const double n = static_cast<double>(samples);
    result.sigma = std::sqrt((n - 1.0) / n * sum_squares);
    return result;
}

std::string SearchMinimum::bound_note() const {
    const double bound = hi - argmin < argmin - lo ? hi : lo;
    return fmt::format("at the search bound {:g} of [{:g}, {:g}]: the minimum lies beyond the range", bound, lo, hi);
}

Measured SearchMinimum::measured() const { return at_bound ? Measured::missing(bound_note()) : Measured{argmin, ""}; }

Estimate bounded_jackknife(std::size_t samples,
                           const std::function<SearchMinimum(std::optional<std::size_t>)>& estimator) {
    const SearchMinimum full = estimator(std::nullopt);
    if (full.at_bound) return Estimate::missing(full.bound_note());
    // One realization: the minimum is measured, its sigma is n/a (jackknife's note).
    std::optional<std::string> replica_at_bound;
    Estimate result = jackknife(samples, [&](std::optional<std::size_t> left_out) {
        if (!left_out) return full.argmin;
        const SearchMinimum replica = estimator(left_out);
        if (replica.at_bound && !replica_at_bound)
            replica_at_bound = fmt::format("the jackknife replica without sample {} is {}", *left_out,
                                           replica.bound_note());
        return replica.argmin;
    });
    if (replica_at_bound) {
        result.sigma = std::numeric_limits<double>::quiet_NaN();
        result.note = *replica_at_bound;
    }
    return result;
}

Estimate mean_and_standard_error(std::span<const double> values) {
    if (values.empty()) throw InsufficientData("mean of an empty set");
    double mean = 0.0;
    for (double v : values) mean += v;
    const double n = static_cast<double>(values.size());
    mean /= n;
    if (values.size() < 2)
        return {mean, std::numeric_limits<double>::quiet_NaN(), "one value: no scatter to estimate an error from"};
    double sum_squares = 0.0;
    for (double v : values) sum_squares += (v - mean) * (v - mean);
    return {mean, std::sqrt(sum_squares / (n - 1.0) / n)};
}

}  // namespace shockgas::analysis
