// SPDX-License-Identifier: GPL-3.0-or-later
// How long a gas with threshold delta > 0 stands in for the sticky gas
// (docs/validity.md). The paper takes delta as harmless (its Fig. 2); Shinde,
// Das & Rajesh (PRL 99, 234505 (2007); PRE 79, 021303 (2009)) find that the
// gas leaves the sticky gas for t >> 1/delta, and the estimate "the typical
// velocity t^(-1/3) reaches delta" gives t ~ delta^(-3). This measures, per
// observable, when a run leaves its sticky-gas reference (r = 0, the same N,
// seeds and times) and how that time scales with delta.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/analysis/compare.hpp"
#include "shockgas/analysis/results.hpp"
#include "shockgas/analysis/validity_map.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::analysis {

// nu of the sticky gas's cluster density n = nu t^(-2/3) (docs/exact-theory.md:
// clusters per particle x t^(2/3) -> 1.9156786, from python/exact_ballistic.py).
inline constexpr double sticky_gas_cluster_prefactor = 1.9156786;
// The kurtosis of the sticky gas's exact Phi (docs/exact-theory.md, the same
// source), the value a sticky-gas run's kurtosis approaches.
inline constexpr double sticky_gas_kurtosis = 3.0410;

// The definitions behind the structural observables, each with why it is
// what it is (docs/validity.md).
struct ValidityRule {
    // A cluster of a gas whose particles need not stick: a maximal run of ring
    // neighbours whose gaps are below this fraction of the sticky gas's mean
    // cluster spacing at the same t, t^(2/3) / nu (in units of L/N; nu =
    // sticky_gas_cluster_prefactor). The sticky gas's own clusters are
    // points, and 5-8 % of its empty gaps are that short (tested), so the rule
    // finds 92-95 % of its clusters for t >= 100; a cluster of the delta gas,
    // whose particles need not stick, has an extent, and stays one cluster
    // while its internal gaps are small on the scale of the clusters'
    // spacing. 0.01 splits the delta gas's clusters at every time (their gaps
    // are 0.01-0.05 at t = 1e4 for delta = 1e-2, r = 0.9), 0.3 merges a quarter of
    // the sticky gas's.
    double cluster_gap_fraction = 0.1;
    // The empty-gap distribution's weight at small gaps: the fraction of gaps
    // between clusters shorter than this fraction of their mean.
    double small_gap_fraction = 0.1;
    // The density structure function is read at k = this / t^(2/3) (in units
    // of N/L): a wavelength of 2 pi / 100 = 6 % of the mean cluster spacing
    // scale t^(2/3), its small-distance (Porod) side. Point clusters give
    // S(k) -> sum m^2 / N there; clusters of width w > 1/k give less.
    double structure_wavenumber = 100.0;
    // The 3-sigma criterion of the departure: sigma is the paired jackknife
    // error of the difference from the reference.
    double k_sigma = 3.0;
};

// Observable names, in display order (ValidityMap::observables).
const std::vector<std::string>& validity_observables();

// The structural observables of one snapshot.
struct SnapshotObservables {
    double kurtosis = 0.0;            // mass-weighted <(v-V)^4> / <(v-V)^2>^2 (kurtosis of Phi, Eq. 4)
    double cluster_density = 0.0;     // clusters per particle x t^(2/3) / nu (1 for the sticky gas's scaling)
    double small_gap_fraction = 0.0;  // see ValidityRule::small_gap_fraction
    double structure_function = 0.0;  // S(k) t^(-2/3) at k = structure_wavenumber / t^(2/3)
};

// Cluster boundaries of a state in ring order (as snapshots store it): the
// indices at which a new cluster begins, by ValidityRule::cluster_gap_fraction
// at the state's time. A ring of one cluster returns {0}.
std::vector<std::size_t> cluster_starts(const ClusterState& state, double ring_length, std::int64_t particles,
                                        const ValidityRule& rule);

SnapshotObservables snapshot_observables(const ClusterState& state, double ring_length, std::int64_t particles,
                                         const ValidityRule& rule);

// The fraction of the clusters of `earlier` whose particles are not all in
// one cluster of `later` (the same realization at a later time), per unit
// ln t: the effective fragmentation rate. Particles are known by their ring
// order (first_particle), which collisions on a line never change. The
// sticky gas's clusters never split: 0.
double fragmentation_rate(const ClusterState& earlier, const ClusterState& later, double ring_length,
                          std::int64_t particles, const ValidityRule& rule);

// An observable of every realization at a run's times: R x K, row-major
// (the analysis library's history table).
struct ObservableHistory {
    std::string observable;
    TemperatureHistory values;
};

// Every observable of validity_observables() for one run: temperature from
// the time series (T t^(2/3) / kappa), the others from the snapshots
// (fragmentation at each snapshot time but the last, towards the next).
std::vector<ObservableHistory> observable_histories(const std::string& run_path, const ValidityRule& rule);

// t* of one observable against its reference by one criterion ("3sigma":
// k_sigma paired jackknife errors; "1percent", "5percent": a relative band,
// |X / X_ref - 1| > 0.01 or 0.05 by 2 sigma; for the fragmentation rate, whose reference
// is 0, an absolute one: that fraction of the clusters splitting per unit
// ln t), with its delete-one-pair jackknife sigma (runs paired by realization).
ValidityDeparture departure(const ObservableHistory& run, const ObservableHistory& reference,
                            const std::string& criterion, const ValidityRule& rule);

// t* = A delta^(-mu) over the runs of one (observable, criterion, r,
// mechanism, N) that departed; follows says which of mu = 1 and 3 lies
// within 2 sigma.
ValidityFit fit_departures(const std::vector<const ValidityRun*>& runs, const std::string& observable,
                           const std::string& criterion);

// shockgas-analyze validity: every input with r = 0 and delta = 0 is a
// sticky-gas reference; every other input is compared with the reference of
// its N and seed. Writes the results file (with /validity_map), and the
// gnuplot tables: `data` the departures and fits, `curves` each observable's
// difference from the reference against t, one block per run and observable.
void run_validity(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, const std::string& data, const std::string& curves,
                  const std::string& fidelity, const ValidityRule& rule);

}  // namespace shockgas::analysis
