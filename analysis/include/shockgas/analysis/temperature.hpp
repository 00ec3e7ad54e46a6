// SPDX-License-Identifier: GPL-3.0-or-later
// Estimators on the temperature history T(t): the power-law decay exponent
// of the sticky-gas regime (Fig. 1, P1) with its automatic window and window
// scan, and the crossover times t_dissip and t_stick (Eq. 3, P3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/model/records.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {

// T(t) of every realization at common sample times, restricted to the times
// t > 0 (the stored start, t = 0, has no place on log-log axes) that every
// realization reached with T > 0 (a realization that collapsed or was
// interrupted would otherwise bias the mean at late times).
struct TemperatureHistory {
    std::vector<double> time;                // K
    std::size_t realizations = 0;            // R
    std::vector<double> temperature;         // R x K, row-major
    double at(std::size_t realization, std::size_t k) const { return temperature[realization * time.size() + k]; }
    // Mean over realizations, leaving out one realization when asked (jackknife).
    double mean(std::size_t k, std::optional<std::size_t> left_out = std::nullopt) const;
    // Standard error of the mean at time k: sample std over realizations / sqrt(R), leaving out one
    // realization when asked (a jackknife replica's own weights). NaN with fewer than 2 values.
    double standard_error(std::size_t k, std::optional<std::size_t> left_out = std::nullopt) const;
    // The means and their standard errors at the samples `indices`, from the realizations an estimate
    // uses (all, or all but left_out): a weighted fit's points and sigmas, from one pass over each
    // sample's values (not one for the points and another for the sigmas' fallback). mean[j] is mean(indices[j], left_out) bit for bit. Where a standard error
    // is not above rounding level relative to the mean (identical realizations, or one left), equal
    // relative weights take its place: fallback_fraction x the mean.
    struct FitPoints {
        std::vector<double> mean, sigma;
    };
    FitPoints fit_points(const std::vector<std::size_t>& indices, std::optional<std::size_t> left_out,
                         double fallback_fraction) const;

    static TemperatureHistory from(const TimeSeries& series);
    static TemperatureHistory from(const EnsembleResult& result);
    static TemperatureHistory from(const std::vector<double>& time, std::int64_t realizations,
                                   const std::vector<double>& temperature);
};

// The time series of a shockgas-sim output (read_timeseries) and its
// TemperatureHistory, with the checks every analysis of T(t) needs: the
// /timeseries tables are realizations x times (h5::Error naming the dataset
// and the file otherwise), and the file holds at least one realization and a
// sample time t > 0 that every realization reached (InsufficientData
// otherwise, whose message the caller completes with the file's name).
struct TemperatureRun {
    TimeSeries series;
    TemperatureHistory history;
};
TemperatureRun read_temperature_run(const std::string& path);

// The automatic post-crossover window (see analysis/README.md, "Window rule"):
//   t_lo = start_factor * max(scaling_onset, eps^(-3/2)),  eps = (1 - r)/2, the sticky crossover of
//          Eq. (3), but no earlier than the sticky gas's own approach to scaling (t ~ 100);
//   t_hi = min(last common sample time, end_factor * N^(3/2), delta^(-3) when delta > 0),
// the finite-ring crossover of Eq. (3) and the threshold's validity bound t_valid ~ delta^(-3).
struct WindowRule {
    double start_factor = 10.0;  // "t >> t_stick" of Eq. (3) read as one decade past eps^(-3/2)
    double scaling_onset = 10.0; // ... and never before t = 100: the sticky gas's own approach to scaling
    double end_factor = 0.01;    // stays two decades below N^(3/2), where a few dozen clusters remain
};
struct DecayWindow {
    double t_lo = 0.0;
    double t_hi = 0.0;
};
// The bounds of the rule, whether or not they leave a window.
DecayWindow decay_window_bounds(double restitution, double velocity_threshold, double particles, double last_time,
                                const WindowRule& rule = {});
// The same, throwing InsufficientData that explains an empty window.
// run_status: the run's status attribute; when it is "collapsed" or
// "interrupted", last_time is its last sample (a collapse lies after it), and
// an empty window says so.
DecayWindow automatic_decay_window(double restitution, double velocity_threshold, double particles,
                                   double last_time, const WindowRule& rule = {},
                                   const std::string& run_status = "complete");

// Empty when the fit window [t_lo, t_hi] spans a decade or more; else one line saying it spans
// less (so its exponent has no window systematic and may still carry the crossover) and what
// gives a decade: for the automatic window (manual false) the run that makes the rule's t_hi reach
// 10 t_lo (t_max, N, delta as the bounds require); for a chosen one, --t-hi (or a longer run).
// last_time: the last sample time every realization reached.
std::string short_window_note(double t_lo, double t_hi, bool manual, double last_time, double particles,
                              double velocity_threshold, const WindowRule& rule = {});

// The decay exponent alpha of T ~ t^(-alpha) over a window.
struct DecayFit {
    double t_lo = 0.0, t_hi = 0.0;   // the window
    std::size_t points = 0;          // sample times inside it
    double exponent = 0.0;           // alpha = -d ln T / d ln t from the weighted fit of ln <T> vs ln t
    double exponent_sigma = 0.0;     // jackknife over realizations; NaN for one realization
    std::string exponent_sigma_note; // why exponent_sigma is NaN
    double fit_sigma = 0.0;          // from the weights alone (ignores time correlations; for comparison)
    double chi2_per_dof = 0.0;       // with sigma_k = standard error of ln <T(t_k)>
    std::string fit_note;            // why fit_sigma and chi2_per_dof are NaN (one realization: no weights)
    double prefactor = 0.0;          // T t^alpha
};

// Fits ln <T>(t_k) = ln C - alpha ln t_k over t_lo <= t_k <= t_hi, weights
// 1/sigma_k^2 with sigma_k = SE(T_k)/<T_k>; alpha's sigma is the jackknife
// over realizations (each leave-one-out fit with its own weights), NaN for
// R = 1 (nothing to leave out). With R = 1 the weights are undefined too: the
// fit uses equal weights, and fit_sigma and chi2_per_dof are NaN (fit_note). Throws InsufficientData for fewer than 3
// points in the window.
DecayFit fit_temperature_decay(const TemperatureHistory& history, double t_lo, double t_hi);

// The exponent in windows of fixed width (width_decades of ln t / ln 10),
// moved by step_decades from the first sample time to the last; windows with
// fewer than 3 samples are left out. Needs a finite width > 0 and a finite
// step >= min_scan_step_decades (std::invalid_argument otherwise; the CLI
// refuses such values with a message first).
std::vector<DecayFit> scan_decay_windows(const TemperatureHistory& history, double width_decades,
                                         double step_decades);
// The smallest scan step. Windows moved by less than the spacing of the
// samples (1/K decade for K samples per decade; shockgas-sim's default K is 10)
// hold the same samples and repeat the same fit; a step of 10^-3 decade only
// resolves grids of 1000 samples per decade and already makes 10^3 fits per
// decade (each with its jackknife), while a step of 10^-9 would make 10^9.
constexpr double min_scan_step_decades = 1e-3;

// Systematic error of the window choice: half the spread (max - min)/2 of the
// exponents of the one-decade scan windows (step 0.1 decade) lying inside
// [t_lo, t_hi]. Corrections to scaling make the local exponent wander; this
// says by how much. Missing (NaN with the reason) when fewer than two such
// windows lie inside [t_lo, t_hi], e.g. a fit window shorter than 1.1 decades.
Measured window_systematic(const TemperatureHistory& history, double t_lo, double t_hi);

// --- crossovers (Eq. 3) ---
// t_dissip: the time at which <T> has fallen to half its initial value,
//   <T>(t_dissip) = T0 / 2 (log-log interpolation between samples);
// Haff fit: sqrt(T0 / <T>) = 1 + a t (Eq. 2 rearranged, linear in t), fitted
//   on the samples with <T> >= haff_floor * T0 (the homogeneous regime);
// t_stick: the first time after t_dissip at which <T> exceeds the fitted
//   Haff curve by the factor stick_ratio: clusters have become opaque and the
//   decay has slowed from t^-2 towards t^(-2/3); T(t_stick) = <T>(t_stick).
// Any fixed ratio gives t_stick ~ eps^(-3/2) if the crossover has a scaling
// form; the ratio only sets the prefactor.
struct CrossoverRule {
    double haff_floor = 0.25;   // Haff fit on T >= T0/4: past t_dissip, still homogeneous
    double stick_ratio = 2.0;   // departure from Haff by a factor 2 marks t_stick
    // Set: the Haff rate a used instead of the fit (derived_haff_rate, for
    // shockgas-analyze --haff-constant derived). The fit's window T >= T0/4
    // ends at t = 18 and 32 for eps = 0.05 and 0.025, inside the lattice
    // start's transient, where the fitted a exceeds the derived one by 1.5%
    // and 1.0%; that steepens the t_stick exponent by 0.016 +- 0.002 over
    // eps = 0.05 ... 0.00625 (analysis/README.md).
    std::optional<double> haff_rate;
};
struct Crossovers {
    double initial_temperature = 0.0;  // T0 = <T>(first sample)
    Estimate t_dissip;
    Estimate haff_rate;         // a of sqrt(T0/T) = 1 + a t
    Estimate t_stick;
    Estimate temperature_at_stick;
};
// Sigmas by the jackknife over realizations, each replica with its own Haff-fit
// weights; with one realization the values stand and the sigmas are NaN with
// the reason (equal relative weights in the Haff fit).
Crossovers find_crossovers(const TemperatureHistory& history, const CrossoverRule& rule = {});

// The t_stick that `rule` reads on the noise-free reference T_ref(t): Haff's
// law T0 / (1 + A eps (1 - eps) sqrt(T0) t)^2 (Eq. (2), with its derived
// A = 6 sqrt(3)/5, E3) until, after t = 1/(2a), it falls to the sticky gas's
// exact T = kappa t^(-2/3) (Eq. (3)), and kappa t^(-2/3) after: a crossover that scales
// exactly as eps^(-3/2) when eps -> 0. At finite eps the "1 +" and the
// (1 - eps) of Haff's law tilt what the rule reads: with the default rule the
// reference gives eps^(-1.52) over eps = 0.05 ... 0.00625, so a measured
// exponent is compared with the reference's at the same eps, not with -3/2
// alone. On the reference the Haff fit returns A eps (1 - eps) sqrt(T0)
// exactly, so t_stick solves kappa t^(-2/3) (1 + a t)^2 / T0 = stick_ratio on
// the rising branch t > 1/(2a) (GSL's Brent solver, in ln t). Missing, with
// the reason, where the Haff fit's window would reach the sticky branch (eps
// too large for a Haff regime at this floor) or no such t exists.
Measured reference_stick_time(double inelasticity, const CrossoverRule& rule = {});

// A of Haff's law for the Gaussian start of variance T0 (Eq. (2) with A =
// <|g|^3> / (2 T0^(3/2)), docs/haff-and-collapse.md): g = v1 - v2 is normal
// with variance 2 T0, so <|g|^3> = 8 T0^(3/2) / sqrt(pi) and A = 4 / sqrt(pi),
// 8.6% above the uniform start's 6 sqrt(3)/5.
inline constexpr double haff_constant_gaussian = 2.2567583341910251;  // 4 / sqrt(pi)

// Haff's rate a = A eps (1 - eps) sqrt(T0) of sqrt(T0/T) = 1 + a t, with the
// derived A of the start's velocity law, T0 = 1/3 for both: 6 sqrt(3)/5 for
// the uniform start (Eq. (2), E3), 4/sqrt(pi) for the Gaussian one.
double derived_haff_rate(double inelasticity, VelocityLaw law = VelocityLaw::uniform);

}  // namespace shockgas::analysis
