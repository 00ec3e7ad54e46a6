// SPDX-License-Identifier: GPL-3.0-or-later
// The commands of shockgas-analyze called in-process, as the program calls them
// (shockgas/analysis/commands.hpp, analyze_command.hpp): a run file in, a results file and a
// data file out, and the checks made before any work.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/analyze_command.hpp"
#include "shockgas/analysis/commands.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;

// Each realization's T(t) is an exact power law, so every fit over every subset of realizations
// gives the same exponent and only the rounding of log, pow and the least-squares sums is left
// (a few ulps of 2/3 at these 21 points).
constexpr double rounding_tolerance = 1e-12;
constexpr double decay_exponent = 2.0 / 3.0;
// Data files print 10 significant digits (DataFile::row's {:.10g}): half a unit in the tenth digit.
constexpr double data_file_rounding = 5e-10;

// Three realizations of T_k(t) = c_k t^(-2/3) at 5 samples per decade on [1, 1e4], written as
// shockgas-sim writes a run (r = 0: the automatic window rule needs no crossover).
std::string write_power_law_run(const std::string& name) {
    shockgas::SimulationParameters parameters;
    parameters.particles = 1000;
    parameters.collision.restitution = 0.0;
    parameters.collision.velocity_threshold = 1e-2;
    parameters.t_max = 1e4;
    parameters.realizations = 3;
    shockgas::EnsembleResult result;
    result.realizations = 3;
    for (int s = 0; s <= 20; ++s) result.times.push_back(std::pow(10.0, s / 5.0));
    const std::vector<double> prefactor = {0.20, 0.21, 0.23};
    for (int k = 0; k < 3; ++k)
        for (const double t : result.times) {
            result.temperature.push_back(prefactor[static_cast<std::size_t>(k)] * std::pow(t, -decay_exponent));
            result.kinetic_energy.push_back(0.5 * result.temperature.back());
            result.collisions_per_particle.push_back(t);
            result.clusters.push_back(1000.0 / (1.0 + t));
        }
    result.realization_status = {0, 0, 0};
    result.status = "complete";
    result.engine = "exact";
    const auto path = (fs::temp_directory_path() / ("shockgas_commands_" + name + ".h5")).string();
    shockgas::write_output(path, parameters, result);
    return path;
}

shockgas::analysis::AnalysisInvocation decay_invocation() {
    return {"shockgas-analyze decay", "shockgas-analyze decay run.h5 --t-lo 10 --t-hi 1000", {{"t_lo", "10", true}}};
}

TEST(AnalyzeCommands, DecayFitsAPowerLawAndWritesItsFiles) {
    const auto input = write_power_law_run("decay");
    const auto output = (fs::temp_directory_path() / "shockgas_commands_decay_results.h5").string();
    const auto data = (fs::temp_directory_path() / "shockgas_commands_decay.dat").string();
    shockgas::analysis::DecayOptions options;
    options.t_lo = 10.0;
    options.t_hi = 1000.0;
    shockgas::analysis::run_decay(decay_invocation(), input, output, data, "", options);

    const auto results = shockgas::h5::File::open_read(output);
    const auto decay = results.root().open_group("decay");
    EXPECT_NEAR(decay.attribute_double("exponent"), decay_exponent, rounding_tolerance);
    EXPECT_NEAR(decay.attribute_double("exponent_sigma"), 0.0, rounding_tolerance);
    EXPECT_EQ(decay.attribute_double("t_lo"), 10.0);
    EXPECT_EQ(decay.attribute_double("t_hi"), 1000.0);
    EXPECT_EQ(decay.attribute_integer("points"), 11);  // 5 per decade over two decades, both ends included
    EXPECT_EQ(decay.attribute_string("window_rule"), "manual");
    // The results file says how it was made and from what.
    EXPECT_EQ(results.root().attribute_string("command_line"), decay_invocation().command_line);
    EXPECT_EQ(results.root().attribute_string("input_path"), input);
    EXPECT_EQ(results.root().open_group("options").attribute_double("t_lo"), 10.0);

    // The data file: '#' lines, then one row per sample with the ensemble mean.
    std::ifstream table(data);
    std::string line;
    int rows = 0;
    while (std::getline(table, line)) {
        if (line.empty() || line[0] == '#') continue;
        double time = 0, temperature = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf", &time, &temperature), 2) << line;
        EXPECT_NEAR(temperature / ((0.20 + 0.21 + 0.23) / 3 * std::pow(time, -decay_exponent)), 1.0,
                    2 * data_file_rounding);  // both time and T(t) are rounded
        ++rows;
    }
    EXPECT_EQ(rows, 21);
    for (const auto& path : {input, output, data}) fs::remove(path);
}

TEST(AnalyzeCommands, AWindowWithoutSamplesNamesTheInput) {
    const auto input = write_power_law_run("empty_window");
    const auto output = (fs::temp_directory_path() / "shockgas_commands_empty_results.h5").string();
    shockgas::analysis::DecayOptions options;
    options.t_lo = 11.0;  // between two samples (10 and 15.8): no point to fit
    options.t_hi = 12.0;
    try {
        shockgas::analysis::run_decay(decay_invocation(), input, output, "", "", options);
        ADD_FAILURE() << "a window without samples was fitted";
    } catch (const shockgas::InputError& error) {
        EXPECT_NE(std::string(error.what()).find(input), std::string::npos) << error.what();
    }
    EXPECT_FALSE(fs::exists(output)) << "a failed command left a results file";
    fs::remove(input);
}

// The program's request (analyze_command.hpp): checks, then the subcommand's command.
shockgas::analysis::AnalyzeRequest decay_request(const std::string& input, const std::string& output) {
    shockgas::analysis::AnalyzeRequest request;
    request.command = "decay";
    request.invocation = decay_invocation();
    request.input = input;
    request.output = output;
    request.t_lo = 10.0;
    request.t_hi = 1000.0;
    request.t_lo_given = request.t_hi_given = true;
    return request;
}

// The message of the InputError that request throws ("" if none).
std::string analyze_refusal(const shockgas::analysis::AnalyzeRequest& request) {
    return shockgas::testing::input_error_message([&] { shockgas::analysis::run_analyze(request); });
}

TEST(AnalyzeCommands, TheRequestRunsTheSubcommandWithItsWindow) {
    const auto input = write_power_law_run("request");
    const auto output = (fs::temp_directory_path() / "shockgas_commands_request_results.h5").string();
    shockgas::analysis::run_analyze(decay_request(input, output));
    const auto results = shockgas::h5::File::open_read(output);
    const auto decay = results.root().open_group("decay");
    EXPECT_NEAR(decay.attribute_double("exponent"), decay_exponent, rounding_tolerance);
    EXPECT_EQ(decay.attribute_double("t_lo"), 10.0);
    EXPECT_EQ(decay.attribute_double("t_hi"), 1000.0);
    fs::remove(output);

    // A window given but not taken (t_lo_given false) is the automatic one.
    auto automatic = decay_request(input, output);
    automatic.t_lo_given = automatic.t_hi_given = false;
    shockgas::analysis::run_analyze(automatic);
    EXPECT_NE(shockgas::h5::File::open_read(output).root().open_group("decay").attribute_string("window_rule"),
              "manual");
    for (const auto& path : {input, output}) fs::remove(path);
}

TEST(AnalyzeCommands, BadValuesAreRefusedBeforeAnyWork) {
    const auto input = write_power_law_run("refused");
    const auto output = (fs::temp_directory_path() / "shockgas_commands_refused_results.h5").string();
    auto request = decay_request(input, output);
    request.t_lo = 100.0;
    request.t_hi = 10.0;
    EXPECT_EQ(analyze_refusal(request), "--t-hi (10) must be larger than --t-lo (100)");
    request = decay_request(input, output);
    request.t_lo = -1.0;
    EXPECT_EQ(analyze_refusal(request), "--t-lo must be positive and finite, not -1");
    request = decay_request(input, output);
    request.decay.scan_step = 1e-4;
    EXPECT_EQ(analyze_refusal(request).rfind("--scan-step must be finite and at least 0.001 decades, not 0.0001", 0),
              0u);
    request = decay_request(input, output);
    request.decay.data_only = true;
    EXPECT_EQ(analyze_refusal(request),
              "--data-only needs --data FILE: it writes the T(t) table there and nothing else");

    shockgas::analysis::AnalyzeRequest shocks;
    shocks.command = "shocks";
    shocks.input = input;
    shocks.output = output;
    shocks.merge_gap = -1;
    EXPECT_EQ(analyze_refusal(shocks), "--merge-gap must be a whole number at least 0, not -1");
    shockgas::analysis::AnalyzeRequest crossover;
    crossover.command = "crossover";
    crossover.inputs = {input};
    crossover.output = output;
    crossover.crossover.haff_floor = 1.5;
    EXPECT_EQ(analyze_refusal(crossover).rfind("--haff-floor must be below 1", 0), 0u);
    shockgas::analysis::AnalyzeRequest collapse;
    collapse.command = "collapse";
    collapse.inputs = {input};
    collapse.output = output;
    collapse.hazard = "hazard.dat";
    EXPECT_EQ(analyze_refusal(collapse).rfind("--hazard needs --vs N", 0), 0u);
    // An output that names the input (h5::check_not_an_input).
    EXPECT_THROW(shockgas::analysis::run_analyze(decay_request(input, input)), shockgas::h5::Error);
    EXPECT_FALSE(fs::exists(output)) << "a refused request left a results file";
    fs::remove(input);
}

TEST(AnalyzeCommands, CommandLineWordsQuotedAsAShellReadsThem) {
    EXPECT_EQ(shockgas::analysis::shell_quoted("run.h5"), "run.h5");
    EXPECT_EQ(shockgas::analysis::shell_quoted("--t-lo=1e3"), "--t-lo=1e3");
    EXPECT_EQ(shockgas::analysis::shell_quoted("my run.h5"), "'my run.h5'");
    EXPECT_EQ(shockgas::analysis::shell_quoted("it's"), "'it'\\''s'");
    EXPECT_EQ(shockgas::analysis::shell_quoted(""), "''");
}

}  // namespace
