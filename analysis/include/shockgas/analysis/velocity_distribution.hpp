// SPDX-License-Identifier: GPL-3.0-or-later
// Estimators on the mass-weighted velocity distribution P(v, t): the scaling
// collapse of Eq. (4) with its best exponent, the kurtosis of Phi, and the
// tail exponent gamma of Eq. (6).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/model/records.hpp"

namespace shockgas::analysis {

// One /histograms/<h> entry: mass-weighted counts of v - V per realization,
// of the realizations that reached its time (histograms_of_run).
struct VelocityHistogram {
    std::string label;          // e.g. "r=0.9 t=1000", for data files
    double time = 0.0;
    std::vector<double> edges;  // bins + 1, velocity units (v - V)
    std::size_t realizations = 0;           // rows of counts: the realizations that reached time
    std::size_t recorded_realizations = 0;  // R of the run; more than realizations when some stopped before time
    std::vector<double> counts; // realizations x (bins + 2): underflow, bins, overflow

    std::size_t bins() const { return edges.size() - 1; }
    // Counts summed over realizations (bins + 2 entries); realizations r with
    // r % groups == left_out_group are left out (delete-one-group jackknife).
    std::vector<double> pooled(std::optional<std::size_t> left_out_group = std::nullopt,
                               std::size_t groups = 1) const;
};

// The histograms of a run, each over the realizations that reached its time.
// A realization stopped before a histogram time (an interrupted run: Ctrl-C,
// or a realization that never started) left a row of zeros there, which
// counted as a realization would bias every mean, standard error, jackknife
// and tail fit (in one interrupted run: kurtosis sigma 0.206 instead of 0.168,
// no usable tail bin instead of 12). Which realizations reached time t is what the run
// recorded: T(t) in /timeseries/temperature is a number exactly for them
// (NaN otherwise); for a time the series does not hold, a row with mass.
// Their rows are kept in realization order, so with the usual interruption
// (the last realizations unfinished) the jackknife groups r % G stay the same
// realizations at every time. A row recorded as reached but without mass, or
// with mass but not reached, is refused as damaged (h5::Error naming it).
struct RunHistograms {
    std::vector<VelocityHistogram> histograms;  // the times at least one realization reached, in time order
    std::vector<double> unreached_times;        // histogram times no realization reached (left out)
    std::size_t realizations = 0;               // R of the run
    std::string status;                         // the run's: complete | collapsed | interrupted
};
RunHistograms histograms_of_run(const EnsembleResult& result, const std::string& label_prefix = "",
                                const std::string& path = "");
// histograms_of_run(...).histograms: runs made in memory (run_ensemble) have every time.
std::vector<VelocityHistogram> histograms_from(const EnsembleResult& result, const std::string& label_prefix = "");
// A shockgas-sim output's histograms; damaged ones refused (h5::Error naming
// the file and the group).
RunHistograms read_histograms(const std::string& path, const std::string& label_prefix = "");

// Jackknife groups used for histogram estimators: min(R, max_jackknife_groups) over all
// inputs; each group is every realization r with r % groups == g.
constexpr std::size_t max_jackknife_groups = 20;  // enough for a 16%-accurate sigma, cheap to recompute

// --- Eq. (4): P(v, t) = t^beta Phi(v t^beta), beta = 1/3 ---
// Rescaled cumulative distribution G_t(z) = F_t(z t^(-beta)), F_t the
// piecewise-linear CDF of the mass-weighted histogram (underflow counted
// below the first edge). Collapse distance of a set of curves:
//   D(beta) = mean over pairs (a, b) of mean over a grid of z of (G_a(z) - G_b(z))^2,
// the grid covering the z range every curve resolves. D = 0 for a perfect collapse.
double collapse_distance(const std::vector<VelocityHistogram>& histograms, double beta,
                         std::optional<std::size_t> left_out_group = std::nullopt, std::size_t groups = 1);
// sup_z |G_a(z) - G_b(z)| at beta, the largest over pairs (a Kolmogorov distance).
double collapse_max_deviation(const std::vector<VelocityHistogram>& histograms, double beta);

struct ScalingCollapse {
    Estimate beta;                   // argmin D(beta), sigma from the group jackknife; n/a at a search bound
    Measured distance_at_best;       // D(beta*); missing when beta is
    double distance_at_one_third = 0.0;
    double max_deviation_at_one_third = 0.0;
    std::size_t jackknife_groups = 0;
};
// Minimises D over beta in [beta_min, beta_max] (grid, then golden section).
// A minimum at either end of the range is not a measurement: beta is then
// missing with the bound named (sigma likewise when a jackknife replica's is).
ScalingCollapse fit_scaling_collapse(const std::vector<VelocityHistogram>& histograms, double beta_min = 0.05,
                                     double beta_max = 0.8);

// Phi(z) on the histogram's bins with z = v t^beta: bin centres and density
// normalised to unit total mass (under- and overflow included in the mass).
struct ScaledDistribution {
    std::vector<double> z;
    std::vector<double> density;
    double outside_fraction = 0.0;  // mass in under- and overflow
};
ScaledDistribution scaled_distribution(const VelocityHistogram& histogram, double beta = 1.0 / 3.0);

// Kurtosis of Phi: <(v - <v>)^4> / <(v - <v>)^2>^2 over bin centres,
// mass-weighted (3 for a Gaussian); sigma from the group jackknife.
Estimate velocity_kurtosis(const VelocityHistogram& histogram);

// --- Eq. (6): Phi(z) ~ exp(-c |z|^gamma) for |z| >> 1 ---
// Both signs of z are folded. Tail bins: |z| >= tail_start * sqrt(<z^2>) whose
// folded density has relative standard error (realization scatter) at most
// max_relative_error. For each gamma, ln Phi = a - c |z|^gamma is linear in
// (a, c) and fitted by weighted_linear_fit with sigma_{ln Phi} = SE/Phi; gamma
// minimises chi2 (grid then golden section) over [0.5, 8]. sigma(gamma) from the group
// jackknife over realizations; the Delta chi2 = 1 width is reported too. A
// minimum at 0.5 or 8 is the range, not the data: gamma and both widths are
// then missing, with the bound named.
struct TailRule {
    double tail_start = 1.5;         // in units of the rms of z: beyond the Gaussian-like bulk
    double max_relative_error = 0.3; // keeps ln(Phi +- SE) linear in SE (first-order propagation)
};
struct TailFit {
    Estimate gamma;                // missing at an end of the search range [0.5, 8] (not a measurement)
    double gamma_fit_sigma = 0.0;  // Delta chi2 = 1 (ignores bin-to-bin correlations); NaN with the note below
    std::string gamma_fit_sigma_note;
    double c = 0.0;                // Phi ~ exp(-c |z|^gamma), z in units of the rms of z
    double chi2_per_dof = 0.0;
    std::size_t bins = 0;
    double z_lo = 0.0, z_hi = 0.0; // fitted range, units of the rms of z
    double total_mass = 0.0;       // particles (mass) in the histogram, all realizations
};
TailFit fit_tail(const VelocityHistogram& histogram, const TailRule& rule = {});
// The same fit on a histogram pooled over realizations (shockgas-spheres'
// /histograms: counts per bin, edges bins + 1), each folded bin weighed by its
// Poisson error 1/sqrt(n) in ln Phi: there is no realization scatter to weigh
// by or to jackknife, so gamma's sigma is the Delta chi2 = 1 width (with a
// note saying so). Throws InsufficientData as fit_tail does.
TailFit fit_pooled_tail(const std::vector<double>& edges, const std::vector<double>& counts,
                        const TailRule& rule = {});

}  // namespace shockgas::analysis
