// SPDX-License-Identifier: GPL-3.0-or-later
// compare_temperatures: the deviation of one T(t) from a reference, and the
// time from which on it stays outside the noise.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/compare.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"

namespace {

using shockgas::analysis::compare_temperatures;
using shockgas::analysis::Realizations;
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
    const auto comparison = compare_temperatures(a, a, Realizations::paired);
    EXPECT_EQ(comparison.max_abs_deviation, 0.0);
    EXPECT_TRUE(std::isinf(comparison.departure_time));
}

TEST(Compare, FindsTheDepartureAndTheLargestDeviation) {
    const std::vector<double> time{1, 10, 100, 1000, 10000};
    const auto reference = history(time, 1.0, 0);
    const auto run = history(time, 1.1, 2);  // 10% high from t = 100 on
    const auto comparison = compare_temperatures(run, reference, Realizations::independent);
    EXPECT_NEAR(comparison.max_abs_deviation, 0.1, 1e-12);
    EXPECT_EQ(comparison.departure_time, 100.0);
    ASSERT_EQ(comparison.relative_deviation.size(), time.size());
    EXPECT_NEAR(comparison.relative_deviation[0], 0.0, 1e-12);
    // A deviation below the 2% floor does not count as departing.
    const auto close = compare_temperatures(history(time, 1.01, 2), reference, Realizations::independent);
    EXPECT_TRUE(std::isinf(close.departure_time));
}

TEST(Compare, RunsWithoutACommonTimeAreNotInAgreement) {
    // Runs that share no sample time are refused, not reported in perfect
    // agreement ("max |dT/T| 0") with nothing compared.
    const auto reference = history({1, 10, 100}, 1.0, 0);
    const auto run = history({0.5, 0.9}, 1.0, 0);
    EXPECT_THROW(compare_temperatures(run, reference, Realizations::paired), shockgas::analysis::InsufficientData);
}

TEST(Compare, OneRealizationHasNoSigmaNotAZeroOne) {
    const std::vector<double> time{1, 10, 100};
    std::vector<double> temperature;
    for (double t : time) temperature.push_back(std::pow(t, -2.0 / 3.0) * 1.01);
    const auto single = TemperatureHistory::from(time, 1, temperature);
    const auto comparison = compare_temperatures(single, history(time, 1.0, 0), Realizations::independent);
    for (double sigma : comparison.relative_sigma) EXPECT_TRUE(std::isnan(sigma));
    EXPECT_FALSE(comparison.sigma_note.empty());
    // 1% off: inside the 2% floor, which alone judges the departure then.
    EXPECT_TRUE(std::isinf(comparison.departure_time));
    EXPECT_NEAR(comparison.max_abs_deviation, 0.01, 1e-3);
    EXPECT_EQ(comparison.time_of_max, 1.0);
}

TEST(Compare, OneRealizationInCommonHasNoPairedSigma) {
    const std::vector<double> time{1, 10, 100};
    const auto single = TemperatureHistory::from(time, 1, {1.0, 0.5, 0.25});
    const auto comparison = compare_temperatures(single, history(time, 1.0, 0), Realizations::paired);
    for (double sigma : comparison.relative_sigma) EXPECT_TRUE(std::isnan(sigma));
    EXPECT_FALSE(comparison.sigma_note.empty());
    EXPECT_EQ(comparison.realizations_compared, 1u);
    EXPECT_NE(comparison.pairing_note.find("the run has 1, the reference 2"), std::string::npos)
        << comparison.pairing_note;
}

// Realization i of both runs starts from the same state, so a run's T(t) is
// its reference's realization by realization times a factor: 1 until index
// `from`, then shift x (1 +- wobble). The realizations themselves spread by
// +-30%, as T(t) of small rings does.
constexpr std::size_t paired_realizations = 8;
constexpr double realization_spread = 0.3;
constexpr double paired_shift = 1.05;
constexpr double paired_wobble = 0.002;
TemperatureHistory spread_history(const std::vector<double>& time, double shift, double wobble, std::size_t from) {
    std::vector<double> temperature;
    for (std::size_t i = 0; i < paired_realizations; ++i) {
        const double realization_factor =
            1.0 + realization_spread * (static_cast<double>(i) - 3.5) / 3.5;
        for (std::size_t k = 0; k < time.size(); ++k)
            temperature.push_back(std::pow(time[k], -2.0 / 3.0) * realization_factor *
                                  (k >= from ? shift * (1.0 + (i % 2 == 0 ? wobble : -wobble)) : 1.0));
    }
    return TemperatureHistory::from(time, static_cast<std::int64_t>(paired_realizations), temperature);
}

TEST(Compare, PairedRealizationsSeeAShiftTheirSpreadHides) {
    // A 5% shift under a 30% realization spread: as independent ensembles the
    // 3 sigma band (about 29%) hides it; paired, each realization's ratio is
    // 1.05 +- 0.2%, and the shift departs where it begins.
    const std::vector<double> time{1, 10, 100, 1000, 10000};
    const auto reference = spread_history(time, 1.0, 0.0, 0);
    const auto run = spread_history(time, paired_shift, paired_wobble, 2);
    const auto independent = compare_temperatures(run, reference, Realizations::independent);
    const auto paired = compare_temperatures(run, reference, Realizations::paired);
    EXPECT_TRUE(std::isinf(independent.departure_time));
    EXPECT_EQ(paired.departure_time, 100.0);
    EXPECT_EQ(paired.realizations_compared, paired_realizations);
    EXPECT_TRUE(paired.pairing_note.empty());
    // Before the shift the runs are identical realization by realization: sigma exactly 0.
    EXPECT_EQ(paired.relative_sigma[0], 0.0);
    EXPECT_EQ(paired.relative_deviation[0], 0.0);
    // The ratio of sums is the shift up to the wobble's weighted mean (below 2e-3).
    constexpr double wobble_bound = paired_wobble;
    EXPECT_NEAR(paired.relative_deviation[3], paired_shift - 1.0, wobble_bound);
    // The paired sigma is of the wobble's size (2e-3 / sqrt(8) x 1.05 ~ 8e-4),
    // the independent one of the spread's (about 0.1).
    EXPECT_LT(paired.relative_sigma[3], 3.0 * paired_wobble);
    EXPECT_GT(independent.relative_sigma[3], 20.0 * paired_wobble);
}

TEST(Compare, PairedSigmaAgainstAConstantReferenceIsTheStandardError) {
    // With every reference realization equal to 1 the ratio of sums is the
    // run's mean, and the delete-one jackknife error of a mean is exactly the
    // standard error s / sqrt(n) (Efron & Tibshirani 1993, Sec. 11.2): an
    // identity, so only rounding separates the two.
    constexpr double rounding_tolerance = 1e-12;
    const std::vector<double> time{1, 10};
    const auto run = spread_history(time, 1.0, 0.0, 0);
    const auto ones = TemperatureHistory::from(time, static_cast<std::int64_t>(paired_realizations),
                                               std::vector<double>(paired_realizations * time.size(), 1.0));
    const auto paired = compare_temperatures(run, ones, Realizations::paired);
    for (std::size_t k = 0; k < time.size(); ++k) {
        EXPECT_NEAR(paired.relative_deviation[k], run.mean(k) - 1.0, rounding_tolerance);
        EXPECT_NEAR(paired.relative_sigma[k] / run.standard_error(k), 1.0, rounding_tolerance);
    }
}

// A run of one realization and three sample times with these parameters, as shockgas-sim writes it.
std::string write_compared_run(const std::string& name, const shockgas::SimulationParameters& parameters) {
    shockgas::EnsembleResult result;
    result.realizations = 1;
    result.times = {1.0, 10.0, 100.0};
    result.temperature = {0.3, 0.1, 0.05};
    result.collisions_per_particle = {1.0, 2.0, 3.0};
    result.clusters = {8.0, 6.0, 4.0};
    result.kinetic_energy = {0.15, 0.05, 0.025};
    result.realization_status = {0};
    result.status = "complete";
    result.engine = "event";
    const auto path = (std::filesystem::temp_directory_path() / ("shockgas_compare_" + name + ".h5")).string();
    shockgas::write_output(path, parameters, result);
    return path;
}

TEST(Compare, RunsOfAnotherEnsembleAreNamedByTheirDifferences) {
    // A reference at r = 0.9, N = 2000 against runs with N = 1000 or r = 0.8 is
    // refused: a deviation table would measure N or r, not delta.
    shockgas::SimulationParameters reference;
    reference.particles = 2000;
    reference.collision.restitution = 0.9;
    reference.collision.velocity_threshold = 1e-4;
    reference.seed = 8090;
    reference.t_max = 100.0;
    const auto reference_path = write_compared_run("reference", reference);
    // What compare is for (fig_tradeoff): another delta, the other sub-threshold rule, another t_max and R.
    auto cheaper = reference;
    cheaper.collision.velocity_threshold = 1e-2;
    cheaper.collision.subthreshold = shockgas::Subthreshold::sticky;
    cheaper.t_max = 50.0;
    cheaper.realizations = 4;
    const auto cheaper_path = write_compared_run("cheaper", cheaper);
    EXPECT_EQ(shockgas::analysis::comparison_differences(reference_path, cheaper_path), "");
    auto other = reference;
    other.particles = 1000;
    other.collision.restitution = 0.8;
    other.seed = 7;
    const auto other_path = write_compared_run("other", other);
    EXPECT_EQ(shockgas::analysis::comparison_differences(reference_path, other_path),
              "particles 1000 vs 2000, ring_length 1000 vs 2000, restitution 0.8 vs 0.9, seed 7 vs 8090");
    auto shifted = reference;
    shifted.first_realization = 4;  // other initial states: realization k starts as the reference's k + 4
    const auto shifted_path = write_compared_run("shifted", shifted);
    EXPECT_EQ(shockgas::analysis::comparison_differences(reference_path, shifted_path), "first_realization 4 vs 0");
    for (const auto& path : {reference_path, cheaper_path, other_path, shifted_path}) std::filesystem::remove(path);
}

}  // namespace
