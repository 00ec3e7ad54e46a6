// The tail exponent gamma of Phi(z) ~ exp(-a z^gamma) (Eq. (5); exact value 3
// for the sticky gas, EB9 of python/exact_ballistic.py) from the far-tail
// sampler's output (shockgas-tail, docs/far-tail.md).
#pragma once

#include <cstddef>
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

// Eq. (5) with the exact tail's prefactor and linear term (EB9):
//   ln Phi = c - 2 ln z - a z^gamma - b z.
// At fixed gamma it is linear in (c, a, b) (weighted_multilinear_fit with
// sigma = sigma(ln Phi)); gamma minimises chi2 over [1, 6]. The Delta
// chi2 = 1 width ignores that neighbouring bins share chains' samples.
struct TailExponentFit {
    double gamma = 0.0;
    double gamma_fit_sigma = 0.0;
    double a = 0.0, b = 0.0, c = 0.0;
    double chi2_per_dof = 0.0;
    std::size_t points = 0;
    double z_lo = 0.0, z_hi = 0.0;
};
TailExponentFit fit_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi,
                                  const std::vector<double>& log_phi_sigma, double z_lo, double z_hi);

// gamma over [z_lo, z_hi] with its statistical error from the delete-one-chain
// jackknife (the chains are independent) and a window systematic: half the
// spread (max - min)/2 of gamma when z_lo and z_hi move by +-window_shift.
struct TailExponent {
    TailExponentFit fit;
    Estimate gamma;                 // value and jackknife sigma
    double window_systematic = 0.0;
    double total_sigma() const;     // statistical (+) systematic in quadrature
};
TailExponent estimate_tail_exponent(const FarTail& tail, double z_lo, double z_hi, double window_shift = 0.25);

}  // namespace shockgas::analysis
