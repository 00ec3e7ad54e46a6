// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-tail's work as the program calls it (shockgas/tail/tail_command.hpp):
// the sampler's parameters from the options, the instanton starts, the summary's
// deepest Phi, a small run end to end, and its progress line (sim/cli).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/cli/progress.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/tail/tail_command.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;

// A request for the tagged cluster at `time` in a window of 2 half_window + 1 sites, with the
// default ladder's targets z_step, 2 z_step, ... z_reach.
shockgas::TailRequest ladder_request(double time, std::int64_t half_window, double z_reach, double z_step) {
    shockgas::TailRequest request;
    request.time = time;
    request.half_window = half_window;
    request.z_reach = z_reach;
    request.z_step = z_step;
    return request;
}

TEST(TailCommand, SamplerParametersFromTheOptions) {
    shockgas::TailRequest request;
    request.half_window = 10;
    request.focus = 3;
    request.bin_width = 0.02;
    const auto p = shockgas::tail_sampler_parameters(request);
    EXPECT_EQ(p.sites, 21);
    EXPECT_EQ(p.focus_begin, 7);  // sites 7 .. 13: the tag (10) and 3 on each side
    EXPECT_EQ(p.focus_end, 14);
    EXPECT_EQ(p.fine_bins_per_output_bin, 20);  // 0.02 / 0.001
    EXPECT_EQ(p.biases, shockgas::tail_bias_ladder(request.z_reach, request.z_step));
    EXPECT_EQ(p.steps_per_bias, 100000);  // the program's defaults, not the sampler's
    EXPECT_EQ(p.burn_in_steps, 10000);
    EXPECT_EQ(p.threads, 0);
    EXPECT_EQ(p.law, shockgas::VelocityLaw::gaussian);

    // No focus, or one wider than the window: the whole window.
    request.focus = 0;
    EXPECT_EQ(shockgas::tail_sampler_parameters(request).focus_begin, 0);
    request.focus = 50;
    EXPECT_EQ(shockgas::tail_sampler_parameters(request).focus_end, 21);

    request.biases = {0.0, 1.0};
    EXPECT_EQ(shockgas::tail_sampler_parameters(request).biases, request.biases);

    auto refused = request;
    refused.focus = -1;
    EXPECT_THROW(shockgas::tail_sampler_parameters(refused), shockgas::InputError);
    refused = request;
    refused.bin_width = 0.0215;  // 21.5 WHAM bins
    EXPECT_THROW(shockgas::tail_sampler_parameters(refused), shockgas::InputError);
    refused.bin_width = 0.0;
    EXPECT_THROW(shockgas::tail_sampler_parameters(refused), shockgas::InputError);
}

TEST(TailCommand, StartsAtTheInstantonOfEachTargetUnlessTold) {
    auto request = ladder_request(100.0, 50, 3.0, 1.0);
    const auto targets = shockgas::tail_ladder_targets(request.z_reach, request.z_step);
    const auto means = shockgas::tail_start_means(request);
    const std::size_t sites = 2 * 50 + 1;
    ASSERT_EQ(means.size(), targets.size() * sites);
    for (std::size_t k = 0; k < targets.size(); ++k) {
        const auto expected = shockgas::tagged_cluster_instanton(targets[k], request.time, request.half_window);
        EXPECT_EQ(std::vector<double>(means.begin() + static_cast<std::ptrdiff_t>(k * sites),
                                      means.begin() + static_cast<std::ptrdiff_t>((k + 1) * sites)),
                  expected)
            << "target z = " << targets[k];
    }
    // Below z = 1.5 the chains start from the prior (mean 0); the deepest target, z = 3, does not.
    const auto nonzero = [&](std::size_t k) {
        return std::any_of(means.begin() + static_cast<std::ptrdiff_t>(k * sites),
                           means.begin() + static_cast<std::ptrdiff_t>((k + 1) * sites), [](double v) { return v != 0.0; });
    };
    EXPECT_FALSE(nonzero(1));  // z = 1
    EXPECT_TRUE(nonzero(targets.size() - 1));

    request.prior_start = true;
    EXPECT_TRUE(shockgas::tail_start_means(request).empty());
    request.prior_start = false;
    request.biases = {0.0, 2.0};
    EXPECT_TRUE(shockgas::tail_start_means(request).empty());
}

TEST(TailCommand, TheSummaryNamesTheDeepestPositivePhi) {
    shockgas::TailEstimate estimate;
    estimate.z = {0.0, 1.0, 2.0, 3.0, 4.0};
    estimate.density = {0.4, 2e-3, 1e-9, 0.0, 3e-7};  // 0 at z = 3: no sample there, not the deepest
    const auto deepest = shockgas::deepest_density(estimate);
    EXPECT_EQ(deepest.density, 1e-9);
    EXPECT_EQ(deepest.z, 2.0);

    shockgas::TailEstimate flat;
    flat.z = {0.0};
    flat.density = {0.0};
    EXPECT_EQ(shockgas::deepest_density(flat).density, 1.0);
    EXPECT_EQ(shockgas::deepest_density(flat).z, 0.0);

    shockgas::TailRequest request;
    request.output = "tail.h5";
    request.time = 1000.0;
    shockgas::TailOutcome outcome;
    outcome.parameters.biases = {0.0, 1.0, 2.0};
    outcome.parameters.chains = 4;
    outcome.estimate = estimate;
    outcome.estimate.evaluations = 12345;
    outcome.estimate.cpu_seconds = 2.34;
    outcome.estimate.wall_seconds = 0.66;
    EXPECT_EQ(shockgas::tail_summary(request, outcome),
              "tail.h5: t = 1000, 3 biases x 4 chains, 12345 evaluations; deepest Phi = 1e-09 at z = 2.000; "
              "2.3 s CPU, 0.7 s wall");
}

TEST(TailCommand, ASmallRunWritesItsFile) {
    auto request = ladder_request(20.0, 20, 1.0, 0.5);
    request.sampler.steps_per_bias = 400;
    request.sampler.burn_in_steps = 40;
    request.sampler.chains = 2;
    request.sampler.threads = 1;
    request.output = shockgas::testing::temp_path("shockgas_tail_command.h5");
    bool sampled = false;
    double last_done = 0.0;
    shockgas::TailHooks hooks;
    hooks.progress = [&](double done, double) { last_done = done; };
    hooks.sampled = [&] { sampled = true; };
    const auto outcome = shockgas::run_tail(request, "test_tail_command", hooks);
    EXPECT_TRUE(sampled);
    EXPECT_LE(last_done, 1.0);
    EXPECT_EQ(outcome.parameters.sites, 41);
    EXPECT_EQ(outcome.parameters.biases.size(), 3u);  // 0, and z = 0.5, 1
    EXPECT_GT(outcome.estimate.evaluations, 0);
    const auto file = shockgas::h5::File::open_read(request.output);
    EXPECT_EQ(file.root().attribute_string("kind"), "far_tail");
    EXPECT_EQ(file.root().attribute_string("observable"), "tagged_cluster_velocity");
    EXPECT_EQ(file.root().attribute_integer("half_window"), 20);
    fs::remove(request.output);

    // An output that cannot be written is refused before the chains run.
    request.output = shockgas::testing::temp_path("no_such_directory/tail.h5");
    sampled = false;
    EXPECT_ANY_THROW(shockgas::run_tail(request, "test_tail_command", hooks));
    EXPECT_FALSE(sampled);
}

TEST(TailCommand, ProgressLineWithItsEta) {
    EXPECT_EQ(shockgas::cli::format_steps_progress("shockgas-tail", 0.25, 40.0),
              "shockgas-tail: progress: 25.0% of the steps  elapsed 40 s  ETA 120 s");
    EXPECT_EQ(shockgas::cli::format_steps_progress("shockgas-tail", 0.0, 3.0),
              "shockgas-tail: progress: 0.0% of the steps  elapsed 3 s  ETA --");
}

}  // namespace
