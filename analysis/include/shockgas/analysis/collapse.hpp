// SPDX-License-Identifier: GPL-3.0-or-later
// Inelastic collapse of pure inelastic runs (delta = 0; P4): the time at which
// collapse stops a realization and the mass of the collapsing cluster, per
// file, and how they scale (docs/haff-and-collapse.md, "Collapse against eps and N").
//
// Against eps, competing forms are fitted to the ensemble means:
//   the paper:           t ~ eps^(-3/2), m ~ eps^-1 (t_stick, and m ~ t^(2/3) at t_stick);
//   McNamara & Young:    m ~ ln(1/2eps)/(2eps), the minimal collapsing cluster as r -> 1
//                        (Phys. Fluids A 4, 496 (1992); PRE 50, R28 (1994)), and
//                        t ~ m^(3/2) of it (sticky-gas growth m ~ t^(2/3));
//   a free power law     eps^x, and the paper's law with a free log correction.
// Against N at one eps, the first collapse on the ring is the earliest of
// about N/m independent regions: the cumulative collapse hazard per particle,
// H(t)/N, is then the same function of t for every N.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"

namespace shockgas::analysis {

// What one shockgas-sim output says about collapse.
struct CollapseEvents {
    double inelasticity = 0.0;          // eps = (1 - r)/2
    std::int64_t particles = 0;         // N
    std::size_t realizations = 0;       // realizations run
    double t_max = 0.0;                 // realizations that did not collapse ran to t_max
    double velocity_threshold = 0.0;    // delta (root attribute velocity_threshold); > 0: no collapse can happen
    std::vector<double> time;           // one entry per collapsed realization
    std::vector<double> cluster_mass;   // particles in the collapsing cluster, likewise
};
CollapseEvents read_collapse_events(const std::string& path);

struct CollapseSummary {
    double inelasticity = 0.0;
    std::int64_t particles = 0;
    std::size_t collapsed = 0, realizations = 0;
    Estimate time;           // mean over collapsed realizations, SE from their scatter
    Estimate cluster_mass;   // likewise, SE at least the counting resolution 1/sqrt(12 n)
    double time_spread = 0;  // sample standard deviation of t_collapse (the distribution's width)
};
// A run of one realization that collapsed gives its time and mass with sigma
// NaN and the jackknife's reason in note (nothing to leave out), and
// time_spread NaN for the same reason. Throws InsufficientData when a run of
// R >= 2 had fewer than 2 collapses, when a run of one did not collapse, or
// when some realizations did not (the mean over the collapsed ones would be
// biased early).
CollapseSummary summarize_collapse(const CollapseEvents& events);

// One fitted form y = prefactor * g(eps; exponent), fitted as ln y with
// sigma_{ln y} = sigma_y / y, so that the chi2, AIC and BIC of every form of
// one quantity are comparable.
struct CollapseForm {
    std::string name;       // power | log_corrected | paper | mcnamara_young
    std::string formula;    // for people, e.g. "C eps^-3/2 (ln 1/eps)^y"
    double prefactor = 0.0;
    Estimate exponent;      // the free exponent (x or y); for a fixed form its fixed value, sigma 0
    // sigma of the exponent scaled by sqrt(chi2/dof) when that exceeds 1 (the
    // Particle Data Group's scale factor: the scatter is larger than the error bars say); NaN when the
    // fit leaves no degree of freedom (a free form through 2 points).
    double exponent_sigma_scaled = 0.0;
    LinearFit fit;          // in the form's log variables: chi2, points, parameters, AIC, BIC
};

enum class CollapseQuantity { time, cluster_mass };

// The paper's exponent of eps for each quantity: t ~ eps^(-3/2), m ~ eps^-1.
double paper_exponent(CollapseQuantity quantity);

// McNamara & Young's minimal collapsing cluster for r -> 1, ln(1/(2 eps)) / (2 eps)
// (PRE 50, R28 (1994); r = 1 - 2 eps). Needs 0 < eps < 1/2.
double mcnamara_young_cluster(double inelasticity);

// The four forms of the header, fitted by weighted_linear_fit / fixed_slope_fit,
// in the order power, log_corrected, paper, mcnamara_young.
std::vector<CollapseForm> fit_collapse_forms(CollapseQuantity quantity, const std::vector<double>& inelasticity,
                                             const std::vector<Estimate>& values);

// Nelson-Aalen estimate of the cumulative collapse hazard of one ensemble,
// divided by N: at the i-th earliest collapse time (1-based, R realizations,
// every realization at risk until it collapses or reaches t_max)
//   H(t_i) = sum_{j <= i} 1/(R - j + 1),   var H(t_i) = sum_{j <= i} 1/(R - j + 1)^2
// (Nelson, Technometrics 14, 945 (1972); Aalen, Ann. Stat. 6, 701 (1978)).
// If collapse strikes independent regions, the survival of a ring of N
// particles is S_N(t) = exp(-N h(t)) and H/N = h(t) does not depend on N.
struct CumulativeHazard {
    std::vector<double> time;
    std::vector<double> per_particle;        // H(t_i) / N
    std::vector<double> per_particle_sigma;  // sqrt(var H(t_i)) / N
};
CumulativeHazard cumulative_hazard_per_particle(const CollapseEvents& events);

// The N dependence at one eps (the extreme-value picture).
struct FirstCollapseScaling {
    LinearFit mean_time;      // ln <t> = ln C + slope ln N
    LinearFit cluster_mass;   // ln <m> = ln C + slope ln N (0 if collapse is local)
    // Pooled over every N: ln(H/N) = ln a + k ln t, with the covariance scaled
    // by the residuals (the points of one curve are cumulative, hence
    // correlated; the sigma is indicative). A cumulative hazard H/N = a t^k
    // makes S_N(t) = exp(-N a t^k) a Weibull law of shape k, whose mean is
    // Gamma(1 + 1/k) (N a)^(-1/k): <t> ~ N^(-1/k).
    LinearFit hazard;
    Estimate predicted_mean_time_exponent;  // -1/k from the hazard, sigma propagated
    // Many regions (N/<m> >= gumbel_min_regions): if the cumulative hazard per
    // particle rises exponentially, H/N = a e^(t/tau), the first collapse is
    // Gumbel-distributed, t = tau ln(E/(N a)) with E ~ Exp(1): its mean falls as
    // -tau ln N and its standard deviation is pi tau / sqrt 6 at every N
    // (Gumbel, Statistics of Extremes (1958)). Fitted: <t> = a + slope ln N
    // (slope = -tau); compared: the predicted and the measured spread.
    std::size_t gumbel_runs = 0;                // runs with enough regions
    LinearFit gumbel;                           // valid when gumbel_note is empty
    std::string gumbel_note;                    // why the Gumbel fit was not made (fewer than 2 distinct N)
    Estimate gumbel_tau;                        // -slope
    Estimate gumbel_predicted_spread;           // pi tau / sqrt 6
    Estimate gumbel_measured_spread;            // weighted mean of their sample standard deviations
};
// A region is about one collapsing cluster; 50 of them make the minimum an extreme.
constexpr double gumbel_min_regions = 50.0;
// Throws InsufficientData naming a run of one realization: the fits weigh each
// run by its error bar, which one realization does not have (summarize_collapse).
FirstCollapseScaling fit_first_collapse_scaling(const std::vector<CollapseEvents>& runs);

// Power law y = C eps^exponent over several eps (fit_power_law with the SEs as
// sigma); also used for the crossover times.
LinearFit fit_against_inelasticity(const std::vector<double>& inelasticity, const std::vector<Estimate>& values);

}  // namespace shockgas::analysis
