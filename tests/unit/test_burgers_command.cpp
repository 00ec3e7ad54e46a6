// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-burgers' work as the program calls it (shockgas/analysis/burgers_command.hpp):
// the memory a solve needs and its refusal, the checks of the request, and a profile from
// shockgas-sim's initial condition end to end.
#include <filesystem>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "shockgas/analysis/burgers_command.hpp"
#include "shockgas/model/parameters.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::testing::read_text;
using shockgas::testing::temp_path;

// The message of the InputError that request throws ("" if none).
std::string refusal(const shockgas::analysis::BurgersRequest& request) {
    return shockgas::testing::input_error_message([&] { shockgas::analysis::run_burgers(request); });
}

TEST(BurgersCommand, MemoryNeedPerParticlePointAndProfile) {
    using shockgas::analysis::burgers_memory_bytes;
    // 200 bytes per particle and cell per particle, 48 per output point (four per particle by
    // default) and 24 more per point and viscous profile.
    EXPECT_EQ(burgers_memory_bytes(1000, 4, 0, 0), 200.0 * 1000 * 4 + 4000 * 48.0);
    EXPECT_EQ(burgers_memory_bytes(1000, 4, 0, 2), 1184000.0);
    EXPECT_EQ(burgers_memory_bytes(1000, 1, 500, 1), 200000.0 + 500 * 72.0);
}

TEST(BurgersCommand, ASolveBeyondTheMachineIsRefusedBeforeTheWork) {
    shockgas::analysis::BurgersRequest request;
    request.particles = 1'000'000'000'000'000;  // 10^15 particles: 8 * 10^17 bytes
    request.time = 1.0;
    request.output = temp_path("burgers_too_big.dat");
    const std::string message = refusal(request);
    EXPECT_EQ(message.rfind("not enough memory: N = 1000000000000000 needs about ", 0), 0u) << message;
    EXPECT_NE(message.find("give a smaller N, --points or --cells-per-particle"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(request.output));
}

TEST(BurgersCommand, BadValuesAndSharedOutputsAreRefused) {
    shockgas::analysis::BurgersRequest request;
    request.particles = 64;
    request.time = 10.0;
    request.output = temp_path("burgers_refused.dat");
    auto bad = request;
    bad.cells_per_particle = 0;
    EXPECT_EQ(refusal(bad), "--cells-per-particle must be at least 1");
    bad = request;
    bad.time = -1.0;
    EXPECT_EQ(refusal(bad), "--time must be positive and finite, not -1");
    bad = request;
    bad.viscosities = {0.1, 0.0};
    EXPECT_EQ(refusal(bad), "--viscosity must be positive and finite, not 0");
    bad = request;
    bad.summary = request.output;
    EXPECT_EQ(refusal(bad), "-o and --summary name the same file '" + request.output + "': give each its own");
    bad = request;
    bad.particles = 1;
    EXPECT_EQ(refusal(bad), "give --run, --init or --particles (at least 2)");
    EXPECT_FALSE(fs::exists(request.output));
}

TEST(BurgersCommand, ProfileAndSummaryFromTheSimulatorsStart) {
    shockgas::analysis::BurgersRequest request;
    request.particles = 64;
    request.seed = 3;
    request.time = 10.0;
    request.viscosities = {0.5};
    request.output = temp_path("burgers_profile.dat");
    request.summary = temp_path("burgers_summary.gp");
    shockgas::analysis::run_burgers(request);

    const std::string profile = read_text(request.output);
    EXPECT_NE(profile.find("# Burgers profile at t = 10: N = 64, L = 64, 4 cells per particle"), std::string::npos);
    EXPECT_NE(profile.find("# x v_inviscid v_nu=0.5\n"), std::string::npos);
    EXPECT_NE(profile.find("seed 3 realization 0 (positions lattice, velocities uniform"), std::string::npos);
    // Block 0: four points per particle, each "x v_0 v_nu".
    const std::string block = profile.substr(0, profile.find("\n\n\n"));
    int rows = 0;
    std::istringstream lines(block);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && line[0] != '#') ++rows;
    EXPECT_EQ(rows, 256);

    const std::string vars = read_text(request.summary);
    EXPECT_NE(vars.find("burgers_time = 10\n"), std::string::npos) << vars;
    EXPECT_NE(vars.find("burgers_cells_per_particle = 4\n"), std::string::npos) << vars;
    EXPECT_NE(vars.find("burgers_shock_count = "), std::string::npos) << vars;
    fs::remove(request.output);
    fs::remove(request.summary);
}

}  // namespace
