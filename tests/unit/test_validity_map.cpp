// SPDX-License-Identifier: GPL-3.0-or-later
// The validity map as the planner and shockgas-sim read it: its HDF5 round trip
// (+inf and NaN included), the planner's answers and refusals on a map made by
// hand (validity_map_fixture.hpp), and shockgas-sim's warning.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "shockgas/analysis/plan_command.hpp"
#include "shockgas/analysis/validity_map.hpp"
#include "shockgas/analysis/validity_warning.hpp"
#include "shockgas/model/parameters.hpp"
#include "../test_support.hpp"
#include "../validity_map_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::analysis::make_plan;
using shockgas::analysis::Plan;
using shockgas::analysis::PlanOption;
using shockgas::analysis::PlanRequest;
using shockgas::analysis::ValidityMap;
using shockgas::testing::fixture_map;
using shockgas::testing::input_error_message;
using shockgas::testing::temp_path;
using shockgas::testing::write_map_file;

// Interpolated costs are a few logarithms and exponentials of exact numbers:
// rounding, not a method error, separates them from the closed form.
constexpr double rounding = 1e-12;

// Equal doubles, NaN equal to NaN (a NaN that round-trips is the same NaN to a reader).
void expect_same(double a, double b, const std::string& what) {
    if (std::isnan(a) || std::isnan(b))
        EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what << ": " << a << " vs " << b;
    else
        EXPECT_EQ(a, b) << what;
}

PlanRequest request_at(double t_max, const std::string& observable = "temperature",
                       const std::string& tolerance = "3sigma") {
    PlanRequest request;
    request.t_max = t_max;
    request.particles = 100'000;
    request.restitution = 0.9;
    request.observable = observable;
    request.tolerance = tolerance;
    request.map_file = "fixture.h5";
    return request;
}

const PlanOption& best(const Plan& plan) { return plan.options.at(plan.best); }

std::string refusal(const PlanRequest& request) {
    return input_error_message([&] { make_plan(fixture_map(), request); });
}

TEST(ValidityMap, RoundTripKeepsEveryFieldInfinityAndNaN) {
    const ValidityMap written = fixture_map();
    const std::string path = temp_path("validity_round_trip.h5");
    write_map_file(path, written);
    const ValidityMap read = shockgas::analysis::read_validity_map(path);
    EXPECT_EQ(read.version, written.version);
    EXPECT_EQ(read.fidelity, written.fidelity);
    EXPECT_EQ(read.observables, written.observables);
    ASSERT_EQ(read.runs.size(), written.runs.size());
    for (std::size_t i = 0; i < written.runs.size(); ++i) {
        const auto &a = written.runs[i], &b = read.runs[i];
        EXPECT_EQ(b.name, a.name) << "the map's order of runs is kept";
        EXPECT_EQ(b.restitution, a.restitution);
        EXPECT_EQ(b.velocity_threshold, a.velocity_threshold);
        EXPECT_EQ(b.subthreshold, a.subthreshold);
        EXPECT_EQ(b.particles, a.particles);
        EXPECT_EQ(b.realizations, a.realizations);
        EXPECT_EQ(b.t_end, a.t_end);
        EXPECT_EQ(b.cpu_seconds, a.cpu_seconds);
        EXPECT_EQ(b.time, a.time);
        EXPECT_EQ(b.collisions_per_particle, a.collisions_per_particle);
        ASSERT_EQ(b.departures.size(), a.departures.size()) << a.name;
        for (std::size_t k = 0; k < a.departures.size(); ++k) {
            const std::string where = a.name + " departure " + std::to_string(k);
            EXPECT_EQ(b.departures[k].observable, a.departures[k].observable) << where;
            EXPECT_EQ(b.departures[k].criterion, a.departures[k].criterion) << where;
            expect_same(b.departures[k].departure_time, a.departures[k].departure_time, where);
            expect_same(b.departures[k].departure_sigma, a.departures[k].departure_sigma, where);
            EXPECT_EQ(b.departures[k].note, a.departures[k].note) << where;
        }
    }
    // The fixture holds t* = +inf (not left by t_end) and t* = NaN (never within).
    EXPECT_TRUE(std::isinf(read.runs[2].departures[2].departure_time));
    EXPECT_GT(read.runs[2].departures[2].departure_time, 0.0);
    EXPECT_TRUE(std::isnan(read.runs[1].departures[3].departure_time));
    ASSERT_EQ(read.fits.size(), written.fits.size());
    for (std::size_t i = 0; i < written.fits.size(); ++i) {
        const auto &a = written.fits[i], &b = read.fits[i];
        EXPECT_EQ(b.observable, a.observable);
        EXPECT_EQ(b.criterion, a.criterion);
        EXPECT_EQ(b.subthreshold, a.subthreshold);
        EXPECT_EQ(b.restitution, a.restitution);
        EXPECT_EQ(b.particles, a.particles);
        expect_same(b.mu, a.mu, "mu");
        expect_same(b.mu_sigma, a.mu_sigma, "mu_sigma");
        expect_same(b.log_amplitude, a.log_amplitude, "log_amplitude");
        expect_same(b.log_amplitude_sigma, a.log_amplitude_sigma, "log_amplitude_sigma");
        EXPECT_EQ(b.points, a.points);
        EXPECT_EQ(b.follows, a.follows);
    }
}

TEST(ValidityMap, AFileWithoutAMapIsRefusedNamingItAndTheObject) {
    const std::string empty = temp_path("validity_no_map.h5");
    shockgas::h5::write_atomically(empty, [](shockgas::h5::Group& root) { root.set_attribute("note", "no map"); });
    std::string message = input_error_message([&] { shockgas::analysis::read_validity_map(empty); });
    EXPECT_NE(message.find("holds no validity map (no group /validity_map)"), std::string::npos) << message;
    EXPECT_NE(message.find(empty), std::string::npos) << message;
    const std::string bare = temp_path("validity_bare_group.h5");
    shockgas::h5::write_atomically(bare, [](shockgas::h5::Group& root) { root.create_group("validity_map"); });
    message = input_error_message([&] { shockgas::analysis::read_validity_map(bare); });
    EXPECT_NE(message.find("/validity_map/version"), std::string::npos) << message;
    EXPECT_NE(message.find(bare), std::string::npos) << message;
}

TEST(ValidityMap, CollisionsPerParticleAreInterpolatedInLogLogNeverExtrapolated) {
    const auto run = fixture_map().runs[1];  // 2 sqrt(t)
    EXPECT_NEAR(shockgas::analysis::collisions_per_particle_at(run, 30.0), 2.0 * std::sqrt(30.0),
                rounding * std::sqrt(30.0));
    EXPECT_EQ(shockgas::analysis::collisions_per_particle_at(run, 100.0), 20.0);
    EXPECT_TRUE(std::isnan(shockgas::analysis::collisions_per_particle_at(run, 0.5)));
    EXPECT_TRUE(std::isnan(shockgas::analysis::collisions_per_particle_at(run, 2e4)));
}

TEST(Planner, CheapestValidChoiceAndItsCost) {
    const Plan plan = make_plan(fixture_map(), request_at(30.0));
    // Every run at r = 0.9 keeps T within 3 sigma to t = 30; delta = 0.1
    // elastic makes the fewest collisions.
    EXPECT_EQ(best(plan).run, "r0.9_elastic_d-1");
    EXPECT_EQ(plan.options.size(), 4u);
    EXPECT_EQ(plan.map_version, "test map, shockgas fixture");
    // sqrt(30) collisions per particle by t = 30; the run's CPU per
    // particle-collision is 8 s / (4 realizations x 1000 particles x 100
    // collisions per particle at t_end = 10^4) = 2e-5 s, times 10^5 particles.
    const double collisions = std::sqrt(30.0);
    EXPECT_NEAR(best(plan).collisions_per_particle, collisions, rounding * collisions);
    const double cpu = 2e-5 * 1e5 * collisions;
    EXPECT_NEAR(best(plan).cpu_seconds_per_realization, cpu, rounding * cpu);
    const std::string text = shockgas::analysis::format_plan(plan, request_at(30.0));
    EXPECT_NE(text.find("cheapest: delta = 0.1, sub-threshold elastic"), std::string::npos) << text;
    EXPECT_NE(text.find("map: test map, shockgas fixture"), std::string::npos) << text;
    EXPECT_NE(text.find("0.001"), std::string::npos) << "every measured choice in the table:\n" << text;
}

TEST(Planner, TheChoiceChangesWithTMax) {
    // t* of T by 3 sigma: 50 (0.1 elastic), 500 (0.01 elastic), 400 (0.01
    // sticky), 5000 (0.001 sticky); the costs rise in that order of listing.
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(30.0))).run, "r0.9_elastic_d-1");
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(100.0))).run, "r0.9_elastic_d-2");
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(450.0))).run, "r0.9_elastic_d-2");
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(600.0))).run, "r0.9_sticky_d-3");
    // At t* itself the observable has left: valid means t* > t_max.
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(50.0))).run, "r0.9_elastic_d-2");
}

TEST(Planner, NeverWithinIsNotValidNotLeftByTheEndIs) {
    // Kurtosis by 3 sigma: NaN for 0.01 elastic (the cheaper), 2000 for 0.01 sticky.
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(100.0, "kurtosis"))).run, "r0.9_sticky_d-2");
    // T by 5 %: +inf (had not left by t_end = 10^4) for both sticky runs.
    EXPECT_EQ(best(make_plan(fixture_map(), request_at(5000.0, "temperature", "5percent"))).run, "r0.9_sticky_d-2");
}

TEST(Planner, RefusesWhatTheMapDidNotMeasure) {
    auto request = request_at(30.0);
    request.restitution = 0.7;
    EXPECT_EQ(refusal(request), "r = 0.7 is not among the map's restitutions: it measured r = 0.5, 0.9 (give one of "
                                "them; the map does not interpolate in r)");
    // Within the tolerance of a typed 0.9 it is 0.9.
    request.restitution = 0.9 + 1e-12;
    EXPECT_EQ(refusal(request), "");
    EXPECT_EQ(refusal(request_at(2e4)), "t_max = 20000 lies beyond the measured map, which reaches t = 10000 at r = 0.9");
    request = request_at(30.0);
    request.restitution = 0.5;
    request.particles = 1000;
    EXPECT_EQ(refusal(request),
              "N = 1000 is below the map's rings at r = 0.5: smaller rings reach their finite-size regime sooner, so "
              "the map, measured at N = 2000, says nothing of them; give N >= 2000");
    EXPECT_EQ(refusal(request_at(30.0, "pressure")), "unknown observable 'pressure': the map measured temperature, kurtosis");
    EXPECT_EQ(refusal(request_at(30.0, "kurtosis", "1percent")),
              "the map has not measured kurtosis by 1percent: it measured it by 3sigma only");
    EXPECT_EQ(refusal(request_at(30.0, "temperature", "2percent")),
              "--tolerance must be one of 3sigma, 1percent, 5percent, not '2percent'");
    EXPECT_EQ(refusal(request_at(0.5)),
              "t_max = 0.5 lies before the map's first sample time, t = 1, at r = 0.9: its cost there is not measured");
}

TEST(Planner, NothingValidNamesTheSmallestDeltaAndWhenItLeaves) {
    // T by 1 %: 20, 300, 100, 3000: none reaches t = 5000.
    EXPECT_EQ(refusal(request_at(5000.0, "temperature", "1percent")),
              "no measured delta keeps temperature within 1percent to t = 5000 at r = 0.9; the smallest measured "
              "delta, 0.001 (sticky), leaves at t* = 3e+03");
}

TEST(Planner, NoMapSaysHowToMakeOne) {
    auto request = request_at(30.0);
    request.map_file = "";
    const std::string message = input_error_message([&] { shockgas::analysis::run_plan(request, stdout); });
    EXPECT_NE(message.find("cmake --build --preset quick --target fig_validity"), std::string::npos) << message;
    EXPECT_NE(message.find("--map FILE"), std::string::npos) << message;
}

TEST(ValidityWarning, AMeasuredDeltaWarnsPastItsDepartureOnly) {
    using shockgas::analysis::validity_warning;
    const ValidityMap map = fixture_map();
    // T leaves by 1 % at t* = 300 for r = 0.9, delta = 0.01, elastic.
    EXPECT_EQ(validity_warning(map, 0.9, 0.01, "elastic", 1000.0),
              "t_max = 1000 lies past the measured validity of T for r = 0.9, delta = 0.01 (elastic): T leaves the "
              "sticky gas by 1 % at t* \u2248 300 (test map, shockgas fixture; docs/validity.md)");
    EXPECT_EQ(validity_warning(map, 0.9, 0.01, "elastic", 300.0), "");
    EXPECT_EQ(validity_warning(map, 0.9, 0.01, "elastic", 200.0), "");
}

TEST(ValidityWarning, ADeltaBetweenTwoMeasuredOnesInterpolatesInLogLog) {
    using shockgas::analysis::validity_warning;
    const ValidityMap map = fixture_map();
    // Halfway in log delta between 0.1 (t* = 20) and 0.01 (t* = 300): t* = sqrt(20 x 300) = 77.5.
    const double delta = std::sqrt(0.1 * 0.01);
    const std::string warning = validity_warning(map, 0.9, delta, "elastic", 100.0);
    EXPECT_NE(warning.find("t* \u2248 77.5 "), std::string::npos) << warning;
    EXPECT_EQ(validity_warning(map, 0.9, delta, "elastic", 70.0), "");
    // Sticky between 0.01 (t* = 100) and 0.001 (3000): sqrt(3 x 10^5) = 548.
    EXPECT_NE(validity_warning(map, 0.9, std::sqrt(1e-5), "sticky", 1000.0).find("t* \u2248 548 "), std::string::npos);
}

TEST(ValidityWarning, NothingWhereTheMapCannotSay) {
    using shockgas::analysis::validity_warning;
    const ValidityMap map = fixture_map();
    EXPECT_EQ(validity_warning(map, 0.9, 0.5, "elastic", 1e4), "") << "delta above the measured ones";
    EXPECT_EQ(validity_warning(map, 0.9, 1e-4, "sticky", 1e4), "") << "delta below the measured ones";
    EXPECT_EQ(validity_warning(map, 0.9, 0.1, "sticky", 1e4), "") << "no sticky run at 0.1";
    EXPECT_EQ(validity_warning(map, 0.7, 0.01, "elastic", 1e4), "") << "an r the map lacks";
    EXPECT_EQ(validity_warning(map, 1.0, 0.01, "elastic", 1e4), "") << "r = 1 is elastic: no sticky gas to leave";
    EXPECT_EQ(validity_warning(map, 0.0, 0.01, "elastic", 1e4), "") << "r = 0 is the sticky gas";
    EXPECT_EQ(validity_warning(map, 0.9, 0.0, "elastic", 1e4), "") << "delta = 0: no threshold";
    // r = 0.5: T had not left by 1 % at delta = 0.01 within its run (+inf).
    EXPECT_EQ(validity_warning(map, 0.5, 0.01, "elastic", 1e6), "");
    EXPECT_EQ(validity_warning(map, 0.5, std::sqrt(1e-3), "elastic", 1e6), "");
    EXPECT_NE(validity_warning(map, 0.5, 0.1, "elastic", 1e3), "");
}

TEST(ValidityWarning, TheMapARunReads) {
    using shockgas::analysis::validity_warning_for_run;
    const std::string path = temp_path("validity_for_run.h5");
    write_map_file(path, fixture_map());
    EXPECT_NE(validity_warning_for_run(path, true, 0.9, 0.01, "elastic", 1000.0), "");
    EXPECT_EQ(validity_warning_for_run("", true, 0.9, 0.01, "elastic", 1000.0), "") << "'' looks up none";
    const std::string absent = temp_path("validity_absent.h5");
    EXPECT_EQ(validity_warning_for_run(absent, false, 0.9, 0.01, "elastic", 1000.0), "")
        << "a default map that does not exist is passed over in silence";
    EXPECT_NE(input_error_message([&] { validity_warning_for_run(absent, true, 0.9, 0.01, "elastic", 1000.0); }), "")
        << "a map the user named must be there";
    const std::string garbage = temp_path("validity_garbage.h5");
    std::ofstream(garbage) << "not a map\n";
    EXPECT_EQ(validity_warning_for_run(garbage, false, 0.9, 0.01, "elastic", 1000.0).rfind(
                  "the validity map was not checked: ", 0),
              0u);
}

TEST(ValidityWarning, TheEnvironmentChoosesTheDefaultMap) {
    using shockgas::analysis::default_validity_map;
    const std::string existing = temp_path("validity_default.h5");
    write_map_file(existing, fixture_map());
    const std::string absent = temp_path("validity_default_absent.h5");
    const char* saved = std::getenv("SHOCKGAS_VALIDITY_MAP");
    const std::string saved_value = saved != nullptr ? saved : "";
    ::unsetenv("SHOCKGAS_VALIDITY_MAP");
    EXPECT_EQ(default_validity_map({absent, existing}), existing) << "the first build-tree map that exists";
    EXPECT_EQ(default_validity_map({absent}), "");
    ::setenv("SHOCKGAS_VALIDITY_MAP", "", 1);
    EXPECT_EQ(default_validity_map({existing}), "") << "set and empty: none (the test suite's setting)";
    ::setenv("SHOCKGAS_VALIDITY_MAP", "elsewhere.h5", 1);
    EXPECT_EQ(default_validity_map({existing}), "elsewhere.h5");
    if (saved != nullptr)
        ::setenv("SHOCKGAS_VALIDITY_MAP", saved_value.c_str(), 1);
    else
        ::unsetenv("SHOCKGAS_VALIDITY_MAP");
}

}  // namespace
