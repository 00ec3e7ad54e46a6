// SPDX-License-Identifier: GPL-3.0-or-later
// The far-tail sampler (shockgas/tail/tail_sampler.hpp): the weighted-histogram
// combination on a law known in closed form down to 10^-30 and below, and the
// tagged-cluster sampler against plain sampling where a histogram reaches.
#include <atomic>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "shockgas/tail/tail_sampler.hpp"

namespace {

// ln of the probability that N(0, variance) lies in [lo, hi], divided by
// (hi - lo): the exact bin average the sampler estimates (no bin-centre error).
double log_gaussian_bin_density(double lo, double hi, double variance) {
    const double s = std::sqrt(2.0 * variance);
    // Upper tail by erfc, exact to 10^-300: P = (erfc(lo/s) - erfc(hi/s)) / 2.
    const double upper = std::erfc(lo / s), lower = std::erfc(hi / s);
    return std::log(0.5 * (upper - lower)) - std::log(hi - lo);
}

// The ladder settings of the tests against laws known in closed form or
// plain sampling: 8 chains (their jackknife gives the sigmas the 4-sigma
// checks use) of 10^4 steps per bias, a focus on the sites the observable reads.
shockgas::TailSamplerParameters exact_law_ladder(std::int64_t sites, std::int64_t focus_begin, std::int64_t focus_end,
                                                 std::uint64_t seed, double z_min, double z_max) {
    shockgas::TailSamplerParameters p;
    p.sites = sites;
    p.focus_begin = focus_begin;
    p.focus_end = focus_end;
    p.focus_probability = 0.9;
    p.steps_per_bias = 10000;
    p.burn_in_steps = 1000;
    p.chains = 8;
    p.seed = seed;
    p.z_min = z_min;
    p.z_max = z_max;
    return p;
}

TEST(TailSampler, MeanOfGaussiansRecoveredBelowTenToTheMinusThirty) {
    // Observable: the mean of the 4 central velocities of an 8-site window of
    // i.i.d. N(0, 1/3): exactly N(0, 1/12). Its density is 10^-30 at
    // S = 3.43 (11.9 sigma) and 10^-36 at 3.75; the ladder reaches 4.
    constexpr std::int64_t averaged = 4;
    constexpr double variance = 1.0 / (3.0 * averaged);
    auto p = exact_law_ladder(8, 2, 6, 11, -2.0, 4.6);
    // Gaussian tilt: exp(beta S) moves the law's mean to beta * variance, so
    // the ladder beta_k = S_k / variance puts chain k at S_k; steps of 0.2 are
    // below the width sqrt(1/12) = 0.29, so neighbours overlap.
    p.biases.push_back(0.0);
    for (double s = 0.2; s <= 4.0 + 1e-9; s += 0.2) p.biases.push_back(s / variance);
    const shockgas::WindowObservable mean_of_four = [](std::span<const double> v) {
        return (v[2] + v[3] + v[4] + v[5]) / static_cast<double>(averaged);
    };
    const auto estimate = shockgas::sample_far_tail(p, mean_of_four);

    // Every estimate is compared with the exact bin average. The jackknife
    // over 8 chains estimates sigma itself to ~25%, and a handful of points
    // are tested: 4 sigma keeps a correct sampler from failing by chance
    // (Student t, 7 dof: p ~ 0.005 per point) and still catches an error of a
    // factor e^(4 sigma) ~ 1.5 at 10^-30.
    constexpr double allowed_sigmas = 4.0;
    const double width = estimate.z[1] - estimate.z[0];
    std::size_t deep_points = 0;
    double deepest = 0.0;
    for (std::size_t i = 0; i < estimate.z.size(); ++i) {
        if (estimate.samples[i] < 50.0 || !std::isfinite(estimate.log_density_sigma[i])) continue;
        const double exact = log_gaussian_bin_density(estimate.z[i] - width / 2, estimate.z[i] + width / 2, variance);
        // Check every 0.25 in S; the bins between share the chains' samples.
        if (std::fmod(i, 25.0) != 0.0) continue;
        EXPECT_NEAR(estimate.log_density[i], exact, allowed_sigmas * estimate.log_density_sigma[i])
            << "S = " << estimate.z[i];
        if (exact < std::log(1e-30)) ++deep_points;
        deepest = std::min(deepest, estimate.log_density[i]);
    }
    EXPECT_GE(deep_points, 2u);
    EXPECT_LT(deepest, std::log(1e-30));
    // The pieces overlap (the combination needs it) and the chains moved.
    for (std::size_t k = 0; k + 1 < estimate.biases.size(); ++k) EXPECT_GT(estimate.overlap_with_next[k], 0.2);
    for (double a : estimate.acceptance) EXPECT_GT(a, 0.1);
}

// ln of the probability that the mean of 4 velocities uniform on [-1, 1] lies
// in [lo, hi], divided by (hi - lo). With u = (v + 1)/2 the sum of the four u
// is Irwin-Hall: CDF F(x) = (1/24) sum_{k <= x} (-1)^k C(4, k) (x - k)^4, and
// the mean S maps to x = 2 (S + 1). The upper tail is taken as F(4 - x) (the
// law is symmetric), exact near the edge where 1 - F would cancel.
double log_mean_of_four_uniforms_bin_density(double lo, double hi) {
    const auto cdf = [](double x) {
        constexpr double binomial[5] = {1, 4, 6, 4, 1};
        double sum = 0.0;
        for (int k = 0; k <= 4 && k <= x; ++k) sum += (k % 2 ? -1.0 : 1.0) * binomial[k] * std::pow(x - k, 4);
        return sum / 24.0;
    };
    const double x_lo = 2.0 * (lo + 1.0), x_hi = 2.0 * (hi + 1.0);
    const double probability = x_lo >= 2.0 ? cdf(4.0 - x_lo) - cdf(4.0 - x_hi) : cdf(x_hi) - cdf(x_lo);
    return std::log(probability) - std::log(hi - lo);
}

TEST(TailSampler, MeanOfUniformsRecoveredNearTheLawsEdge) {
    // The uniform law's chains move latent Gaussians mapped to velocities by
    // erf (tail_sampler.cpp); any error in that map changes the law. The mean
    // S of 4 uniform velocities has the exact density above, falling as
    // (1 - S)^3 at the edge: 2.7e-6 at 1 - S = 0.01. An exponential bias
    // e^(beta S) centres the tilted law at 1 - S ~ 4 / beta, so the ladder
    // beta = 4 / y for y from 1.2 down to 0.01 (ratio 1.4, the tilted law's
    // relative width 1/2) reaches the edge with overlapping neighbours.
    auto p = exact_law_ladder(6, 1, 5, 13, -1.0, 1.0);
    p.law = shockgas::VelocityLaw::uniform;
    p.biases.push_back(0.0);
    for (double y = 1.2; y >= 0.01; y /= 1.4) p.biases.push_back(4.0 / y);
    // WHAM's bins must be narrow enough that e^(beta S) varies little across
    // one: beta = 400 at the deepest chain, so 1e-4 (4%).
    p.fine_bin_width = 1e-4;
    p.fine_bins_per_output_bin = 50;  // output bins of 0.005
    const shockgas::WindowObservable mean_of_four = [](std::span<const double> v) {
        for (std::size_t i = 1; i < 5; ++i)
            if (!(std::abs(v[i]) <= 1.0)) throw std::logic_error("a velocity left [-1, 1]");
        return (v[1] + v[2] + v[3] + v[4]) / 4.0;
    };
    const auto estimate = shockgas::sample_far_tail(p, mean_of_four);
    // As in MeanOfGaussiansRecoveredBelowTenToTheMinusThirty: the jackknife
    // over 8 chains (Student t, 7 dof) and a handful of points; 4 sigma fails
    // a correct sampler with p ~ 0.005 per point; a map whose scale is off
    // by 1% fails it (the bin at S = 0.9925 is out).
    constexpr double allowed_sigmas = 4.0;
    const double width = estimate.z[1] - estimate.z[0];
    std::size_t deep_points = 0, compared = 0;
    for (std::size_t i = 0; i < estimate.z.size(); ++i) {
        const double lo = estimate.z[i] - width / 2, hi = estimate.z[i] + width / 2;
        if (lo < 0.0 || hi > 0.995 || estimate.samples[i] < 50.0 || !std::isfinite(estimate.log_density_sigma[i]))
            continue;
        if (i % 10 != 0 && hi < 0.97) continue;  // every 0.05 in S, every bin near the edge
        EXPECT_NEAR(estimate.log_density[i], log_mean_of_four_uniforms_bin_density(lo, hi),
                    allowed_sigmas * estimate.log_density_sigma[i])
            << "S = " << estimate.z[i];
        ++compared;
        if (log_mean_of_four_uniforms_bin_density(lo, hi) < std::log(1e-5)) ++deep_points;
    }
    EXPECT_GE(compared, 20u);
    EXPECT_GE(deep_points, 2u);
    for (double a : estimate.acceptance) EXPECT_GT(a, 0.1);
}

TEST(TailSampler, WhamGivesBackAKnownLawFromExactHistograms) {
    // Histograms without noise: chain k's expected counts N_k P_b
    // exp(beta_k z_b - F_k) for a discretized Gaussian. The equations must
    // return P_b to rounding, across 40 decades.
    std::vector<double> centres, log_p;
    for (double z = -3.0; z < 12.0; z += 0.05) {
        centres.push_back(z);
        log_p.push_back(-z * z / 2.0);
    }
    const double norm = std::log(std::accumulate(log_p.begin(), log_p.end(), 0.0,
                                                 [](double s, double l) { return s + std::exp(l); }));
    for (double& l : log_p) l -= norm;
    const std::vector<double> biases{0.0, 2.0, 4.0, 6.0, 8.0, 10.0};
    std::vector<double> histograms, samples(biases.size(), 1e6);
    for (double beta : biases) {
        double log_z = -INFINITY;
        for (std::size_t b = 0; b < centres.size(); ++b) log_z = std::max(log_z, log_p[b] + beta * centres[b]);
        double partition = 0.0;
        for (std::size_t b = 0; b < centres.size(); ++b) partition += std::exp(log_p[b] + beta * centres[b] - log_z);
        for (std::size_t b = 0; b < centres.size(); ++b) {
            const double expected = 1e6 * std::exp(log_p[b] + beta * centres[b] - log_z) / partition;
            histograms.push_back(expected >= 1e-300 ? expected : 0.0);
        }
    }
    const auto recovered = shockgas::wham_log_probability(histograms, samples, biases, centres);
    // The iteration stops at |dF| < 1e-10; the answer carries that error.
    constexpr double iteration_tolerance = 1e-8;
    for (std::size_t b = 0; b < centres.size(); ++b) {
        if (centres[b] >= 11.0) continue;
        EXPECT_NEAR(recovered[b], log_p[b], iteration_tolerance) << "z = " << centres[b];
    }
}

// t = 100, 200 particles each side of the tag (the cluster scale is
// (t^2/3)^(1/3) = 15 particles, a fast cluster moves z t^(2/3) ~ 60).
// Plain sampling: i.i.d. windows of the given law, histogram of z. Sampler:
// the ladder to z = 2.5. They must agree bin by bin where the plain histogram
// has >= 100 counts (Phi >~ 10^-2) and z > -1.
void expect_tagged_cluster_agrees_with_plain_sampling(shockgas::VelocityLaw law) {
    constexpr std::int64_t half_window = 200;
    constexpr double t = 100.0;
    shockgas::TaggedClusterVelocity tagged(half_window, t);
    constexpr std::size_t plain_samples = 100000;
    constexpr double z_min = -3.0, bin = 0.1;
    std::vector<double> plain(60, 0.0), velocity(tagged.sites());
    std::mt19937_64 engine(5);
    std::normal_distribution<double> gaussian(0.0, std::sqrt(1.0 / 3.0));
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (std::size_t s = 0; s < plain_samples; ++s) {
        for (double& v : velocity) v = law == shockgas::VelocityLaw::gaussian ? gaussian(engine) : uniform(engine);
        const double z = tagged(velocity);
        const double position = (z - z_min) / bin;
        if (position >= 0 && position < 60) plain[static_cast<std::size_t>(position)] += 1.0;
    }
    auto p = exact_law_ladder(static_cast<std::int64_t>(tagged.sites()), half_window - 80, half_window + 81, 3,
                              z_min, 3.0);
    p.focus_probability = 0.8;  // the defaults this test was set against
    p.chains = 6;
    p.biases = shockgas::tail_bias_ladder(2.5, 0.25);
    p.law = law;
    p.fine_bin_width = 1e-3;
    p.fine_bins_per_output_bin = 100;  // output bins of 0.1, as the plain histogram
    const auto estimate =
        shockgas::sample_far_tail(p, [&tagged](std::span<const double> v) { return tagged(v); });
    // Plain counts are Poisson; the sampler's sigma is its jackknife. 4
    // combined sigmas over ~40 bins: a correct sampler fails with p ~ 0.01.
    constexpr double allowed_sigmas = 4.0;
    std::size_t compared = 0;
    for (std::size_t i = 0; i < plain.size(); ++i) {
        // The ladder biases towards z > 0; below z = -1 only the unbiased
        // replica visits, too rarely for a jackknife over chains.
        if (plain[i] < 100.0 || estimate.z[i] < -1.0) continue;
        const double plain_log = std::log(plain[i] / (plain_samples * bin));
        const double plain_sigma = 1.0 / std::sqrt(plain[i]);
        const double sigma = std::hypot(plain_sigma, estimate.log_density_sigma[i]);
        EXPECT_NEAR(estimate.log_density[i], plain_log, allowed_sigmas * sigma) << "z = " << estimate.z[i];
        ++compared;
    }
    EXPECT_GE(compared, 20u);
}

TEST(TailSampler, TaggedClusterAgreesWithPlainSamplingWhereHistogramsReach) {
    expect_tagged_cluster_agrees_with_plain_sampling(shockgas::VelocityLaw::gaussian);
}

TEST(TailSampler, TaggedClusterOfTheUniformLawAgreesWithPlainSampling) {
    expect_tagged_cluster_agrees_with_plain_sampling(shockgas::VelocityLaw::uniform);
}

}  // namespace

namespace {
// A small ladder on the mean of two velocities: enough chains and steps to
// give every bin a value, quick enough to run three times.
shockgas::TailSamplerParameters small_ladder() {
    shockgas::TailSamplerParameters p;
    p.sites = 4;
    p.focus_begin = 1;
    p.focus_end = 3;
    p.biases = {0.0, 3.0, 6.0, 9.0};
    p.steps_per_bias = 2000;
    p.burn_in_steps = 200;
    p.chains = 5;
    p.seed = 3;
    p.z_min = -2.0;
    p.z_max = 3.0;
    return p;
}
shockgas::WindowObservable mean_of_two() {
    return [](std::span<const double> v) { return 0.5 * (v[1] + v[2]); };
}
}  // namespace

TEST(TailSampler, ThreadsChangeNothing) {
    // Each chain has its own random stream and the chains are combined in
    // chain order, so any number of threads gives the one-thread result bit
    // for bit (5 chains on 3 threads: uneven shares, chains taken out of order).
    auto p = small_ladder();
    const auto one = shockgas::sample_far_tail(p, mean_of_two());
    p.threads = 3;
    std::atomic<int> observables_made{0};
    const auto three = shockgas::sample_far_tail(p, shockgas::ObservableFactory([&] {
                                                     ++observables_made;
                                                     return mean_of_two();
                                                 }));
    EXPECT_EQ(observables_made.load(), 3);  // one per thread, not shared
    EXPECT_EQ(one.evaluations, three.evaluations);
    ASSERT_EQ(one.log_density.size(), three.log_density.size());
    for (std::size_t i = 0; i < one.log_density.size(); ++i) {
        if (std::isnan(one.log_density[i])) {
            EXPECT_TRUE(std::isnan(three.log_density[i]));
            continue;
        }
        EXPECT_EQ(one.log_density[i], three.log_density[i]) << "bin " << i;
    }
    EXPECT_EQ(one.leave_one_out, three.leave_one_out);
    EXPECT_GT(three.wall_seconds, 0.0);
}

TEST(TailSampler, AFailingObservableStopsTheRunWithItsError) {
    auto p = small_ladder();
    p.threads = 2;
    std::atomic<std::int64_t> calls{0};
    const auto failing = shockgas::ObservableFactory([&] {
        return shockgas::WindowObservable([&](std::span<const double> v) {
            if (++calls > 5000) throw std::runtime_error("observable failed");
            return v[1];
        });
    });
    EXPECT_THROW(
        {
            try {
                shockgas::sample_far_tail(p, failing);
            } catch (const std::runtime_error& error) {
                EXPECT_STREQ(error.what(), "observable failed");
                throw;
            }
        },
        std::runtime_error);
}
