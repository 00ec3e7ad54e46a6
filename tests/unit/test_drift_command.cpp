// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-drift's work as the program calls it (drift.hpp: DriftRequest,
// run_drift_command, drift_summary): the summary line's numbers, the checks
// of the request, and a short run that writes its rows and passes its checks.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "drift.hpp"
#include "shockgas/model/parameters.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::testing::temp_path;

TEST(DriftCommand, TheSummaryLineIsTheLastRowAndTheRunsWorst) {
    shockgas::drift::DriftReport report;
    report.ended = "reached the target";
    report.max_rise = 1.25e-17;
    report.nonfinite = 0;
    shockgas::drift::DriftRow row{};
    row.collisions = 1e6;
    row.time = 123.456789;
    row.cpu_seconds = 0.84;
    row.rate = 1.19e6;
    row.drift = 4.5e-19;
    row.bound = 4.51e-13;
    row.min_gap_run = 3.2e-7;
    report.rows = {shockgas::drift::DriftRow{}, row};
    EXPECT_EQ(shockgas::drift::drift_summary(report),
              "# reached the target: 1000000 collisions, t = 123.457, 0.8 s CPU, 1.19e+06 collisions/s; final dP/S0 = "
              "4.500e-19 (bound 4.510e-13); max energy rise 1.250e-17; smallest gap 3.200e-07 L/N; ring order held; "
              "non-finite 0");
    report.order_held = false;
    report.nonfinite = 3;
    const std::string broken = shockgas::drift::drift_summary(report);
    EXPECT_NE(broken.find("ring order BROKEN; non-finite 3"), std::string::npos) << broken;
}

TEST(DriftCommand, TheProgramsDefaultsAndRefusals) {
    shockgas::drift::DriftRequest request;
    EXPECT_EQ(request.parameters.particles, 1000);
    EXPECT_EQ(request.parameters.collision.restitution, 0.5);
    EXPECT_EQ(request.parameters.collision.velocity_threshold, 1e-2);
    EXPECT_EQ(request.parameters.engine, "event");
    EXPECT_EQ(request.subthreshold, "elastic");

    auto refused = request;
    refused.output = temp_path("drift.txt");
    try {
        shockgas::drift::run_drift_command(refused);
        ADD_FAILURE() << "an output neither .csv nor .h5 was taken";
    } catch (const shockgas::InputError& error) {
        EXPECT_EQ(std::string(error.what()), "--output must end in .csv or .h5, got '" + refused.output + "'");
    }
    refused = request;
    refused.check = true;
    refused.subthreshold = "sticky";  // merges: the rounding bounds cannot judge them
    EXPECT_THROW(shockgas::drift::run_drift_command(refused), shockgas::InputError);
    refused.subthreshold = "glue";
    EXPECT_THROW(shockgas::drift::run_drift_command(refused), shockgas::InputError);
}

TEST(DriftCommand, AShortRunWritesItsRowsAndPassesItsChecks) {
    shockgas::drift::DriftRequest request;
    request.parameters.particles = 200;
    request.parameters.seed = 1;
    request.options.target_collisions = 2e4;
    request.options.record_every = 1e4;
    request.options.chunk_collisions = 2e3;
    request.output = temp_path("drift_rows.csv");
    request.check = true;
    EXPECT_EQ(shockgas::drift::run_drift_command(request), 0);
    std::ifstream csv(request.output);
    std::string header;
    ASSERT_TRUE(std::getline(csv, header));
    EXPECT_EQ(header.rfind("collisions,time,clusters,momentum,", 0), 0u) << header;
    int rows = 0;
    for (std::string line; std::getline(csv, line);) ++rows;
    EXPECT_GE(rows, 2);  // 10^4 and 2 10^4 collisions at least
    fs::remove(request.output);

    // A start off by far more than rounding fails the check: exit status 1.
    request.output.clear();
    request.options.inject_momentum_error = 1e-3;
    EXPECT_EQ(shockgas::drift::run_drift_command(request), 1);
}

}  // namespace
