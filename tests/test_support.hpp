// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers shared by the test executables (header only, tests only).
#pragma once

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/run/ensemble.hpp"
#include "shockgas/model/observables.hpp"
#include "shockgas/model/parameters.hpp"
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

// Bitwise equality of doubles, NaN equal to NaN (unreached samples, the
// switch time of an engine that never switches).
inline bool same(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
    return true;
}

// Two ensemble results alike bit for bit: every sample table, record and count.
inline void expect_same_result(const EnsembleResult& a, const EnsembleResult& b) {
    EXPECT_EQ(a.status, b.status);
    EXPECT_TRUE(same(a.times, b.times));
    EXPECT_TRUE(same(a.temperature, b.temperature));
    EXPECT_TRUE(same(a.collisions_per_particle, b.collisions_per_particle));
    EXPECT_TRUE(same(a.clusters, b.clusters));
    EXPECT_TRUE(same(a.kinetic_energy, b.kinetic_energy));
    EXPECT_EQ(a.realization_status, b.realization_status);
    EXPECT_TRUE(same(a.engine_switch_time, b.engine_switch_time));
    EXPECT_EQ(a.total_collisions, b.total_collisions);
    ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
    for (std::size_t s = 0; s < a.snapshots.size(); ++s) {
        EXPECT_EQ(a.snapshots[s].realization, b.snapshots[s].realization);
        expect_identical(a.snapshots[s].state, b.snapshots[s].state, "snapshot");
    }
    ASSERT_EQ(a.histograms.size(), b.histograms.size());
    for (std::size_t h = 0; h < a.histograms.size(); ++h) EXPECT_TRUE(same(a.histograms[h].counts, b.histograms[h].counts));
}

// The paper's gas r = 0.9, delta = 1e-2 (elastic sub-threshold) through the
// ensemble driver: N = 20000 to t = 300, three realizations on two threads,
// a snapshot and two histograms. Sized so that a run takes a few hundred
// milliseconds on one core: long enough for several checkpoints at a 20 ms
// interval.
inline SimulationParameters checkpoint_ensemble() {
    SimulationParameters p;
    p.particles = 20000;
    p.collision = {0.9, 1e-2, Subthreshold::elastic};
    p.t_max = 300.0;
    p.realizations = 3;
    p.threads = 2;
    p.seed = 7;
    p.snapshot_times = {50.0};
    p.histogram_times = {30.0, 300.0};
    return p;
}

// An ensemble of the elastic r = 0.9, delta = 1e-2 gas through the driver,
// on `engine`, two realizations.
inline SimulationParameters elastic_ensemble(std::int64_t particles, double t_max, const std::string& engine) {
    SimulationParameters p;
    p.particles = particles;
    p.collision = {0.9, 0.01, Subthreshold::elastic};
    p.t_max = t_max;
    p.realizations = 2;
    p.engine = engine;
    return p;
}

// Times first, first 10^(1/per_decade), ... up to last.
inline std::vector<double> log_times(double first, double last, int per_decade) {
    std::vector<double> times;
    for (int k = 0;; ++k) {
        const double t = first * std::pow(10.0, k / static_cast<double>(per_decade));
        if (t > last) break;
        times.push_back(t);
    }
    return times;
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

// A file named `name` in the test's temporary folder.
inline std::string temp_path(const std::string& name) {
    return (std::filesystem::path(::testing::TempDir()) / name).string();
}

// The whole text of a file ("" if it cannot be read).
inline std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The message of the InputError that `work` throws, "" if it throws none (other exceptions pass).
template <class Work>
std::string input_error_message(Work&& work) {
    try {
        work();
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

}  // namespace shockgas::testing
