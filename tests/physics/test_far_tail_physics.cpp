// SPDX-License-Identifier: GPL-3.0-or-later
// The sticky gas's far tail at quick fidelity: the sampler (shockgas-tail's
// library) at t = 100 gives Phi on the exact curve 10^-34 deep and the tail
// exponent gamma = 3 (docs/far-tail.md). About 20 s of CPU.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "shockgas/analysis/far_tail.hpp"
#include "shockgas/tail/tail_sampler.hpp"

namespace {

// ln Phi of the exact sticky-gas solution (python/exact_ballistic.py, EB8,
// D = 1/3) at the centres of the output bins [4.00, 4.02] and [5.00, 5.02].
constexpr double exact_log_phi_at_4_01 = -44.40386419;  // Phi = 5.2e-20
constexpr double exact_log_phi_at_5_01 = -78.18179999;  // Phi = 1.1e-34

TEST(FarTailPhysics, PhiOnTheExactCurveAndGammaThreeAtTimeOneHundred) {
    constexpr double t = 100.0;
    constexpr std::int64_t half_window = 300;  // > 2.5 V t for z <= 6 (V t = z t^(2/3) = 129 at z = 6)
    constexpr double z_reach = 6.0, z_step = 0.25;
    shockgas::TaggedClusterVelocity tagged(half_window, t);
    shockgas::TailSamplerParameters p;
    p.sites = static_cast<std::int64_t>(tagged.sites());
    p.focus_begin = half_window - 250;
    p.focus_end = half_window + 251;
    p.block_max = 150;
    p.biases = shockgas::tail_bias_ladder(z_reach, z_step);
    for (double z : shockgas::tail_ladder_targets(z_reach, z_step)) {
        const auto mean = shockgas::tagged_cluster_instanton(z, t, half_window);
        p.start_mean.insert(p.start_mean.end(), mean.begin(), mean.end());
    }
    p.steps_per_bias = 30000;
    p.burn_in_steps = 6000;
    p.chains = 4;
    p.seed = 2026;
    p.fine_bins_per_output_bin = 20;  // bins of 0.02
    const auto estimate =
        shockgas::sample_far_tail(p, [&tagged](std::span<const double> v) { return tagged(v); });
    shockgas::write_tail_estimate("far_tail_t100.h5", "test_far_tail_physics", p, estimate, t, half_window,
                                  "tagged_cluster_velocity");
    const auto tail = shockgas::analysis::read_far_tail("far_tail_t100.h5");

    // Phi at two deep points against the exact curve. Chains this short (for
    // CI's time) are not yet equilibrated that deep: with these very options
    // and seed (the quick fig_tail's) Phi / exact is 0.46 at z = 4 and 0.35
    // at z = 5, where chains 13 times longer give 0.99 and 0.93
    // (docs/measurements.md, "Longer chains"). The allowance ln 3 covers that
    // shortfall, and 4 jackknife sigmas (4 chains: sigma itself uncertain by
    // ~40%) the noise. A wrong scaling (z = V t^0.3) or a broken reweighting
    // is off by decades here.
    constexpr double short_chain_allowance = 1.0986;  // ln 3
    constexpr double allowed_sigmas = 4.0;
    for (const auto& [z, exact] : {std::pair{4.01, exact_log_phi_at_4_01}, std::pair{5.01, exact_log_phi_at_5_01}}) {
        std::size_t i = 0;
        while (i + 1 < tail.z.size() && tail.z[i] < z - 1e-9) ++i;
        ASSERT_NEAR(tail.z[i], z, 1e-9);
        ASSERT_TRUE(std::isfinite(tail.log_phi_sigma[i])) << "z = " << z;
        EXPECT_NEAR(tail.log_phi[i], exact, short_chain_allowance + allowed_sigmas * tail.log_phi_sigma[i])
            << "z = " << z;
    }
    // Deepest measured point is beyond 10^-30.
    double deepest = 0.0;
    for (std::size_t i = 0; i < tail.z.size(); ++i)
        if (std::isfinite(tail.log_phi_sigma[i])) deepest = std::min(deepest, tail.log_phi[i]);
    EXPECT_LT(deepest, std::log(1e-30));

    // gamma from ln Phi = c - 2 ln z - a z^gamma - b z (b from EB9) over
    // z in [2, 5.5]. The target is 3 +- 0.1; the fit's own bias on
    // the exact Phi is 0.001 over this window. So gamma must lie within
    // 0.1 of 3, and its error (jackknife (+) window) must resolve that.
    constexpr double gamma_target_tolerance = 0.1;
    const auto gamma = shockgas::analysis::estimate_tail_exponent(tail, 2.0, 5.5);
    std::printf("gamma = %.3f +- %.3f (stat) +- %.3f (window), a = %.3f\n", gamma.gamma.value, gamma.gamma.sigma,
                gamma.window_systematic.value, gamma.fit.a);
    EXPECT_NEAR(gamma.gamma.value, 3.0, gamma_target_tolerance);
    EXPECT_LT(gamma.total_sigma(), gamma_target_tolerance);
}

}  // namespace
