// SPDX-License-Identifier: GPL-3.0-or-later
// Large-deviation sampler for the far tail of the sticky gas's mass-weighted
// velocity distribution Phi(z), z = V t^(1/3) (docs/far-tail.md).
//
// Phi is a tagged-particle law: the mass-weighted distribution of cluster
// velocities is the law of the velocity V of the cluster that holds one given
// particle. So a sample is a function of the i.i.d. initial velocities of an
// open window of particles around a tagged one (the clusters by the one PAV,
// shockgas/model/pav.hpp), and probabilities far below any histogram's reach
// (10^-30 and less) are measured by biased Markov chains over those
// velocities (Hartmann's method: Hartmann, Le Doussal, Majumdar, Rosso &
// Schehr, EPL 121, 67004 (2018)): a chain at bias beta samples the window
// with weight prior(v) exp(beta z(v)); chains at a ladder of biases overlap,
// and the weighted-histogram equations (WHAM: Ferrenberg & Swendsen, PRL 63,
// 1195 (1989); Kumar et al., J. Comput. Chem. 13, 1011 (1992)) combine them
// into one normalized Phi. Error bars come from independent chains (the
// delete-one-chain jackknife), not from a model of the correlations.
#pragma once

#include "shockgas/model/parameters.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "shockgas/model/pav.hpp"

namespace shockgas {

// The law of each initial velocity. Both have variance 1/3 (the project's
// uniform law on [-1, 1]); the Gaussian is the white-noise setting of the
// exact solution (python/exact_ballistic.py).
// The initial velocity law is the simulator's (parameters.hpp: VelocityLaw,
// to_string, velocity_law_from_string), variance 1/3 either way. The chains
// move latent N(0, 1/3) variables for both laws and map them to velocities
// (for the uniform law v = erf(g sqrt(3/2)), which is uniform on [-1, 1]), so
// no move can leave the law's support.

// z = V t^(1/3) of the cluster holding the tagged particle at time t: unit
// masses at x = -W, ..., W (W = half_window) on an open line, the tagged
// particle at x = 0 (EB8 of python/exact_ballistic.py: Phi(z) is the law of
// this z for t -> infinity and W -> infinity).
class TaggedClusterVelocity {
public:
    TaggedClusterVelocity(std::int64_t half_window, double time);
    std::size_t sites() const { return position_.size(); }
    std::size_t tagged() const { return position_.size() / 2; }
    double time() const { return time_; }
    // velocity has sites() entries, in the order of x.
    double operator()(std::span<const double> velocity);
    // Mass of the tagged cluster after the last call (particles).
    double last_cluster_mass() const { return last_mass_; }

private:
    std::vector<double> position_;
    std::vector<LineCluster> clusters_;  // workspace
    double time_;
    double scale_;  // t^(1/3)
    double last_mass_ = 0.0;
};

// Any observable of the window's initial velocities (the sampler does not
// care which: tests use the mean of M velocities, whose law is exact).
using WindowObservable = std::function<double(std::span<const double> velocity)>;
// Makes one observable per thread (an observable may keep scratch state, as
// TaggedClusterVelocity does, so threads do not share one).
using ObservableFactory = std::function<WindowObservable()>;
// Called from the calling thread about twice a second while the chains run:
// the share of all Metropolis steps done, and the wall seconds since the start.
using TailProgress = std::function<void(double fraction_done, double elapsed_seconds)>;

struct TailSamplerParameters {
    std::vector<double> biases;          // beta_k, ascending; the first must be 0 (plain sampling, fixes the norm)
    std::int64_t sites = 0;              // initial velocities in the chain state
    std::int64_t focus_begin = 0;        // proposals pick a site in [focus_begin, focus_end) ...
    std::int64_t focus_end = 0;
    double focus_probability = 0.8;      // ... with this probability, else any site
    double block_probability = 0.3;      // share of block-shift moves (a run of sites moved together)
    std::int64_t block_max = 100;        // longest run a block shift moves
    std::int64_t exchange_interval = 50; // steps per bias between replica-exchange attempts
    std::vector<double> start_mean;      // biases x sites: replica k starts at prior noise + this (empty: prior)
    std::int64_t steps_per_bias = 0;     // recorded Metropolis steps per chain and bias
    std::int64_t burn_in_steps = 0;      // unrecorded steps per bias before the record starts
    std::int64_t chains = 4;             // independent chains (error bars); >= 2
    std::uint64_t seed = 1;
    VelocityLaw law = VelocityLaw::gaussian;
    double z_min = -3.0, z_max = 7.0;    // histogram range (must hold the whole unbiased mass)
    double fine_bin_width = 1e-3;        // WHAM bins: bias varies by beta * width <= ~0.07 across one
    std::int64_t fine_bins_per_output_bin = 10;
    // Chains run at once, one per thread (0: every core). Each chain has its
    // own random stream (realization_seed(seed, chain)) and the chains are
    // combined in chain order, so the result does not depend on it.
    int threads = 1;
};

// A ladder of biases for Phi's tail: beta(z*) = -d ln Phi/dz at z*, from the
// bulk Gaussian (z*/kappa) and the exact tail (EB9: 3 z*^2/2 + |a_1|/(2D)^(1/3)),
// whichever is larger, for z* = step, 2 step, ..., reach; plus beta = 0.
// A chain at beta then sits near z*, and neighbours overlap when step is
// below the tilted law's width (~ 1/sqrt(3 z*)).
std::vector<double> tail_bias_ladder(double z_reach, double z_step);

// The z_k at which tail_bias_ladder(z_reach, z_step) centres its chains (0 first).
std::vector<double> tail_ladder_targets(double z_reach, double z_step);

// The optimal (instanton) mean of the initial velocities for the tagged
// cluster to reach z at time t, from the saddle of EB9 in lattice units:
// the cluster, of scaled mass 6/w^2 (w = z D^(-1/3)) ending at the tag, moves
// at V = z t^(-1/3); the particles ahead must get out of its way, which
// costs least as a linear ramp of velocities from V down to 0 over the V t
// particles it would otherwise sweep up (the one-sided factor
// psi(b) ~ exp(-|b|^3/6) of EB4' is the cost of this ramp: the cubic tail).
// Zero for z < 1.5. Used to start the chains near their typical set; it is
// also why the window must reach well beyond V t ahead of the tag.
std::vector<double> tagged_cluster_instanton(double z, double time, std::int64_t half_window);

struct TailEstimate {
    // Output bins (centres): Phi, its jackknife sigma (NaN where a
    // leave-one-chain-out estimate has no samples), ln Phi and its sigma.
    std::vector<double> z;
    std::vector<double> density;
    std::vector<double> density_sigma;
    std::vector<double> log_density;
    std::vector<double> log_density_sigma;
    std::vector<double> samples;          // recorded samples per output bin, all chains and biases
    std::vector<double> leave_one_out;    // chains x bins: ln Phi without chain c (for jackknifed fits)
    // Per bias: how the pieces were sampled and how they overlap.
    std::vector<double> biases;
    std::vector<double> acceptance;
    std::vector<double> mean_z;
    std::vector<double> log_partition;    // F_k = ln sum_b P_b exp(beta_k z_b), from WHAM
    std::vector<double> overlap_with_next;// sum_b min(h_k(b), h_{k+1}(b)) of normalized histograms
    std::vector<double> swap_acceptance;  // replica exchange between biases k and k + 1
    std::int64_t chains = 0;
    std::int64_t evaluations = 0;         // observable evaluations, all chains
    std::int64_t wham_iterations = 0;
    double cpu_seconds = 0.0;             // CPU of the whole process while the chains ran (all threads)
    double wall_seconds = 0.0;
};

// Runs the chains and combines them. Each chain holds one replica per bias,
// all started from the prior, with replica exchange between neighbours.
TailEstimate sample_far_tail(const TailSamplerParameters& parameters, const ObservableFactory& make_observable,
                             const TailProgress& progress = {});
// The same with one observable, used by one thread (parameters.threads is not
// read).
TailEstimate sample_far_tail(const TailSamplerParameters& parameters, const WindowObservable& observable);

// The WHAM equations on bins of centres z_b for histograms h_kb (K x B,
// row-major) from chains biased by exp(beta_k z), N_k = samples_k:
//   P_b = sum_k h_kb / sum_k N_k exp(beta_k z_b - F_k),  F_k = ln sum_b P_b exp(beta_k z_b),
// iterated in logarithms to |dF| < 1e-10; returns ln P_b (sum_b P_b = 1;
// -inf where no chain has a sample). iterations, if given, gets the count.
std::vector<double> wham_log_probability(std::span<const double> histograms, std::span<const double> samples,
                                         std::span<const double> biases, std::span<const double> bin_centres,
                                         std::vector<double>* log_partition = nullptr,
                                         std::int64_t* iterations = nullptr);

// Writes the estimate as HDF5 (schema in docs/far-tail.md) with provenance
// and every parameter as root attributes.
void write_tail_estimate(const std::string& path, const std::string& program, const TailSamplerParameters& parameters,
                         const TailEstimate& estimate, double time, std::int64_t half_window,
                         const std::string& observable_name);

}  // namespace shockgas
