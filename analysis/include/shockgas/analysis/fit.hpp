// SPDX-License-Identifier: GPL-3.0-or-later
// The one fitting core of the analysis library. Every power law, every tail
// and every segment slope is fitted by weighted_linear_fit (GSL's
// gsl_fit_wlinear); error bars of the fitted physics numbers come from the
// jackknife over independent realizations, which also captures the
// correlations between the points of one realization that the fit ignores.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shockgas::analysis {

// Thrown when the data cannot support an estimate (too few points, a window
// outside the data, a realization count too small for the jackknife). The
// message names what is missing.
struct InsufficientData : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// How the fit's covariance is obtained.
enum class ErrorModel {
    // sigma are true standard deviations: weights 1/sigma^2, covariance from
    // the weights alone (gsl_fit_wlinear). chi2/dof then tests the model.
    known_sigmas,
    // sigma are only relative: the covariance is scaled by chi2/dof, as
    // gsl_fit_linear does. For data without an error model (segment slopes).
    scale_by_residuals,
};

// A number the data may not determine. When they do not, value is NaN and
// note says why; it is printed "n/a (<note>)" and stored as NaN beside a
// <name>_note attribute (results.hpp), never as 0, which would read as a
// measurement.
struct Measured {
    double value = std::numeric_limits<double>::quiet_NaN();
    std::string note;
    Measured() = default;
    Measured(double measured, std::string why) : value(measured), note(std::move(why)) {}
    bool known() const { return !std::isnan(value); }
    static Measured missing(std::string why) { return {std::numeric_limits<double>::quiet_NaN(), std::move(why)}; }
};

struct LinearFit {
    double intercept = 0.0;
    double slope = 0.0;
    double intercept_variance = 0.0;
    double slope_variance = 0.0;
    double covariance = 0.0;  // cov(intercept, slope)
    double chi2 = 0.0;        // sum of (y - intercept - slope x)^2 / sigma^2
    std::size_t points = 0;
    std::size_t parameters = 2;  // fitted parameters: 2, or 1 when the slope is fixed

    double slope_sigma() const;
    double intercept_sigma() const;
    std::size_t degrees_of_freedom() const { return points > parameters ? points - parameters : 0; }
    // chi2 / (points - parameters). A fit with no degree of freedom left (two
    // points and a line) passes through every point, and its chi2 = 0 says
    // nothing: chi2_per_dof() then throws InsufficientData ("need at least 3
    // points for chi2"), reduced_chi2() returns it as missing with that reason.
    double chi2_per_dof() const;
    Measured reduced_chi2() const;
    // Information criteria for comparing models fitted to the same points with
    // the same known sigmas (-2 ln L = chi2 + a constant common to all models):
    // AIC = chi2 + 2k (Akaike 1974), BIC = chi2 + k ln n (Schwarz 1978), k the
    // fitted parameters, n the points. The model with the lower value is
    // preferred; a difference of 2 is weak evidence, above 6 strong, above 10
    // decisive (Kass & Raftery, J. Am. Stat. Assoc. 90, 773 (1995), for BIC).
    double aic() const;
    double bic() const;
};

// Weighted least squares for y = intercept + slope x: minimises
// chi2 = sum_i (y_i - intercept - slope x_i)^2 / sigma_i^2 (gsl_fit_wlinear).
// Throws InsufficientData for fewer than two points, a non-positive sigma,
// x values that are all equal (no slope is defined; gsl_fit_wlinear does not
// fail but returns nan and inf), and, with ErrorModel::scale_by_residuals,
// fewer than 3 points (the residual scatter that sets the error bars needs a
// degree of freedom).
LinearFit weighted_linear_fit(std::span<const double> x, std::span<const double> y, std::span<const double> sigma,
                              ErrorModel model = ErrorModel::known_sigmas);

// The same least squares with the slope fixed (a one-parameter model):
// intercept = sum w (y - slope x) / sum w, variance 1 / sum w, w = 1/sigma^2;
// chi2 as above, parameters = 1, slope_variance = 0. Throws InsufficientData
// for no points or a non-positive sigma.
LinearFit fixed_slope_fit(std::span<const double> x, std::span<const double> y, std::span<const double> sigma,
                          double slope);

// Power law y = prefactor x^exponent, fitted as ln y = ln prefactor +
// exponent ln x with sigma_{ln y} = sigma_y / y (first-order error
// propagation). Returns the linear fit in log-log variables: slope is the
// exponent, intercept is ln prefactor.
LinearFit fit_power_law(std::span<const double> x, std::span<const double> y, std::span<const double> y_sigma);

// A number with its standard error. Not measured until set: NaN, not 0. When
// value or sigma cannot be estimated it is NaN and note says why (for sigma
// alone: e.g. "one realization: the jackknife has nothing to leave out").
struct Estimate {
    double value = std::numeric_limits<double>::quiet_NaN();
    double sigma = std::numeric_limits<double>::quiet_NaN();
    std::string note;
    Estimate() = default;
    Estimate(double measured, double error, std::string why = "")
        : value(measured), sigma(error), note(std::move(why)) {}
    static Estimate missing(std::string why) {
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(), std::move(why)};
    }
};

// Delete-one jackknife over `samples` independent samples (realizations):
// value = theta(all), sigma^2 = (n - 1)/n sum_i (theta_(i) - mean_i theta_(i))^2,
// where theta_(i) is the estimator with sample i left out (estimator(i)) and
// estimator(nullopt) uses every sample. With n = 1 the value is measured and
// sigma is NaN with the reason in note (nothing to leave out); n = 0 throws
// InsufficientData.
Estimate jackknife(std::size_t samples, const std::function<double(std::optional<std::size_t>)>& estimator);

// Weighted least squares for a model linear in its parameters,
// y_i = sum_j parameter_j basis_j(x_i) (gsl_multifit_wlinear), sigma as in
// weighted_linear_fit with ErrorModel::known_sigmas. design is points x
// parameters, row-major.
struct MultilinearFit {
    std::vector<double> parameters;
    std::vector<double> covariance;  // parameters x parameters, row-major
    double chi2 = 0.0;
    std::size_t points = 0;
};
MultilinearFit weighted_multilinear_fit(std::span<const double> design, std::size_t parameters,
                                        std::span<const double> y, std::span<const double> sigma);

// The argmin of a bounded one-parameter search, and whether it is a
// measurement. A minimum found at an end of [lo, hi] is not: f still falls
// beyond the range, so the argmin is the bound the search was given, not a
// property of the data (reported as a value, it would read gamma = 0.500 +-
// 0.000, 0.5 being the lower end of the tail fit's range). Such a result is reported n/a
// ("at the search bound 0.5 of [0.5, 8]"), never as the bound.
struct SearchMinimum {
    double argmin = std::numeric_limits<double>::quiet_NaN();
    double lo = 0.0, hi = 0.0;  // the search range
    bool at_bound = false;      // argmin is lo or hi, to the search's tolerance
    // "at the search bound 0.5 of [0.5, 8]: chi2 still falls beyond it"
    std::string bound_note() const;
    // argmin, or missing with bound_note() when at a bound.
    Measured measured() const;
};

// Golden-section minimisation of a one-parameter f on [lo, hi] after a grid
// search (the nonlinear parameter of the fits that are linear in the rest).
// Every bounded search of the analysis goes through here, and so does the
// test of whether its result sits on a bound.
template <class Function>
SearchMinimum minimise(Function f, double lo, double hi, std::size_t grid = 60) {
    double best = lo, best_value = std::numeric_limits<double>::infinity();
    const double step = (hi - lo) / static_cast<double>(grid);
    for (std::size_t i = 0; i <= grid; ++i) {
        const double x = lo + step * static_cast<double>(i);
        const double value = f(x);
        if (value < best_value) {
            best_value = value;
            best = x;
        }
    }
    double a = std::max(lo, best - step), b = std::min(hi, best + step);
    const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
    const double tolerance = 1e-7 * (1.0 + std::abs(best));
    double c = b - golden * (b - a), d = a + golden * (b - a);
    double fc = f(c), fd = f(d);
    for (int iteration = 0; iteration < 60 && b - a > tolerance; ++iteration) {
        if (fc < fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - golden * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + golden * (b - a);
            fd = f(d);
        }
    }
    SearchMinimum result;
    result.argmin = (a + b) / 2.0;
    result.lo = lo;
    result.hi = hi;
    // The bracket never leaves [lo, hi]: a minimum beyond an end shrinks it onto
    // that end, so the argmin lies within the final bracket width of it. Ten
    // times that width separates it from an interior minimum.
    result.at_bound = result.argmin - lo <= 10.0 * tolerance || hi - result.argmin <= 10.0 * tolerance;
    return result;
}

// The jackknife of an estimate found by a bounded search (minimise). value is
// missing, with the bound named, when the search over every sample ends at a
// bound; sigma is missing when a leave-one-out search does (the spread of
// values clipped to the range is not an error bar) or when there is one sample
// only (nothing to leave out). Otherwise as jackknife.
Estimate bounded_jackknife(std::size_t samples,
                           const std::function<SearchMinimum(std::optional<std::size_t>)>& estimator);

// Mean and standard error of the mean (sample standard deviation / sqrt(n));
// for one value the standard error is missing (NaN with a note).
Estimate mean_and_standard_error(std::span<const double> values);

}  // namespace shockgas::analysis
