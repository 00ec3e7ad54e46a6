// compare_temperatures: the deviation of one T(t) from a reference, and the
// time from which on it stays outside the noise.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/compare.hpp"

namespace {

using shockgas::analysis::compare_temperatures;
using shockgas::analysis::TemperatureHistory;

// Two realizations of T = t^(-2/3) with a relative spread of 1e-3 between them.
TemperatureHistory history(const std::vector<double>& time, double late_factor, std::size_t from) {
    std::vector<double> temperature;
    for (int r = 0; r < 2; ++r)
        for (std::size_t k = 0; k < time.size(); ++k)
            temperature.push_back(std::pow(time[k], -2.0 / 3.0) * (k >= from ? late_factor : 1.0) *
                                  (r == 0 ? 1.001 : 0.999));
    return TemperatureHistory::from(time, 2, temperature);
}

TEST(Compare, IdenticalRunsNeverDepart) {
    const std::vector<double> time{1, 10, 100, 1000};
    const auto a = history(time, 1.0, 0);
    const auto comparison = compare_temperatures(a, a);
    EXPECT_EQ(comparison.max_abs_deviation, 0.0);
    EXPECT_TRUE(std::isinf(comparison.departure_time));
}

TEST(Compare, FindsTheDepartureAndTheLargestDeviation) {
    const std::vector<double> time{1, 10, 100, 1000, 10000};
    const auto reference = history(time, 1.0, 0);
    const auto run = history(time, 1.1, 2);  // 10% high from t = 100 on
    const auto comparison = compare_temperatures(run, reference);
    EXPECT_NEAR(comparison.max_abs_deviation, 0.1, 1e-12);
    EXPECT_EQ(comparison.departure_time, 100.0);
    ASSERT_EQ(comparison.relative_deviation.size(), time.size());
    EXPECT_NEAR(comparison.relative_deviation[0], 0.0, 1e-12);
    // A deviation below the 2% floor does not count as departing.
    const auto close = compare_temperatures(history(time, 1.01, 2), reference);
    EXPECT_TRUE(std::isinf(close.departure_time));
}

TEST(Compare, RunsWithoutACommonTimeAreNotInAgreement) {
    // Perfect agreement ("max |dT/T| 0") was reported for runs that share no
    // sample time: nothing was compared.
    const auto reference = history({1, 10, 100}, 1.0, 0);
    const auto run = history({0.5, 0.9}, 1.0, 0);
    EXPECT_THROW(compare_temperatures(run, reference), shockgas::analysis::InsufficientData);
}

TEST(Compare, OneRealizationHasNoSigmaNotAZeroOne) {
    const std::vector<double> time{1, 10, 100};
    std::vector<double> temperature;
    for (double t : time) temperature.push_back(std::pow(t, -2.0 / 3.0) * 1.01);
    const auto single = TemperatureHistory::from(time, 1, temperature);
    const auto comparison = compare_temperatures(single, history(time, 1.0, 0));
    for (double sigma : comparison.relative_sigma) EXPECT_TRUE(std::isnan(sigma));
    EXPECT_FALSE(comparison.sigma_note.empty());
    // 1% off: inside the 2% floor, which alone judges the departure then.
    EXPECT_TRUE(std::isinf(comparison.departure_time));
    EXPECT_NEAR(comparison.max_abs_deviation, 0.01, 1e-3);
    EXPECT_EQ(comparison.time_of_max, 1.0);
}

}  // namespace
