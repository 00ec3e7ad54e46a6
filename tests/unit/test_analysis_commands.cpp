// The commands of shockgas-analyze called in-process, as the program calls them
// (shockgas/analysis/commands.hpp): a run file in, a results file and a data file out.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/analysis/commands.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"

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

}  // namespace
