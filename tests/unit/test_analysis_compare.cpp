// compare_temperatures: the deviation of one T(t) from a reference, and the
// time from which on it stays outside the noise.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/compare.hpp"
#include "shockgas/output.hpp"
#include "shockgas/parameters.hpp"

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
    // A reference at r = 0.9, N = 2000 against runs with N = 1000 or r = 0.8
    // gave a deviation table with exit status 0: it measured N or r, not delta.
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
