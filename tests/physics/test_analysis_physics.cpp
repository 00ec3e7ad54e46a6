// SPDX-License-Identifier: GPL-3.0-or-later
// The paper's numbers from quick-fidelity simulations (fixed seeds), run
// through shockgas::run_ensemble and the analysis library. Every tolerance is
// k = 3 standard errors of the estimate (jackknife over realizations), unless
// a comment names another source. The measured values and the runtime are in
// analysis/README.md ("Physics results").
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"
#include "shockgas/run/ensemble.hpp"

namespace sa = shockgas::analysis;

namespace {

// Agreement with theory within k statistical standard errors: 3 sigma is a
// 0.3% false-alarm rate for a Gaussian estimate.
constexpr double k_sigma = 3.0;

// Fig. 1 setting scaled down: N = 10^5, 10 realizations, delta = 10^-2. The
// sub-threshold mechanism is sticky (the paper's Fig. 2 shows it gives the
// same T(t) as elastic; the elastic one costs ~10^4 collisions per particle by
// t = 10^4 at r = 0.9, beyond the CI budget).
shockgas::SimulationParameters fig1_parameters(double restitution) {
    shockgas::SimulationParameters p;
    p.particles = 100000;
    p.collision.restitution = restitution;
    p.collision.velocity_threshold = 1e-2;
    p.collision.subthreshold = shockgas::Subthreshold::sticky;
    p.t_max = 1e5;
    p.samples_per_decade = 10;
    p.realizations = 10;
    p.seed = 20240601;
    p.threads = 2;
    p.histogram_times = {1e3, 1e4};
    p.snapshot_times = {1e4};
    return p;
}

const shockgas::EnsembleResult& fig1_run(double restitution) {
    static std::map<double, shockgas::EnsembleResult> runs;
    auto found = runs.find(restitution);
    if (found == runs.end())
        found = runs.emplace(restitution, shockgas::run_ensemble(fig1_parameters(restitution), nullptr)).first;
    return found->second;
}

void expect_two_thirds(double restitution) {
    const auto& run = fig1_run(restitution);
    const auto history = sa::TemperatureHistory::from(run);
    const auto parameters = fig1_parameters(restitution);
    const auto window = sa::automatic_decay_window(restitution, parameters.collision.velocity_threshold,
                                                   static_cast<double>(parameters.particles), history.time.back());
    const auto fit = sa::fit_temperature_decay(history, window.t_lo, window.t_hi);
    // Sticky-gas exponent 2/3 (Eq. 3; Carnevale, Pomeau & Young 1990), paper: 0.67, 0.67, 0.66.
    constexpr double expected = 2.0 / 3.0;
    // Statistical (jackknife) and window-choice (window_systematic) errors in
    // quadrature: at this N the local exponent wanders by ~0.01 between decades
    // (corrections to scaling), more than the jackknife error (README, "Decay").
    const auto window_spread = sa::window_systematic(history, fit.t_lo, fit.t_hi);
    ASSERT_TRUE(window_spread.known()) << window_spread.note;
    const double systematic = window_spread.value;
    const double total_sigma = std::hypot(fit.exponent_sigma, systematic);
    std::printf("r = %g: alpha = %.4f +- %.4f (stat) +- %.4f (window), chi2/dof %.2f over [%g, %g]\n", restitution,
                fit.exponent, fit.exponent_sigma, systematic, fit.chi2_per_dof, fit.t_lo, fit.t_hi);
    EXPECT_NEAR(fit.exponent, expected, k_sigma * total_sigma);
}

}  // namespace

TEST(AnalysisPhysics, DecayExponentStickyGas) { expect_two_thirds(0.0); }
TEST(AnalysisPhysics, DecayExponentModeratelyInelastic) { expect_two_thirds(0.5); }
TEST(AnalysisPhysics, DecayExponentWeaklyInelastic) { expect_two_thirds(0.9); }

TEST(AnalysisPhysics, StickTimeScalesAsEpsToMinusThreeHalves) {
    // eps = 0.05, 0.025, 0.0125 (r = 0.9, 0.95, 0.975): t_stick ~ 10^2 .. 10^3.
    std::vector<double> inelasticity;
    std::vector<sa::Estimate> t_stick, temperature;
    for (double restitution : {0.9, 0.95, 0.975}) {
        shockgas::SimulationParameters p;
        p.particles = 20000;
        p.collision.restitution = restitution;
        p.collision.velocity_threshold = 1e-2;
        p.collision.subthreshold = shockgas::Subthreshold::sticky;
        p.t_max = 2e4;
        p.samples_per_decade = 20;  // resolves the crossovers to ~6% in t before interpolation
        p.realizations = 10;
        p.seed = 777;
        p.threads = 2;
        const auto crossovers = sa::find_crossovers(sa::TemperatureHistory::from(shockgas::run_ensemble(p, nullptr)));
        inelasticity.push_back((1.0 - restitution) / 2.0);
        t_stick.push_back(crossovers.t_stick);
        temperature.push_back(crossovers.temperature_at_stick);
    }
    auto power_law = [&](const std::vector<sa::Estimate>& values) {
        std::vector<double> value, sigma;
        for (const auto& v : values) {
            value.push_back(v.value);
            sigma.push_back(v.sigma);
        }
        return sa::fit_power_law(inelasticity, value, sigma);
    };
    const auto stick = power_law(t_stick);
    const auto at_stick = power_law(temperature);
    std::printf("t_stick ~ eps^(%.4f +- %.4f), T(t_stick) ~ eps^(%.4f +- %.4f)\n", stick.slope, stick.slope_sigma(),
                at_stick.slope, at_stick.slope_sigma());
    // Eq. (3): t_stick ~ eps^(-3/2), T(t_stick) ~ eps.
    EXPECT_NEAR(stick.slope, -1.5, k_sigma * stick.slope_sigma());
    EXPECT_NEAR(at_stick.slope, 1.0, k_sigma * at_stick.slope_sigma());
}

TEST(AnalysisPhysics, VelocityDistributionCollapsesWithOneThird) {
    auto histograms = sa::histograms_from(fig1_run(0.0), "r=0");
    const auto weakly = sa::histograms_from(fig1_run(0.9), "r=0.9");
    histograms.insert(histograms.end(), weakly.begin(), weakly.end());
    const auto collapse = sa::fit_scaling_collapse(histograms);
    std::printf("beta = %.4f +- %.4f, D(1/3) = %.3g, max |dG| = %.3g\n", collapse.beta.value, collapse.beta.sigma,
                collapse.distance_at_one_third, collapse.max_deviation_at_one_third);
    EXPECT_NEAR(collapse.beta.value, 1.0 / 3.0, k_sigma * collapse.beta.sigma);  // Eq. (4)
    for (const auto& h : histograms) {
        const auto kurtosis = sa::velocity_kurtosis(h);
        std::printf("%s: kurtosis %.3f +- %.3f\n", h.label.c_str(), kurtosis.value, kurtosis.sigma);
        // "Deviates only slightly from a Gaussian" (text after Eq. 6): not a
        // statistical bound but the paper's qualitative claim, read as a kurtosis
        // within 5% of the Gaussian 3 plus the statistical error.
        constexpr double slight_deviation = 0.15;
        EXPECT_NEAR(kurtosis.value, 3.0, slight_deviation + k_sigma * kurtosis.sigma);
    }
}

TEST(AnalysisPhysics, TailExponentAtQuickFidelity) {
    // Sticky gas, 100 realizations of N = 10^5 at t = 100: 10^7 particles in the histogram.
    shockgas::SimulationParameters p;
    p.particles = 100000;
    p.collision.restitution = 0.0;
    p.t_max = 100;
    p.realizations = 100;
    p.seed = 4242;
    p.threads = 2;
    p.histogram_times = {100};
    const auto histograms = sa::histograms_from(shockgas::run_ensemble(p, nullptr));
    ASSERT_EQ(histograms.size(), 1u);
    const auto tail = sa::fit_tail(histograms.front());
    std::printf("gamma = %.3f +- %.3f (Delta chi2 = 1: %.3f), chi2/dof %.2f, %zu bins, |z|/rms in [%.2f, %.2f]\n",
                tail.gamma.value, tail.gamma.sigma, tail.gamma_fit_sigma, tail.chi2_per_dof, tail.bins, tail.z_lo,
                tail.z_hi);
    // What holds at this fidelity: the tail is no fatter than Gaussian.
    EXPECT_GT(tail.gamma.value, 2.0 - k_sigma * tail.gamma.sigma);
    // What the paper claims (Eq. 6, gamma = 3) is NOT reached: within 4.4 rms
    // the tail is Gaussian (gamma = 2.0 within 1-2 sigma); the cubic term of
    // Frachebourg's exact Phi dominates only further out (README, "Tail").
    // This records the shortfall so that a change in it is noticed.
    EXPECT_LT(tail.gamma.value, 3.0 - k_sigma * tail.gamma.sigma);
}

TEST(AnalysisPhysics, SawtoothSegmentsHaveSlopeOneOverT) {
    const auto& run = fig1_run(0.9);
    const auto snapshots = sa::snapshots_from(run, static_cast<double>(fig1_parameters(0.9).particles));
    const auto summary = sa::summarize_shocks(snapshots);
    std::printf("t = %g: %.1f +- %.1f shocks vs N t^-2/3 = %.1f; slope x t = %.3f +- %.3f over %zu segments\n",
                summary.time, summary.shocks.value, summary.shocks.sigma, summary.expected_shocks,
                summary.slope_times_t.value, summary.slope_times_t.sigma, summary.segments);
    std::printf("density-corrected slope x t / (1 - rho) = %.3f +- %.3f\n", summary.density_corrected_slope_times_t.value,
                summary.density_corrected_slope_times_t.sigma);
    // Eq. (7): v = (x - q)/t; for the particles of a segment of density rho the
    // slope is (1 - rho)/t, so slope t / (1 - rho) = 1.
    EXPECT_NEAR(summary.density_corrected_slope_times_t.value, 1.0,
                k_sigma * summary.density_corrected_slope_times_t.sigma);
    // Shock count "consistent with N t^(-2/3)" (Fig. 5): an order-of-magnitude
    // statement; we require the count within a factor 3 of it.
    constexpr double order_of_magnitude = 3.0;
    EXPECT_GT(summary.shocks.value, summary.expected_shocks / order_of_magnitude);
    EXPECT_LT(summary.shocks.value, summary.expected_shocks * order_of_magnitude);
}
