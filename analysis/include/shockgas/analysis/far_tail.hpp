// SPDX-License-Identifier: GPL-3.0-or-later
// The tail exponent gamma of Phi(z) ~ exp(-a z^gamma) (Eq. (6); exact value 3
// for the sticky gas, EB9 of python/exact_ballistic.py) from the far-tail
// sampler's output (shockgas-tail, docs/far-tail.md).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"

namespace shockgas::analysis {

// ln Phi on output bins, its jackknife sigma, and ln Phi without each chain.
struct FarTail {
    std::vector<double> z;
    std::vector<double> log_phi;
    std::vector<double> log_phi_sigma;
    std::vector<std::vector<double>> log_phi_leave_one_chain_out;  // per chain
    double time = 0.0;
};
FarTail read_far_tail(const std::string& path);

// Eq. (6) with the exact tail's prefactor and linear term (EB9):
//   ln Phi = c - 2 ln z - a z^gamma - b z.
// b is either fixed (default: EB9's |a_1|/(2D)^(1/3) = 2.676 at D = 1/3, a
// subleading term known exactly) or free. At fixed gamma the model is
// linear: in (c, a) with b fixed (weighted_linear_fit against z^gamma), in
// (c, a, b) with b free (weighted_multilinear_fit); sigma = sigma(ln Phi).
// gamma minimises chi2 over [1, 6]; a minimum at 1 or 6 is the range, not
// the data, and gamma is then NaN with the bound named. With b free, a, b and gamma are
// strongly correlated: over z in [2, 6] gamma's error is ~4x larger. On the
// exact Phi (python/exact_ballistic.py) the fixed-b fit gives gamma = 3.001
// over [2, 5.5] and 3.013 over [2, 4] (the O(1/z^2) corrections of EB9).
// The Delta chi2 = 1 width ignores that neighbouring bins share samples.
struct TailExponentFit {
    SearchMinimum search;          // the minimisation over [1, 6]
    double gamma = 0.0;            // NaN when the search ended at a bound of [1, 6], with gamma_note
    std::string gamma_note;
    double gamma_fit_sigma = 0.0;  // NaN (with gamma_fit_sigma_note) when gamma is, or chi2 is not curved up
    std::string gamma_fit_sigma_note;
    double a = 0.0, b = 0.0, c = 0.0;
    double chi2_per_dof = 0.0;
    std::size_t points = 0;
    double z_lo = 0.0, z_hi = 0.0;
};
constexpr double exact_tail_linear_coefficient = 2.676;  // EB9: |a_1| / (2D)^(1/3), D = 1/3
TailExponentFit fit_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi,
                                  const std::vector<double>& log_phi_sigma, double z_lo, double z_hi,
                                  std::optional<double> linear_coefficient = exact_tail_linear_coefficient);

// Local exponent d ln(-ln(z^2 Phi / A)) / d ln z at z0 (A = EB9's prefactor
// 2^(11/6) D^(1/3)/Ai'(a_1) = 3.5237 at D = 1/3): the slope of a straight line
// through the bins within +-half_width of z0 (weighted_linear_fit); NaN where
// fewer than 3 bins or -ln(z^2 Phi/A) <= 0. Tends to gamma for z -> infinity;
// on the exact Phi 2.26, 2.50, 2.65 at z = 3, 4, 5.
constexpr double exact_tail_prefactor = 3.523703;
double local_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi, double z0,
                           double half_width = 0.25);

// gamma over [z_lo, z_hi] with its statistical error from the delete-one-chain
// jackknife (the chains are independent) and a window systematic: half the
// spread (max - min)/2 of gamma when z_lo and z_hi move by +-window_shift.
// gamma is missing when its search ends at a bound (the systematic too), its
// sigma when a leave-one-chain-out search does, or when there are fewer than 3
// chains (two: a replica keeps one, with no spread to weigh the bins by; one:
// nothing to leave out); the systematic when a moved window's does.
// window_note says when the data cut the window short.
struct TailExponent {
    TailExponentFit fit;
    Estimate gamma;                 // value and jackknife sigma
    Measured window_systematic;     // missing when no shifted window holds enough bins
    std::string window_note;        // "the window [2, 5.5] was clipped to the data: ..." or empty
    double total_sigma() const;     // statistical (+) systematic in quadrature
};
TailExponent estimate_tail_exponent(const FarTail& tail, double z_lo, double z_hi, double window_shift = 0.25,
                                    std::optional<double> linear_coefficient = exact_tail_linear_coefficient);

}  // namespace shockgas::analysis
