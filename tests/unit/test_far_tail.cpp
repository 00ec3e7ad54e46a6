// SPDX-License-Identifier: GPL-3.0-or-later
// The tail-exponent estimator (shockgas/analysis/far_tail.hpp) on synthetic
// tails of known gamma with chain-by-chain noise, as the sampler delivers them.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/far_tail.hpp"
#include "shockgas/io/h5.hpp"
#include "../test_support.hpp"

namespace {

using shockgas::analysis::FarTail;

// ln Phi = c - 2 ln z - a z^gamma - b z on z in [1.5, 6) (bins of 0.02), the
// sampler's reach, with the exact tail's a = 1/2, b = 2.676 (EB9) when gamma
// = 3. Each of `chains` chains adds independent Gaussian noise of sigma
// per_chain_sigma to ln Phi (the sampler's chains are independent); the
// estimate is the chains' mean, and leave-one-out means feed the jackknife.
FarTail synthetic_tail(double gamma, double a, double b, std::size_t chains, double per_chain_sigma,
                       std::uint64_t seed) {
    std::mt19937_64 engine(seed);
    std::normal_distribution<double> noise(0.0, per_chain_sigma);
    FarTail tail;
    std::vector<std::vector<double>> per_chain(chains);
    for (double z = 1.51; z < 6.0; z += 0.02) {
        tail.z.push_back(z);
        const double truth = -1.0 - 2.0 * std::log(z) - a * std::pow(z, gamma) - b * z;
        for (auto& chain : per_chain) chain.push_back(truth + noise(engine));
    }
    const double n = static_cast<double>(chains);
    tail.log_phi.assign(tail.z.size(), 0.0);
    for (const auto& chain : per_chain)
        for (std::size_t i = 0; i < tail.z.size(); ++i) tail.log_phi[i] += chain[i] / n;
    tail.log_phi_sigma.assign(tail.z.size(), per_chain_sigma / std::sqrt(n));
    for (std::size_t c = 0; c < chains; ++c) {
        std::vector<double> without(tail.z.size());
        for (std::size_t i = 0; i < tail.z.size(); ++i) without[i] = (tail.log_phi[i] * n - per_chain[c][i]) / (n - 1.0);
        tail.log_phi_leave_one_chain_out.push_back(without);
    }
    return tail;
}

TEST(TailExponent, KnownGammaRecoveredWithinItsJackknifeError) {
    // 6 chains and sigma(ln Phi) = 0.2 per bin: like the sampler's tail at
    // z > 2. The jackknife over 6 chains estimates sigma to ~30%; 4 sigma
    // keeps a right estimator from failing by chance and catches a bias of
    // ~0.1 in gamma (the target accuracy).
    constexpr double allowed_sigmas = 4.0;
    for (double gamma : {3.0, 2.5, 3.5}) {
        const FarTail tail = synthetic_tail(gamma, 0.5, 2.676, 6, 0.2 * std::sqrt(6.0), 17);
        // b fixed at its true value (the default), and b fitted.
        const auto fixed = shockgas::analysis::estimate_tail_exponent(tail, 2.0, 5.8, 0.25, 2.676);
        EXPECT_NEAR(fixed.gamma.value, gamma, allowed_sigmas * fixed.gamma.sigma) << "gamma = " << gamma;
        EXPECT_GT(fixed.gamma.sigma, 0.0);
        EXPECT_LT(fixed.gamma.sigma, 0.05);  // the data determine gamma to better than the target
        EXPECT_GE(fixed.window_systematic.value, 0.0);
        const auto free = shockgas::analysis::estimate_tail_exponent(tail, 2.0, 5.8, 0.25, std::nullopt);
        EXPECT_NEAR(free.gamma.value, gamma, allowed_sigmas * free.gamma.sigma) << "gamma = " << gamma;
        EXPECT_LT(free.gamma.sigma, 0.1);
    }
}

// sigma(ln Phi) as the sampler gives it: the delete-one-chain jackknife spread
// of the leave-one-out tables (sim/tail/src/tail_sampler.cpp), an estimate with
// chains - 1 degrees of freedom instead of the true per-bin error.
void take_sampler_sigma(FarTail& tail) {
    const auto& tables = tail.log_phi_leave_one_chain_out;
    const double n = static_cast<double>(tables.size());
    for (std::size_t i = 0; i < tail.z.size(); ++i) {
        double mean = 0.0, squares = 0.0;
        for (const auto& table : tables) mean += table[i] / n;
        for (const auto& table : tables) squares += (table[i] - mean) * (table[i] - mean);
        tail.log_phi_sigma[i] = std::sqrt((n - 1.0) / n * squares);
    }
}

// With 4 chains the per-bin sigmas are as noisy as ln Phi: weighing by them
// bin by bin, with the full estimate's weights in every replica, the one-sigma
// coverage of gamma is 0.21 over these trials (sigma 0.0036 for a scatter of
// 0.0149). Pooled sigmas and the replicas' own weights give 0.60.
TEST(TailExponent, JackknifeCoverageWithFourChains) {
    constexpr int trials = 300;
    constexpr double student_coverage = 0.6090;  // P(|t_3| < 1): 4 chains, 3 dof (expect_jackknife_coverage)
    int inside = 0;
    for (int trial = 0; trial < trials; ++trial) {
        FarTail tail = synthetic_tail(3.0, 0.5, 2.676, 4, 0.5, 1000 + static_cast<std::uint64_t>(trial));
        take_sampler_sigma(tail);
        const auto gamma = shockgas::analysis::estimate_tail_exponent(tail, 2.0, 5.8, 0.25, 2.676).gamma;
        if (std::abs(gamma.value - 3.0) <= gamma.sigma) ++inside;
    }
    shockgas::testing::expect_jackknife_coverage(inside, trials, student_coverage, "far-tail gamma, 4 chains");
}

// Two chains: a replica keeps one, with no spread to weigh by; gamma stands, its sigma is n/a.
TEST(TailExponent, TwoChainsHaveGammaWithoutJackknifeSigma) {
    FarTail tail = synthetic_tail(3.0, 0.5, 2.676, 2, 0.2, 23);
    take_sampler_sigma(tail);
    const auto result = shockgas::analysis::estimate_tail_exponent(tail, 2.0, 5.8, 0.25, 2.676);
    EXPECT_NEAR(result.gamma.value, 3.0, 0.1);  // the target accuracy; its fit width is ~0.01
    EXPECT_TRUE(std::isnan(result.gamma.sigma));
    EXPECT_NE(result.gamma.note.find("two chains"), std::string::npos) << result.gamma.note;
}

TEST(TailExponent, ExactTailWithoutNoiseGivesGammaToRounding) {
    // No noise: chi2(gamma) is 0 at the true gamma, so the fit returns it to
    // the golden-section tolerance (1e-7 relative).
    const FarTail tail = synthetic_tail(3.0, 0.5, 2.676, 2, 0.0, 1);
    std::vector<double> sigma(tail.z.size(), 0.1);
    const auto fit = shockgas::analysis::fit_tail_exponent(tail.z, tail.log_phi, sigma, 2.0, 5.8, std::nullopt);
    constexpr double minimiser_tolerance = 1e-5;
    EXPECT_NEAR(fit.gamma, 3.0, minimiser_tolerance);
    EXPECT_NEAR(fit.a, 0.5, 1e-4);
    EXPECT_NEAR(fit.b, 2.676, 1e-3);
}

TEST(TailExponent, ShortTablesInAFileAreRefusedByName) {
    // A log_phi shorter than z would be read past its end and give gamma = 1.000.
    const auto path = (std::filesystem::temp_directory_path() / "shockgas_far_tail_short.h5").string();
    shockgas::h5::write_atomically(path, [](shockgas::h5::Group& root) {
        root.set_attribute("kind", "far_tail");
        root.set_attribute("time", 100.0);
        std::vector<double> z, log_phi, sigma(40, 0.1), leave_one_out;
        for (int i = 0; i < 40; ++i) z.push_back(2.0 + 0.1 * i);
        for (int i = 0; i < 20; ++i) log_phi.push_back(-z[static_cast<std::size_t>(i)] * 3.0);
        for (int c = 0; c < 2; ++c)
            for (double value : z) leave_one_out.push_back(-3.0 * value);
        root.write("z", z);
        root.write("log_phi", log_phi);
        root.write("log_phi_sigma", sigma);
        root.write("log_phi_leave_one_chain_out", leave_one_out, {2, 40});
    });
    try {
        shockgas::analysis::read_far_tail(path);
        ADD_FAILURE() << "a short log_phi must be refused";
    } catch (const shockgas::h5::Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("/log_phi holds 20 values but /z holds 40"), std::string::npos) << message;
        EXPECT_NE(message.find(path), std::string::npos) << message;
    }
    std::filesystem::remove(path);
}

}  // namespace
