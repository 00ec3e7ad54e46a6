// SPDX-License-Identifier: GPL-3.0-or-later
// The initial laws (--positions, --velocity-distribution): moments against
// the laws' exact values, seeding, and how they are recorded and merged.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "shockgas/run/ensemble.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/state.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::InitialLaw;
using shockgas::PositionLaw;
using shockgas::VelocityLaw;

// Sample size of the moment tests: 4 realizations of 50 000 particles.
constexpr std::int64_t moment_particles = 50000;
constexpr int moment_realizations = 4;
constexpr double moment_samples = moment_particles * moment_realizations;
// Every moment is checked to within this many standard errors of its
// estimator (two-sided 5 sigma: a correct law fails with probability 6e-7,
// and the seeds are fixed, so the test is deterministic).
constexpr double standard_errors = 5.0;

struct Moments {
    double mean = 0, variance = 0, kurtosis = 0;  // kurtosis: <(v - mean)^4> / variance^2
};

Moments moments(const std::vector<double>& values) {
    Moments m;
    const double n = static_cast<double>(values.size());
    for (double v : values) m.mean += v / n;
    double fourth = 0;
    for (double v : values) {
        const double d = v - m.mean;
        m.variance += d * d / n;
        fourth += d * d * d * d / n;
    }
    m.kurtosis = fourth / (m.variance * m.variance);
    return m;
}

std::vector<double> pooled_velocities(const InitialLaw& law) {
    std::vector<double> all;
    for (int k = 0; k < moment_realizations; ++k) {
        const auto initial = shockgas::generate_initial_condition(moment_particles, moment_particles, 17, k, law);
        all.insert(all.end(), initial.velocity.begin(), initial.velocity.end());
    }
    return all;
}

// Exact moments of the two laws: both have mean 0 and variance 1/3
// (uniform on [-1, 1): 1/3; Gaussian: sigma^2 = 1/3 by construction);
// kurtosis 9/5 for the uniform law, 3 for the Gaussian.
constexpr double law_variance = 1.0 / 3.0;

// n Var(sample kurtosis) for large n, for a symmetric law with standardized
// moments m4, m6, m8 (delta method): m8 - m4^2 - 4 m4 m6 + 4 m4^3. Gaussian
// (3, 15, 105): 24. Uniform (9/5, 27/7, 9): 1152/875.
constexpr double gaussian_kurtosis_variance = 24.0;
constexpr double uniform_kurtosis_variance = 1152.0 / 875.0;

void expect_law_moments(const std::vector<double>& values, double kurtosis, double kurtosis_variance) {
    const Moments m = moments(values);
    // Standard errors of the estimators for n samples: sigma / sqrt(n) for the
    // mean; sigma^2 sqrt((kappa - 1)/n) for the variance; sqrt(kurtosis_variance / n).
    const double n = static_cast<double>(values.size());
    EXPECT_NEAR(m.mean, 0.0, standard_errors * std::sqrt(law_variance / n));
    EXPECT_NEAR(m.variance, law_variance, standard_errors * law_variance * std::sqrt((kurtosis - 1.0) / n));
    EXPECT_NEAR(m.kurtosis, kurtosis, standard_errors * std::sqrt(kurtosis_variance / n));
}

TEST(InitialLaw, UniformVelocitiesHaveTheUniformMoments) {
    expect_law_moments(pooled_velocities({PositionLaw::lattice, VelocityLaw::uniform}), 9.0 / 5.0, uniform_kurtosis_variance);
}

TEST(InitialLaw, GaussianVelocitiesHaveVarianceOneThirdAndKurtosisThree) {
    const auto velocities = pooled_velocities({PositionLaw::lattice, VelocityLaw::gaussian});
    expect_law_moments(velocities, 3.0, gaussian_kurtosis_variance);
    // The tail: P(|v| > 2 sigma) = erfc(sqrt 2) = 0.0455003 for a Gaussian
    // (0 for the uniform law, whose |v| < 1.73 sigma); binomial standard error.
    const double threshold = 2.0 * shockgas::initial_velocity_sigma;
    const double tail = static_cast<double>(std::count_if(velocities.begin(), velocities.end(),
                                                          [&](double v) { return std::abs(v) > threshold; })) /
                        moment_samples;
    const double expected_tail = std::erfc(std::sqrt(2.0));
    EXPECT_NEAR(tail, expected_tail,
                standard_errors * std::sqrt(expected_tail * (1.0 - expected_tail) / moment_samples));
}

TEST(InitialLaw, UniformPositionsHaveExponentialGaps) {
    const double ring_length = 2.0 * moment_particles;  // spacing 2, so L != N is exercised
    const double spacing = ring_length / moment_particles;
    std::vector<double> gaps;
    for (int k = 0; k < moment_realizations; ++k) {
        const auto initial = shockgas::generate_initial_condition(moment_particles, ring_length, 5, k,
                                                                  {PositionLaw::uniform, VelocityLaw::uniform});
        EXPECT_NO_THROW(shockgas::validate(initial));  // sorted, inside [0, L)
        for (std::int64_t i = 0; i < moment_particles; ++i) {
            const double next = i + 1 < moment_particles ? initial.position[i + 1] : initial.position[0] + ring_length;
            gaps.push_back(next - initial.position[i]);
        }
    }
    // N i.i.d. uniform points on a ring of length L: each gap is
    // Beta(1, N - 1) times L, i.e. exponential with mean L/N to O(1/N): mean
    // L/N exactly (the gaps sum to L), variance (L/N)^2, P(gap > 2 L/N) = e^-2.
    const Moments m = moments(gaps);
    EXPECT_NEAR(m.mean, spacing, 1e-9 * spacing);  // the gaps sum to L up to rounding
    EXPECT_NEAR(m.variance, spacing * spacing,
                standard_errors * spacing * spacing * std::sqrt(8.0 / moment_samples));  // exponential: kappa = 9
    const double wide = static_cast<double>(std::count_if(gaps.begin(), gaps.end(),
                                                          [&](double g) { return g > 2.0 * spacing; })) /
                        moment_samples;
    EXPECT_NEAR(wide, std::exp(-2.0), standard_errors * std::sqrt(std::exp(-2.0) * (1.0 - std::exp(-2.0)) / moment_samples));
}

TEST(InitialLaw, SeedStreamIsSharedAndPinned) {
    // Velocities are drawn before positions: the position law does not change them.
    const auto lattice = shockgas::generate_initial_condition(1000, 1000.0, 42, 3, {PositionLaw::lattice, VelocityLaw::gaussian});
    const auto scattered = shockgas::generate_initial_condition(1000, 1000.0, 42, 3, {PositionLaw::uniform, VelocityLaw::gaussian});
    EXPECT_EQ(lattice.velocity, scattered.velocity);
    EXPECT_NE(lattice.position, scattered.position);
    // The default law is the paper's, drawn exactly as before the laws existed.
    EXPECT_EQ(shockgas::generate_initial_condition(1000, 1000.0, 42, 3).velocity,
              shockgas::generate_initial_condition(1000, 1000.0, 42, 3, {}).velocity);
    // Same seed, same start; another realization, another start.
    EXPECT_EQ(scattered.position,
              shockgas::generate_initial_condition(1000, 1000.0, 42, 3, {PositionLaw::uniform, VelocityLaw::gaussian}).position);
    EXPECT_NE(scattered.velocity,
              shockgas::generate_initial_condition(1000, 1000.0, 42, 4, {PositionLaw::uniform, VelocityLaw::gaussian}).velocity);
    // Pinned bits: a seed must mean the same Gaussian start on every platform
    // and in every future version (values from this code).
    EXPECT_EQ(fmt::format("{}", lattice.velocity[0]), "0.1846627271443773");
    EXPECT_EQ(fmt::format("{}", lattice.velocity[1]), "-0.22855549160869038");
    EXPECT_EQ(fmt::format("{}", scattered.position[0]), "0.5067049458272743");
}

TEST(InitialLaw, PortableLogAgreesWithTheLibrary) {
    // Accurate to a few ulp: the series is truncated at 1e-21 and evaluated
    // with about 4 roundings; 4 ulp of log x leaves room for the library's own
    // half ulp.
    constexpr double allowed_ulps = 4.0;
    std::mt19937_64 engine(3);
    for (int i = 0; i < 100000; ++i) {
        const double x = std::ldexp(1.0 + shockgas::unit_uniform(engine), static_cast<int>(engine() % 200) - 150);
        const double expected = std::log(x);
        const double ulp = std::nextafter(std::abs(expected), INFINITY) - std::abs(expected);
        ASSERT_NEAR(shockgas::portable_log(x), expected, allowed_ulps * ulp) << x;
    }
    EXPECT_EQ(shockgas::portable_log(1.0), 0.0);
}

TEST(InitialLaw, RecordedInTheFileAndNamedWhenPartsDisagree) {
    shockgas::SimulationParameters p;
    p.particles = 200;
    p.t_max = 20;
    p.realizations = 2;
    p.initial_law = {PositionLaw::uniform, VelocityLaw::gaussian};
    const auto path = (fs::path(testing::TempDir()) / "law.h5").string();
    shockgas::write_output(path, p, shockgas::run_ensemble(p, nullptr));
    const auto root = shockgas::h5::File::open_read(path).root();
    EXPECT_EQ(root.attribute_string("positions"), "uniform");
    EXPECT_EQ(root.attribute_string("velocity_distribution"), "gaussian");
    const auto back = shockgas::read_output(path);
    EXPECT_EQ(back.parameters.initial_law.positions, PositionLaw::uniform);
    EXPECT_EQ(back.parameters.initial_law.velocities, VelocityLaw::gaussian);

    // A second part with another velocity law and seed: merge names both.
    auto other = p;
    other.first_realization = 2;
    other.initial_law.velocities = VelocityLaw::uniform;
    other.seed = 2;
    const auto other_path = (fs::path(testing::TempDir()) / "law_other.h5").string();
    shockgas::write_output(other_path, other, shockgas::run_ensemble(other, nullptr));
    try {
        shockgas::merge_outputs({back, shockgas::read_output(other_path)}, {path, other_path});
        FAIL() << "parts with different laws were merged";
    } catch (const shockgas::InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("velocity-distribution uniform vs gaussian"), std::string::npos) << message;
        EXPECT_NE(message.find("seed 2 vs 1"), std::string::npos) << message;
        EXPECT_EQ(message.find("restitution"), std::string::npos) << message;  // only what differs
    }
}

TEST(InitialLaw, InitFileIsOneStart) {
    shockgas::SimulationParameters p;
    p.particles = 16;
    p.t_max = 5;
    p.realizations = 4;
    const auto initial = shockgas::generate_initial_condition(16, 16.0, 3, 0);
    try {
        shockgas::run_ensemble(p, &initial);
        FAIL() << "an init file ran 4 identical realizations";
    } catch (const shockgas::InputError& error) {
        EXPECT_NE(std::string(error.what()).find("--velocity-distribution"), std::string::npos) << error.what();
    }
    p.realizations = 1;
    p.initial_law.velocities = VelocityLaw::gaussian;
    EXPECT_THROW(shockgas::run_ensemble(p, &initial), shockgas::InputError);  // a law and a file: which one?
}

}  // namespace
