// Every estimator of the analysis library on synthetic data with a known
// answer: it recovers the answer, and its sigma is calibrated (about 68% of
// independent synthetic samples land within one sigma).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/temperature.hpp"
#include "shockgas/analysis/velocity_distribution.hpp"
#include "shockgas/observables.hpp"

namespace sa = shockgas::analysis;

namespace {

// Coverage of a one-sigma interval for a Gaussian estimator.
constexpr double one_sigma_coverage = 0.6827;
// The coverage fraction of n independent trials has binomial standard error
// sqrt(p (1 - p) / n); we accept 3 of those (a 0.3% false alarm rate).
double coverage_tolerance(int trials) {
    return 3.0 * std::sqrt(one_sigma_coverage * (1.0 - one_sigma_coverage) / trials);
}

}  // namespace

TEST(AnalysisFit, StraightLineExactAndCalibrated) {
    const std::vector<double> x{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    std::vector<double> y(x.size()), sigma(x.size(), 0.5);
    for (std::size_t i = 0; i < x.size(); ++i) y[i] = 1.5 - 0.25 * x[i];
    const auto exact = sa::weighted_linear_fit(x, y, sigma);
    EXPECT_NEAR(exact.slope, -0.25, 1e-12);
    EXPECT_NEAR(exact.intercept, 1.5, 1e-12);
    EXPECT_NEAR(exact.chi2, 0.0, 1e-20);

    std::mt19937_64 random(12345);
    std::normal_distribution<double> noise(0.0, 0.5);
    constexpr int trials = 2000;
    int inside = 0;
    double chi2_sum = 0.0;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<double> noisy(y);
        for (double& value : noisy) value += noise(random);
        const auto fit = sa::weighted_linear_fit(x, noisy, sigma);
        if (std::abs(fit.slope + 0.25) <= fit.slope_sigma()) ++inside;
        chi2_sum += fit.chi2_per_dof();
    }
    std::printf("one-sigma coverage %.3f over %d trials (expected %.3f +- %.3f)\n", static_cast<double>(inside) / trials,
                trials, one_sigma_coverage, coverage_tolerance(trials));
    EXPECT_NEAR(static_cast<double>(inside) / trials, one_sigma_coverage, coverage_tolerance(trials));
    // chi2/dof has mean 1 and variance 2/dof per trial (dof = 8): SE of the mean = sqrt(2/8/trials).
    EXPECT_NEAR(chi2_sum / trials, 1.0, 3.0 * std::sqrt(2.0 / 8.0 / trials));
}

TEST(AnalysisFit, PowerLawRecoversExponent) {
    std::vector<double> x, y, sigma;
    for (int k = 0; k <= 20; ++k) {
        x.push_back(std::pow(10.0, k / 5.0));
        y.push_back(0.21 * std::pow(x.back(), -2.0 / 3.0));
        sigma.push_back(0.01 * y.back());
    }
    const auto fit = sa::fit_power_law(x, y, sigma);
    EXPECT_NEAR(fit.slope, -2.0 / 3.0, 1e-12);
    EXPECT_NEAR(std::exp(fit.intercept), 0.21, 1e-12);
}

TEST(AnalysisFit, JackknifeOfMeanIsStandardError) {
    // For the mean the jackknife sigma equals the textbook standard error exactly.
    const std::vector<double> values{1.0, 2.5, 0.3, 4.0, 2.2, 1.1};
    const auto reference = sa::mean_and_standard_error(values);
    const auto jack = sa::jackknife(values.size(), [&](std::optional<std::size_t> left_out) {
        double sum = 0.0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < values.size(); ++i)
            if (!left_out || *left_out != i) {
                sum += values[i];
                ++count;
            }
        return sum / static_cast<double>(count);
    });
    EXPECT_NEAR(jack.value, reference.value, 1e-14);
    EXPECT_NEAR(jack.sigma, reference.sigma, 1e-14);
}

namespace {

// Synthetic T(t): every realization is C t^-alpha times (1 + a_r + b_r ln(t/10)
// + white noise), so realizations differ in level and slope (as real ones do,
// correlated across times) while the ensemble mean follows t^-alpha.
sa::TemperatureHistory synthetic_history(std::mt19937_64& random, double alpha, std::size_t realizations) {
    std::vector<double> time;
    for (int k = 0; k <= 40; ++k) time.push_back(std::pow(10.0, k / 10.0));
    std::normal_distribution<double> level(0.0, 0.03), slope(0.0, 0.01), white(0.0, 0.005);
    std::vector<double> temperature;
    for (std::size_t r = 0; r < realizations; ++r) {
        const double a = level(random), b = slope(random);
        for (double t : time)
            temperature.push_back(0.2 * std::pow(t, -alpha) * (1.0 + a + b * std::log(t / 10.0) + white(random)));
    }
    return sa::TemperatureHistory::from(time, static_cast<std::int64_t>(realizations), temperature);
}

}  // namespace

TEST(AnalysisDecay, ExponentAndJackknifeCoverage) {
    std::mt19937_64 random(2024);
    constexpr double alpha = 2.0 / 3.0;
    constexpr int trials = 400;
    // R = 20: the jackknife ratio follows Student's t with 19 dof, whose
    // one-sigma coverage 0.670 differs from 0.683 by far less than the tolerance.
    constexpr std::size_t realizations = 20;
    int inside = 0;
    for (int trial = 0; trial < trials; ++trial) {
        const auto history = synthetic_history(random, alpha, realizations);
        const auto fit = sa::fit_temperature_decay(history, 10.0, 1e4);
        if (std::abs(fit.exponent - alpha) <= fit.exponent_sigma) ++inside;
    }
    std::printf("one-sigma coverage %.3f over %d trials (expected %.3f +- %.3f)\n", static_cast<double>(inside) / trials,
                trials, one_sigma_coverage, coverage_tolerance(trials));
    EXPECT_NEAR(static_cast<double>(inside) / trials, one_sigma_coverage, coverage_tolerance(trials));
}

TEST(AnalysisDecay, WindowRuleAndScan) {
    // Eq. (3): r = 0.9 -> eps = 0.05, t_stick = eps^-3/2 = 89.4; t_lo = 10 t_stick.
    const auto window = sa::automatic_decay_window(0.9, 1e-2, 1e6, 1e5);
    EXPECT_NEAR(window.t_lo, 10.0 * std::pow(0.05, -1.5), 1e-9);
    EXPECT_DOUBLE_EQ(window.t_hi, 1e5);  // min(t_last = 1e5, 0.01 N^3/2 = 1e7, delta^-3 = 1e6)
    EXPECT_THROW(sa::automatic_decay_window(0.99, 1e-2, 1e4, 1e3), sa::InsufficientData);
    // A run that collapsed before the window: the message gives its last
    // sample time as such (not as the time of the collapse, which lies after).
    try {
        sa::automatic_decay_window(0.5, 0.0, 100, 7.94328, {}, "collapsed");
        ADD_FAILURE() << "an empty window must throw";
    } catch (const sa::InsufficientData& error) {
        EXPECT_NE(std::string(error.what()).find("last sample is t = 7.94328"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("stopped at inelastic collapse"), std::string::npos) << error.what();
    }
    // The sticky gas (eps = 1/2, eps^-3/2 = 2.8) still starts at t = 100, after its own transient.
    EXPECT_DOUBLE_EQ(sa::automatic_decay_window(0.0, 1e-2, 1e6, 1e5).t_lo, 100.0);
    std::mt19937_64 random(7);
    const auto history = synthetic_history(random, 2.0 / 3.0, 10);
    const auto scan = sa::scan_decay_windows(history, 1.0, 0.5);
    ASSERT_EQ(scan.size(), 7u);  // windows starting at 10^0, 10^0.5, ..., 10^3
    for (const auto& w : scan) EXPECT_NEAR(w.exponent, 2.0 / 3.0, 5.0 * w.exponent_sigma);
}

TEST(AnalysisCrossover, HaffCurveGivesItsTimes) {
    // Pure Haff cooling, Eq. (2): T = T0 / (1 + a t)^2 with T0 = 1/3, followed by
    // a sticky-gas tail B t^-2/3 that takes over where it is larger.
    constexpr double rate = 0.05, sticky = 0.2;
    std::vector<double> time, temperature;
    for (int k = 0; k <= 80; ++k) time.push_back(std::pow(10.0, k / 20.0));
    std::mt19937_64 random(3);
    std::normal_distribution<double> noise(0.0, 1e-3);
    constexpr std::size_t realizations = 8;
    for (std::size_t r = 0; r < realizations; ++r)
        for (double t : time)
            temperature.push_back((1.0 / 3.0 / std::pow(1.0 + rate * t, 2.0) + sticky * std::pow(t, -2.0 / 3.0) *
                                   std::exp(-20.0 / t)) * (1.0 + noise(random)));
    const auto crossovers = sa::find_crossovers(
        sa::TemperatureHistory::from(time, static_cast<std::int64_t>(realizations), temperature));
    // t_dissip: T0 / (1 + a t)^2 = T0 / 2 -> t = (sqrt 2 - 1) / a, shifted slightly by the sticky term.
    EXPECT_NEAR(crossovers.t_dissip.value, (std::sqrt(2.0) - 1.0) / rate, 0.15 * (std::sqrt(2.0) - 1.0) / rate);
    EXPECT_NEAR(crossovers.haff_rate.value, rate, 0.2 * rate);
    // t_stick lies after the asymptotes' intersection T0/(a t)^2 = B t^-2/3 (~ 1e2 here).
    EXPECT_GT(crossovers.t_stick.value, crossovers.t_dissip.value);
    EXPECT_LT(crossovers.t_stick.value, 1e3);
}

namespace {

// Histograms of a symmetric law with density ~ exp(-|x|^gamma_true) scaled by
// width(t) = t^-beta, binned exactly as the simulator bins (histogram_edges).
sa::VelocityHistogram synthetic_histogram(std::mt19937_64& random, double time, double beta, double gamma_true,
                                          std::size_t realizations, std::size_t per_realization) {
    sa::VelocityHistogram h;
    h.time = time;
    h.edges = shockgas::histogram_edges(time, 160, 4.0);
    h.realizations = realizations;
    h.counts.assign(realizations * (h.bins() + 2), 0.0);
    // |x|^gamma is Gamma(1/gamma, 1) distributed for density ~ exp(-|x|^gamma).
    std::gamma_distribution<double> power(1.0 / gamma_true, 1.0);
    std::bernoulli_distribution sign(0.5);
    const double width = 0.5 * std::pow(time, -beta);
    for (std::size_t r = 0; r < realizations; ++r) {
        for (std::size_t i = 0; i < per_realization; ++i) {
            double v = width * std::pow(power(random), 1.0 / gamma_true);
            if (sign(random)) v = -v;
            const auto upper = std::upper_bound(h.edges.begin(), h.edges.end(), v);
            const auto slot = static_cast<std::size_t>(upper - h.edges.begin());  // 0: underflow, bins+1: overflow
            h.counts[r * (h.bins() + 2) + slot] += 1.0;
        }
    }
    return h;
}

}  // namespace

TEST(AnalysisScaling, CollapseExponentAndCoverage) {
    std::mt19937_64 random(99);
    constexpr int trials = 60;
    int inside = 0;
    for (int trial = 0; trial < trials; ++trial) {
        const std::vector<sa::VelocityHistogram> histograms{
            synthetic_histogram(random, 100.0, 1.0 / 3.0, 2.0, 20, 2000),
            synthetic_histogram(random, 1e4, 1.0 / 3.0, 2.0, 20, 2000)};
        const auto collapse = sa::fit_scaling_collapse(histograms);
        if (std::abs(collapse.beta.value - 1.0 / 3.0) <= collapse.beta.sigma) ++inside;
        if (trial == 0) {
            EXPECT_NEAR(collapse.beta.value, 1.0 / 3.0, 4.0 * collapse.beta.sigma);
            EXPECT_LT(collapse.beta.sigma, 0.01);
        }
    }
    std::printf("one-sigma coverage %.3f over %d trials (expected %.3f +- %.3f)\n", static_cast<double>(inside) / trials,
                trials, one_sigma_coverage, coverage_tolerance(trials));
    EXPECT_NEAR(static_cast<double>(inside) / trials, one_sigma_coverage, coverage_tolerance(trials));
}

TEST(AnalysisScaling, KurtosisOfGaussianIsThree) {
    std::mt19937_64 random(5);
    const auto h = synthetic_histogram(random, 1000.0, 1.0 / 3.0, 2.0, 20, 20000);
    const auto kurtosis = sa::velocity_kurtosis(h);
    // Binning adds O((bin width / sigma)^2) = O(1e-3); well inside 4 sigma.
    EXPECT_NEAR(kurtosis.value, 3.0, 4.0 * kurtosis.sigma + 3e-3);
}

TEST(AnalysisTail, GammaRecoveredWithCalibratedSigma) {
    std::mt19937_64 random(11);
    constexpr int trials = 60;
    constexpr double gamma_true = 3.0;  // Eq. (5)
    int inside = 0;
    for (int trial = 0; trial < trials; ++trial) {
        const auto h = synthetic_histogram(random, 1000.0, 1.0 / 3.0, gamma_true, 20, 5000);
        const auto tail = sa::fit_tail(h);
        if (std::abs(tail.gamma.value - gamma_true) <= tail.gamma.sigma) ++inside;
        if (trial == 0) {
            EXPECT_NEAR(tail.gamma.value, gamma_true, 4.0 * tail.gamma.sigma);
        }
    }
    std::printf("one-sigma coverage %.3f over %d trials (expected %.3f +- %.3f)\n", static_cast<double>(inside) / trials,
                trials, one_sigma_coverage, coverage_tolerance(trials));
    EXPECT_NEAR(static_cast<double>(inside) / trials, one_sigma_coverage, coverage_tolerance(trials));
}

// Eq. (6): segments v = (x - q_s)/t of 20 sparse particles each, and between
// them heavy clusters (the shocks) at the segment ends. With dense_run = s the
// shock after segment s is replaced by a cluster that is not (yet) a shock:
// ten particles within 0.09 of a spacing whose velocities rise across it.
sa::Snapshot ideal_sawtooth(double time, double ring_length, int segments, int dense_run = -1) {
    sa::Snapshot snapshot;
    snapshot.time = time;
    snapshot.ring_length = ring_length;
    const double length = ring_length / segments;
    for (int s = 0; s < segments; ++s) {
        const double q = s * length + length / 2.0;  // segment centre: v = 0 there
        for (int i = 0; i < 20; ++i) {
            const double x = s * length + 1.0 + i * (length - 2.0) / 20.0;
            snapshot.position.push_back(x);
            snapshot.velocity.push_back((x - q) / time);
            snapshot.mass.push_back(1.0);
        }
        if (s == dense_run) {
            for (int i = 0; i < 10; ++i) {
                snapshot.position.push_back((s + 1) * length - 0.5 + 0.01 * i);
                snapshot.velocity.push_back(-0.02 + 0.004 * i);
                snapshot.mass.push_back(1.0);
            }
        } else {
            snapshot.position.push_back((s + 1) * length - 0.5);  // the shock cluster
            snapshot.velocity.push_back(0.0);
            snapshot.mass.push_back(50.0);
        }
    }
    return snapshot;
}

// The dense run fits as a "segment" of slope ~0.4 (x t = 444), which is no
// rarefaction; averaged in, such runs swamped the paper-size Fig. 5's raw
// slope. The summary must leave it out of both slope estimates and count it.
TEST(AnalysisShocks, DenseRunIsNotASegment) {
    constexpr double time = 1000.0;
    constexpr int segments = 6;
    const auto summary = sa::summarize_shocks({ideal_sawtooth(time, 1200.0, segments, 2)});
    EXPECT_EQ(summary.dense_segments, 1u);
    EXPECT_EQ(summary.segments, static_cast<std::size_t>(segments));
    EXPECT_NEAR(summary.slope_times_t.value, 1.0, 1e-9);
}

TEST(AnalysisShocks, IdealSawtooth) {
    constexpr double time = 1000.0, ring_length = 1200.0;
    constexpr int segments = 6;
    const sa::Snapshot snapshot = ideal_sawtooth(time, ring_length, segments);
    const auto profile = sa::find_shocks(snapshot);
    EXPECT_EQ(profile.shock_position.size(), static_cast<std::size_t>(segments));
    ASSERT_EQ(profile.segments.size(), static_cast<std::size_t>(segments));
    for (const auto& segment : profile.segments) EXPECT_NEAR(segment.slope * time, 1.0, 1e-9);

    // The same ring moved by `shift` (positions wrapped into [0, L), order
    // kept): shockgas-sim lists clusters in ring order from the smallest slot,
    // so once particle 0 has drifted across x = 0 the seam falls inside the
    // list, not between its last and first entries (seen in the paper-size
    // Fig. 5 run). Nothing may change but the positions.
    for (const double shift : {-0.25, -500.0, 333.3, 1199.0}) {
        sa::Snapshot moved = snapshot;
        for (double& x : moved.position) x = std::fmod(std::fmod(x + shift, ring_length) + ring_length, ring_length);
        const auto moved_profile = sa::find_shocks(moved);
        EXPECT_EQ(moved_profile.shock_position.size(), static_cast<std::size_t>(segments)) << "shift " << shift;
        ASSERT_EQ(moved_profile.segments.size(), static_cast<std::size_t>(segments)) << "shift " << shift;
        for (const auto& segment : moved_profile.segments)
            EXPECT_NEAR(segment.slope * time, 1.0, 1e-9) << "shift " << shift;
    }
}
