// SPDX-License-Identifier: GPL-3.0-or-later
// How far one run's T(t) lies from a reference run's: the measure of the
// speed/accuracy trade (a larger threshold delta, or the sticky sub-threshold
// mechanism, is cheaper; how much does T(t) move?). P5 of the paper: results
// are independent of delta while v ~ t^(-1/3) >> delta, i.e. up to
// t_valid ~ delta^(-3).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shockgas/analysis/temperature.hpp"

namespace shockgas::analysis {

// How the realizations of a run and of its reference relate. compare's runs
// share seed and first realization (comparison_differences), so realization k
// starts from the same state in both: they are paired, and the fluctuations
// of a realization largely cancel in its ratio. Independent ensembles (other
// seeds) are compared with both standard errors in quadrature.
enum class Realizations { paired, independent };

struct TemperatureComparison {
    std::vector<double> time;                // common sample times
    std::vector<double> relative_deviation;  // <T>/<T_ref> - 1
    std::vector<double> relative_sigma;      // its standard error (see compare_temperatures); NaN, see below
    std::string sigma_note;                  // why relative_sigma is NaN (one realization), else empty
    std::size_t realizations_compared = 0;   // paired: the common realizations 0..n-1; independent: 0
    std::string pairing_note;                // paired runs of unequal R: which realizations were compared
    double max_abs_deviation = 0.0;          // max_k |<T>/<T_ref> - 1|
    double time_of_max = 0.0;
    // The first sample time from which on the deviation exceeds
    // max(k_sigma * relative_sigma, floor) at every later time; +inf if never.
    double departure_time = 0.0;
};

// Compares at the sample times both histories share (they must come from the
// same sample grid).
// - paired: over the realizations both runs have (0 .. min(R, R_ref) - 1),
//   ratio = sum_k T_k / sum_k T_ref,k and relative_sigma its delete-one-pair
//   jackknife standard error (Efron & Tibshirani, An Introduction to the
//   Bootstrap, 1993, Eq. 11.5), which keeps the covariance of the pairs. Two
//   runs that have not yet diverged give sigma 0 there, and the floor decides.
// - independent: ratio of the full means, relative_sigma = |ratio|
//   sqrt((SE/T)^2 + (SE_ref/T_ref)^2) (first-order error propagation).
// relative_sigma is NaN with one realization (paired: one in common); the
// departure rule then uses the floor alone. Throws InsufficientData when the
// histories share no sample time: there is nothing to compare, and no
// deviation is not agreement.
TemperatureComparison compare_temperatures(const TemperatureHistory& run, const TemperatureHistory& reference,
                                           Realizations realizations, double k_sigma = 3.0, double floor = 0.02);

// What a deviation from the reference is: relative, <X>/<X_ref> - 1 (T, whose
// tolerances are fractions), or absolute, <X> - <X_ref> (an observable whose
// reference may be 0, such as the sticky gas's fragmentation rate).
enum class Deviation { relative, absolute };

// compare_temperatures for any R x K table of one observable (the history's
// `temperature` holds its values), with the deviation `mode`: what
// shockgas-analyze validity judges every observable by. relative_deviation
// and relative_sigma then hold the absolute difference and its error.
TemperatureComparison compare_histories(const TemperatureHistory& run, const TemperatureHistory& reference,
                                        Realizations realizations, Deviation mode, double k_sigma, double floor);

// compare measures what the threshold delta and the sub-threshold rule cost
// in accuracy: a run and its reference must be the same ensemble otherwise,
// or the deviation measures something else (another N, r or start). They
// must share the root attributes particles, ring_length, restitution (the
// physics), seed, first_realization, positions, velocity_distribution and
// init_file_sha256 (the initial states: realization k starts alike in both).
// They may differ in velocity_threshold, subthreshold, t_max, the sample
// grid, the realization count (the common ones start alike) and the engine.
// An attribute that only one of the files has (an older schema) is not compared.
// Returns the differences as "particles 1000 vs 2000, restitution 0.8 vs 0.9"
// (the run's value first), empty when the runs are comparable.
// With same_restitution false, r may differ too (validity compares every r
// with the sticky gas, r = 0).
std::string comparison_differences(const std::string& reference_path, const std::string& run_path,
                                   bool same_restitution = true);

}  // namespace shockgas::analysis
