// SPDX-License-Identifier: GPL-3.0-or-later
// The late decay of the disk and sphere gas (shockgas-spheres output), after
// Haff's homogeneous cooling. Ben-Naim, Chen, Doolen & Redner (PRL 83, 4069
// (1999), closing paragraph) predict from the inviscid Burgers equation, for
// 2 <= d <= 4, with tau = omega0 t counted in initial collision times and
// eps = (1 - r)/2:
//   T ~ 1 (tau << 1/eps), eps^-2 tau^-2 (Haff), tau^(-d/2) for
//   eps^(-4/(4-d)) << tau << N^(2/d), 1/N after;
// ballistic aggregation would give T ~ tau^(-2d/(d+2)) instead. This measures
// the late exponent theta of T ~ t^-theta between the predicted crossover and
// the finite-size time, where Haff's law meets it, and how the thermal
// velocity compares with the coarse-grained flow (Nie, Ben-Naim & Chen, PRL
// 89, 204301 (2002): Delta v / v ~ t^(-1/4) in 2D).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/analysis/results.hpp"

namespace shockgas::spheres {
struct SphereOutput;
}

namespace shockgas::analysis {

// The fit window in units of the predicted times: from start x t_pred, t_pred
// = eps^(-4/(4-d)) / omega0 (the predicted crossover to the late decay), to
// end x t_N, t_N = N^(2/d) / omega0 (the finite-size time), capped by the
// last sample.
struct LateDecayRule {
    double window_start = 3.0;
    double window_end = 0.3;
};

// The window is moved by this factor either way at each end for the window
// error: a quarter decade, about 2.5 samples of the 10-a-decade sample grid.
inline constexpr double window_shift_decades = 0.25;
// Fewest samples a window needs: a line through 4 points keeps 2 degrees of
// freedom for its chi2.
inline constexpr std::size_t min_window_samples = 4;
// The local slopes are smoothed over this many decades, centred.
inline constexpr double slope_smoothing_decades = 0.5;

// theta of T-bar ~ t^-theta over [t_a, t_b] (fit_power_law of the mean over
// realizations, point sigma its standard error), and where Haff's asymptote
// (t0/t)^2 meets the fitted law A t^-theta: t_c = (t0^2 / A)^(1/(2 - theta)).
// Both with the delete-one-realization jackknife (fit.hpp), each refit weighted
// by the standard errors of its own means. A realization is used when its
// temperature is finite at every sample of the window (a collapsed one is left
// out). An empty window (t_b <= t_a, fewer than min_window_samples samples) or
// fewer than 3 realizations (a refit needs 2 for its errors) give missing
// values with a note naming both times.
struct LateDecayFit {
    Estimate theta;
    Estimate crossover_time;
    Measured chi2_per_dof;
    std::size_t points = 0;
    std::size_t realizations = 0;
};
LateDecayFit fit_late_decay(const spheres::SphereOutput& run, double t_a, double t_b);

// Delta v / v of one realization's coarse-grained field: the flow energy per
// particle E_flow = sum_c n_c |V_c - V-bar|^2 / N (n_c = density_c N / cells
// particles in cell c, V-bar their mass-weighted mean velocity) against the
// total d T; sqrt((d T - E_flow) / E_flow), the thermal speed over the flow
// speed. NaN for a field without flow (E_flow = 0).
double thermal_over_flow(std::span<const double> density, std::span<const double> velocity_field, int dimension,
                         double particles, double temperature);

// The local slope d ln T / d ln t between successive samples, at their
// geometric mid-time, and the slope of the chord over the samples within
// +-slope_smoothing_decades / 2 of it (the mean of the local slopes weighted
// by d ln t). Samples with T not positive and finite are skipped.
struct LocalSlope {
    double time = 0.0;
    double slope = 0.0;
    double smoothed = 0.0;
};
std::vector<LocalSlope> local_slopes(std::span<const double> time, std::span<const double> temperature);

// The plateau of the local exponent: after Haff's law the smoothed local slope
// of T-bar falls to a minimum (the overshoot: its first local minimum at t > t0
// that it later rises from by plateau_rise or more) and then rises to its
// largest value before finite size steepens it again.
// theta is minus that largest slope, searched from the overshoot to the last
// sample, and time where it lies; the jackknife recomputes both from each
// delete-one mean of T. Where the fit window [t_a, t_b] is short or empty this
// is the number that tells 3/2 from 6/5 at a given N; it is not a fit, and a
// maximum of a noisy curve lies above the curve by about its noise. Missing
// when the slope never rises so after t0.
// plateau_rise: the rise after the overshoot is 0.4-0.5 in every run measured
// (-1.6 to -1.2 in 3D, -1.5 to -1.0 in 2D); the half-decade chords of the
// quick tier's means scatter by 0.02-0.04, so 0.1 is above their noise.
inline constexpr double plateau_rise = 0.1;
struct LocalPlateau {
    Estimate theta;
    double time = 0.0;
};
LocalPlateau local_plateau(const spheres::SphereOutput& run);

struct FlowSample {
    double time = 0.0;
    Estimate dv_over_v;  // mean over realizations, jackknife sigma
};

// The velocity distribution at one histogram time (shockgas-spheres'
// --histogram-times): u_k / sqrt(T) over every realization and component, its
// density and the tail fit of Eq. (6)'s form, ln P = a - c |u|^gamma over |u|
// >= 1.5 rms (fit_pooled_tail): gamma = 2 is a Gaussian, 1 an exponential tail.
// Nie, Ben-Naim & Chen (2002) report exponential tails early and a Gaussian
// late in 2D. gamma is missing (with the reason) where too few tail bins are
// filled or the fit ends at its search bound.
struct TailSample {
    double time = 0.0;
    std::vector<double> u, density, density_sigma;  // bin centres; P(u) over all counts; Poisson sigma
    double outside_fraction = 0.0;                  // beyond the histogram's range
    Estimate gamma;
    double c = 0.0;            // P ~ exp(-c |u|^gamma), u in units of its rms
    double u_lo = 0.0, u_hi = 0.0;  // the fitted range
};
TailSample velocity_tail(const spheres::SphereOutput& run, std::size_t histogram);

struct LateDecaySummary {
    double eps = 0.0;                  // (1 - r)/2
    double collision_frequency = 0.0;  // omega0 = Enskog's frequency at T = 1
    double haff_time = 0.0;            // t0
    double predicted_crossover = 0.0;  // t_pred = eps^(-4/(4-d)) / omega0
    double finite_size_time = 0.0;     // t_N = N^(2/d) / omega0
    double window_start = 0.0, window_end = 0.0;  // t_a, t_b
    double field_cell_size = 0.0;      // L / field_cells: Delta v / v depends on it
    LateDecayFit late;                     // over [t_a, t_b]
    Measured theta_window_sigma;       // max |Delta theta| over the shifted windows
    Estimate theta_free;               // the same fit from 3 t0: the drift of the exponent
    LocalPlateau plateau;              // the least steep local slope after the overshoot
    Estimate crossover_collisions;     // tau_c = omega0 t_c
    std::vector<double> temperature, temperature_sigma, kurtosis;  // per sample: mean over realizations
    std::vector<FlowSample> flow;      // per snapshot
    Estimate dv_over_v_exponent;       // of Delta v / v over the snapshots at t >= t_a
    std::vector<TailSample> tails;     // per histogram time
};
LateDecaySummary summarize_late_decay(const spheres::SphereOutput& run, const LateDecayRule& rule);

// The crossover exponent x of tau_c ~ eps^x over inputs of one dimension and
// packing fraction (fit_power_law with the jackknife sigmas; points without a
// measured tau_c and sigma left out), to compare with -4/(4-d). Throws
// InsufficientData unless two of them differ in eps.
struct CrossoverPoint {
    double eps = 0.0;
    Estimate collisions;
};
LinearFit fit_crossover_exponent(const std::vector<CrossoverPoint>& points);

// shockgas-analyze late-decay: per input a section /late_decay<k> of the
// results file, and per dimension and packing fraction /crossover_d<d> (with
// _phi<phi> when a dimension has several); the tables of T(t) (data), the
// local slopes (slopes), tau_c per input (crossovers) and Delta v / v
// (fluctuations), a block per input (per dimension for crossovers); P(u) at
// each histogram time (tails, a block per input and time) and its tail fits
// (tail_fits, a block per input). An empty path writes no table.
struct LateDecayTables {
    std::string data, slopes, crossovers, fluctuations, tails, tail_fits;
};
void run_late_decay(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                    const std::string& output, const LateDecayRule& rule, const LateDecayTables& tables);

}  // namespace shockgas::analysis
