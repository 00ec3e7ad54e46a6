// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-dump's and shockgas-merge's work as the programs call it
// (shockgas/analysis/dump.hpp, shockgas/io/merge.hpp): gnuplot variables from a group's
// attributes, the snapshot rows of one realization, and parts joined into one file.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "shockgas/analysis/dump.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/merge.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/run/ensemble.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::testing::read_text;
using shockgas::testing::temp_path;

bool has_line(const std::string& text, const std::string& line) {
    return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

// A small run of `realizations` realizations with snapshots at t = 5 and 10, written as shockgas-sim writes it.
std::string write_run(const std::string& name, std::int64_t first, int realizations) {
    shockgas::SimulationParameters p;
    p.particles = 50;
    p.t_max = 10;
    p.first_realization = first;
    p.realizations = realizations;
    p.snapshot_times = {5, 10};
    const auto path = temp_path(name);
    shockgas::write_output(path, p, shockgas::run_ensemble(p, nullptr));
    return path;
}

TEST(Dump, AttributesAsGnuplotVariables) {
    const auto path = temp_path("dump_attributes.h5");
    {
        shockgas::h5::AtomicFile file(path);
        auto group = file.root().create_group("decay");
        group.set_attribute("exponent", 0.6666666666666666);
        group.set_attribute("points", std::int64_t{11});
        group.set_attribute("sigma", std::numeric_limits<double>::quiet_NaN());
        group.set_attribute("rule", "say \"auto\"");
        group.create_group("window").set_attribute("t_lo", 10.0);
        file.commit();
    }
    const std::string text = shockgas::gnuplot_variables(path, "/decay", "fit", false);
    EXPECT_TRUE(has_line(text, "fit_exponent = 0.6666666667")) << text;
    EXPECT_TRUE(has_line(text, "fit_points = 11")) << text;
    EXPECT_TRUE(has_line(text, "fit_sigma = NaN")) << text;  // gnuplot reads NaN, not nan
    EXPECT_TRUE(has_line(text, "fit_rule = \"say 'auto'\"")) << text;
    EXPECT_EQ(text.find("t_lo"), std::string::npos) << "a subgroup without --recursive";
    const std::string recursive = shockgas::gnuplot_variables(path, "decay/", "d", true);
    EXPECT_TRUE(has_line(recursive, "d_window_t_lo = 10")) << recursive;
    EXPECT_THROW(shockgas::gnuplot_variables(path, "/absent", "fit", false), shockgas::h5::Error);
    fs::remove(path);
}

TEST(Dump, SnapshotRowsOfOneRealization) {
    const auto run = write_run("dump_run.h5", 0, 2);
    const auto states = shockgas::read_realization_snapshots(run, 1);
    ASSERT_EQ(states.size(), 2u);  // t = 5 and 10
    EXPECT_EQ(states[0].time, 5.0);
    EXPECT_EQ(states[1].time, 10.0);

    shockgas::DumpRequest request;
    request.input = run;
    request.realization = 1;
    request.output = temp_path("dump_rows.txt");
    shockgas::run_dump(request);
    const std::string text = read_text(request.output);
    EXPECT_EQ(text.rfind("# time position velocity mass first_particle  (from " + run + ")\n", 0), 0u);
    std::size_t rows = 0;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && line[0] != '#') ++rows;
    EXPECT_EQ(rows, states[0].size() + states[1].size());

    // A realization the file does not have, and a negative one, are named.
    try {
        shockgas::read_realization_snapshots(run, 2);
        ADD_FAILURE() << "realization 2 of 2 was read";
    } catch (const shockgas::InputError& error) {
        EXPECT_EQ(std::string(error.what()), fmt::format("--realization 2: '{}' has 2 realizations (0 to 1)", run));
    }
    EXPECT_THROW(shockgas::read_realization_snapshots(run, -1), shockgas::InputError);
    // The text may not replace its input.
    request.output = run;
    EXPECT_THROW(shockgas::run_dump(request), shockgas::h5::Error);
    fs::remove(temp_path("dump_rows.txt"));
    fs::remove(run);
}

TEST(Merge, PartsJoinIntoOneFileAndTheSummaryCountsThem) {
    const std::vector<std::string> parts = {write_run("merge_part0.h5", 0, 2), write_run("merge_part2.h5", 2, 3)};
    const auto output = temp_path("merge_whole.h5");
    const auto outcome = shockgas::merge_parts(parts, output, "test_dump_merge");
    EXPECT_EQ(outcome.realizations, 5);
    EXPECT_EQ(outcome.parts, 2u);
    EXPECT_EQ(outcome.status, "complete");
    EXPECT_EQ(shockgas::merge_summary(outcome, output), "5 realizations from 2 parts -> " + output + " (complete)");
    const auto merged = shockgas::read_output(output);
    EXPECT_EQ(merged.parameters.realizations, 5);
    EXPECT_EQ(merged.merged_from.size(), 2u);

    EXPECT_EQ(shockgas::merge_summary({1, 1, "interrupted"}, "x.h5"), "1 realization from 1 part -> x.h5 (interrupted)");
    // A part named as the output would be replaced by the merge.
    EXPECT_THROW(shockgas::merge_parts(parts, parts[0], "test_dump_merge"), shockgas::h5::Error);
    for (const auto& path : parts) fs::remove(path);
    fs::remove(output);
}

}  // namespace
