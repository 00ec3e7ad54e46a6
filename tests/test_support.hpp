// Helpers shared by the test executables (header only, tests only).
#pragma once

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/run/ensemble.hpp"
#include "shockgas/model/observables.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::testing {

// One-sigma coverage of a jackknife sigma from R samples over `trials` independent trials: at best
// (estimate - truth) / sigma follows Student's t with R - 1 degrees of freedom, so the coverage must
// not fall below P(|t_(R-1)| < 1) = student_coverage (a sigma too small), nor rise above the Gaussian
// 0.6827 (a sigma too large), each by more than 3 binomial standard errors (a 0.3% false alarm).
inline void expect_jackknife_coverage(int inside, int trials, double student_coverage, const std::string& what) {
    constexpr double gaussian_coverage = 0.6827;
    const double binomial = 3.0 * std::sqrt(student_coverage * (1.0 - student_coverage) / trials);
    const double coverage = static_cast<double>(inside) / trials;
    std::printf("%s: one-sigma coverage %.3f over %d trials (Student %.3f - %.3f ... Gaussian %.3f + %.3f)\n",
                what.c_str(), coverage, trials, student_coverage, binomial, gaussian_coverage, binomial);
    EXPECT_GT(coverage, student_coverage - binomial) << what;
    EXPECT_LT(coverage, gaussian_coverage + binomial) << what;
}

// A hand-made ring: the given positions and velocities, unit masses.
inline InitialCondition unit_masses(double ring_length, std::vector<double> position, std::vector<double> velocity) {
    InitialCondition initial;
    initial.ring_length = ring_length;
    initial.position = std::move(position);
    initial.velocity = std::move(velocity);
    initial.mass.assign(initial.position.size(), 1.0);
    return initial;
}

// Exact equality of two ring states, element by element (doubles compared
// with ==, so -0.0 vs 0.0 would pass, but any last-bit difference fails): the
// check behind every "bit-identical" claim between engines or runs.
inline void expect_identical(const ClusterState& a, const ClusterState& b, const std::string& where) {
    ASSERT_EQ(a.time, b.time) << where;
    ASSERT_EQ(a.frame_velocity, b.frame_velocity) << where;
    ASSERT_EQ(a.size(), b.size()) << where;
    for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a.first_particle[k], b.first_particle[k]) << where << " cluster " << k;
        ASSERT_EQ(a.position[k], b.position[k]) << where << " cluster " << k;
        ASSERT_EQ(a.velocity[k], b.velocity[k]) << where << " cluster " << k;
        ASSERT_EQ(a.mass[k], b.mass[k]) << where << " cluster " << k;
    }
    const auto moments_a = velocity_moments(a);
    const auto moments_b = velocity_moments(b);
    ASSERT_EQ(moments_a.temperature, moments_b.temperature) << where;
}

// The same for two engines' current states and collision counts.
inline void expect_identical(const Engine& a, const Engine& b, const std::string& where) {
    ClusterState state_a;
    ClusterState state_b;
    a.clusters(state_a);
    b.clusters(state_b);
    expect_identical(state_a, state_b, where);
    EXPECT_EQ(a.collisions(), b.collisions()) << where;
}

// Checkpoints every 20 ms into a fresh file <name>.checkpoint, counting them
// in `written` (the driver's note for each one starts "checkpoint:").
inline CheckpointOptions frequent_checkpoints(const std::string& name, std::atomic<int>& written) {
    CheckpointOptions options;
    // In the system's temporary folder, never the working directory: a test binary run by hand from the
    // source tree must not leave checkpoints (and their ".previous" generation) where git would see them.
    // The process id keeps two build trees' test runs at the same time apart.
    options.path = (std::filesystem::temp_directory_path() / ("shockgas_test_" + std::to_string(::getpid()) + "_" + name + ".checkpoint")).string();
    std::filesystem::remove(options.path);
    std::filesystem::remove(options.path + ".previous");
    options.interval_seconds = 0.02;
    options.note = [&written](const std::string& text) { written += text.rfind("checkpoint:", 0) == 0 ? 1 : 0; };
    return options;
}

// Makes the run of `options` stop (as Ctrl-C does) once `count` checkpoints
// are written: from the note of that checkpoint, in the thread that wrote it,
// so that the rest of the run is still ahead (a polling thread waiting for a
// later one could be scheduled after the run had ended on a loaded machine:
// 1 run in 24 failed so).
inline void stop_after_checkpoints(CheckpointOptions& options, const std::atomic<int>& written,
                                   std::atomic<bool>& stop, int count) {
    options.note = [&written, &stop, count, note = options.note](const std::string& text) {
        note(text);
        if (written.load() >= count) stop.store(true);
    };
}

// The ensemble run of `p` with checkpoints every 20 ms (named `name`) against
// the same run without: pausing a realization to deposit its state must change
// nothing, bit for bit. Returns both results for further checks.
inline std::pair<EnsembleResult, EnsembleResult> run_with_and_without_checkpoint_pauses(
    const SimulationParameters& p, const std::string& name) {
    EnsembleResult reference = run_ensemble(p, nullptr);
    std::atomic<int> written{0};
    const CheckpointOptions options = frequent_checkpoints(name, written);
    EnsembleResult paused = run_ensemble(p, nullptr, nullptr, {}, options);
    EXPECT_GE(written.load(), 2) << "the run ended before checkpoints were taken: the test did not test";
    EXPECT_EQ(paused.temperature, reference.temperature);
    EXPECT_EQ(paused.collisions_per_particle, reference.collisions_per_particle);
    std::filesystem::remove(options.path);
    std::filesystem::remove(options.path + ".previous");
    return {std::move(reference), std::move(paused)};
}

}  // namespace shockgas::testing
