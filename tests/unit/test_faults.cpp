// SPDX-License-Identifier: GPL-3.0-or-later
// Faults that must not lose work or change results silently (docs/reliability.md), at
// the level of the library: the checkpoint unit's generations and fallback,
// its lock, and the memory plan. End-to-end cases (damaged files resumed bit
// for bit, file-size limits, stale temporaries, two processes) are the
// cli.faults.* tests.
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "shockgas/run/checkpoint.hpp"
#include "shockgas/run/ensemble.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/run/memory_plan.hpp"

namespace {

using shockgas::SimulationParameters;

SimulationParameters small_run() {
    SimulationParameters p;
    p.particles = 200;
    p.collision.restitution = 0.9;
    p.collision.velocity_threshold = 1e-2;
    p.t_max = 50.0;
    p.realizations = 2;
    p.threads = 1;
    p.seed = 5;
    return p;
}

// Writes a checkpoint of the run stopped at once (nothing done yet) to path.
void write_stopped_checkpoint(const SimulationParameters& p, const std::string& path) {
    shockgas::CheckpointOptions options;
    options.path = path;
    options.interval_seconds = 0.0;
    std::atomic<bool> stop{true};
    shockgas::run_ensemble(p, nullptr, &stop, {}, options);
}

// Overwrites bytes in the middle of a file, where its datasets are.
void damage(const std::string& path) {
    const auto size = std::filesystem::file_size(path);
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(size / 2));
    file.write("\xde\xad\xbe\xef\x01\x02\x03", 7);
}

TEST(CheckpointGenerations, SavingKeepsThePreviousAndADamagedOneFallsBackToIt) {
    const SimulationParameters p = small_run();
    const std::string path = "generations.checkpoint";
    shockgas::remove_checkpoints(path);
    write_stopped_checkpoint(p, path);
    EXPECT_FALSE(std::filesystem::exists(shockgas::previous_checkpoint_path(path)));
    write_stopped_checkpoint(p, path);
    ASSERT_TRUE(std::filesystem::exists(shockgas::previous_checkpoint_path(path)))
        << "saving over a checkpoint must keep it as the previous generation";

    std::string notes;
    const auto note = [&](const std::string& text) { notes += text + "\n"; };
    const auto times = shockgas::sample_grid(p);
    auto intact = shockgas::load_checkpoint(path, p, times, note);
    ASSERT_TRUE(intact.has_value());
    EXPECT_EQ(intact->source, path);
    EXPECT_EQ(notes, "") << "an intact checkpoint loads without a note";

    damage(path);
    auto fallback = shockgas::load_checkpoint(path, p, times, note);
    ASSERT_TRUE(fallback.has_value()) << notes;
    EXPECT_EQ(fallback->source, shockgas::previous_checkpoint_path(path));
    EXPECT_NE(notes.find("warning: 'generations.checkpoint' is damaged"), std::string::npos) << notes;
    EXPECT_NE(notes.find("resuming from the previous checkpoint"), std::string::npos) << notes;
    EXPECT_EQ(std::count(notes.begin(), notes.end(), '\n'), 1) << "one warning line";

    notes.clear();
    damage(shockgas::previous_checkpoint_path(path));
    EXPECT_FALSE(shockgas::load_checkpoint(path, p, times, note).has_value());
    EXPECT_NE(notes.find("starting from t = 0"), std::string::npos) << notes;
    EXPECT_EQ(std::count(notes.begin(), notes.end(), '\n'), 1) << "one warning line";

    shockgas::remove_checkpoints(path);
    notes.clear();
    EXPECT_FALSE(shockgas::load_checkpoint(path, p, times, note).has_value());
    EXPECT_EQ(notes, "") << "no checkpoint at all is no warning";
}

TEST(CheckpointGenerations, ADamagedCheckpointNeitherEndsNorChangesTheRun) {
    const SimulationParameters p = small_run();
    const std::string path = "damaged_run.checkpoint";
    shockgas::remove_checkpoints(path);
    write_stopped_checkpoint(p, path);
    damage(path);
    shockgas::CheckpointOptions options;
    options.path = path;
    options.resume = true;
    options.interval_seconds = 0.0;
    std::string notes;
    options.note = [&](const std::string& text) { notes += text + "\n"; };
    const auto resumed = shockgas::run_ensemble(p, nullptr, nullptr, {}, options);
    const auto reference = shockgas::run_ensemble(p, nullptr);
    EXPECT_NE(notes.find("starting from t = 0"), std::string::npos) << notes;
    EXPECT_EQ(resumed.total_collisions, reference.total_collisions);
    EXPECT_EQ(resumed.temperature, reference.temperature);
    shockgas::remove_checkpoints(path);
}

TEST(CheckpointLock, ASecondHolderIsRefusedUntilTheFirstLetsGo) {
    const std::string path = "locked.checkpoint";
    {
        const shockgas::CheckpointLock first(path);
        try {
            const shockgas::CheckpointLock second(path);
            FAIL() << "a second lock on the same checkpoint was granted";
        } catch (const shockgas::InputError& error) {
            EXPECT_NE(std::string(error.what()).find("is in use by another running shockgas-sim"), std::string::npos)
                << error.what();
        }
    }
    EXPECT_FALSE(std::filesystem::exists(path + ".lock")) << "the lock file is removed when released";
    EXPECT_NO_THROW(shockgas::CheckpointLock again(path));
}

// When a run ends, shockgas-sim removes only checkpoints under the checkpoint's
// name (and HDF5 files too damaged to tell, which is what --resume passes
// over), never an output given as --checkpoint or the init file: anything else
// is kept and returned.
TEST(CheckpointFiles, OnlyCheckpointsAreRemoved) {
    namespace fs = std::filesystem;
    const SimulationParameters p = small_run();
    const std::string path = "removal.checkpoint", previous = shockgas::previous_checkpoint_path(path);
    fs::remove(path);
    fs::remove(previous);
    write_stopped_checkpoint(p, path);
    shockgas::h5::write_atomically(previous, [](shockgas::h5::Group& root) { root.set_attribute("a", 1.0); });
    EXPECT_EQ(shockgas::remove_checkpoints(path), std::vector<std::string>{previous});
    EXPECT_FALSE(fs::exists(path)) << "the checkpoint is removed";
    EXPECT_TRUE(fs::exists(previous)) << "an HDF5 file without /checkpoint is kept";

    std::ofstream(path) << "notes, not a checkpoint\n";
    write_stopped_checkpoint(p, "removal.damaged");
    fs::rename("removal.damaged", previous);
    fs::resize_file(previous, fs::file_size(previous) / 2);  // truncated: HDF5 cannot open it
    EXPECT_EQ(shockgas::remove_checkpoints(path), std::vector<std::string>{path});
    EXPECT_TRUE(fs::exists(path)) << "a text file is kept";
    EXPECT_FALSE(fs::exists(previous)) << "a damaged checkpoint is removed";
    fs::remove(path);
}

// Refused before a run starts: checkpoint files that are the run's output or
// init file (saving renames over them, the end removes them), and files at
// the checkpoint's names that are not checkpoints.
TEST(CheckpointFiles, APathThatWouldDestroyAnotherFileIsRefused) {
    namespace fs = std::filesystem;
    const auto refusal = [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& others) {
        try {
            shockgas::check_checkpoint_path(path, others);
        } catch (const shockgas::InputError& error) {
            return std::string(error.what());
        }
        return std::string();
    };
    const std::string path = "paths.checkpoint", previous = shockgas::previous_checkpoint_path(path),
                      lock = path + ".lock";
    for (const auto& file : {path, previous, lock}) fs::remove(file);
    // Files not yet there are compared by name, existing ones as files.
    EXPECT_NE(refusal(path, {{"output", path}}).find("checkpoint 'paths.checkpoint' is the output 'paths.checkpoint'"),
              std::string::npos);
    EXPECT_NE(refusal(path, {{"output", "./" + previous}}).find("keeps its older generation in 'paths.checkpoint.previous', which is the output"),
              std::string::npos);
    EXPECT_NE(refusal(path, {{"init file", fs::absolute(lock).string()}}).find("is locked through"), std::string::npos);
    EXPECT_EQ(refusal(path, {{"output", "other.h5"}, {"init file", ""}}), "");
    // A name that reads as another checkpoint's older generation (its lock and clean-up went to that one).
    EXPECT_NE(refusal(previous, {}).find("checkpoint 'paths.checkpoint.previous' ends in '.previous', the ending of "
                                         "a checkpoint's older generation"),
              std::string::npos);

    shockgas::h5::write_atomically(path, [](shockgas::h5::Group& root) { root.set_attribute("a", 1.0); });
    EXPECT_NE(refusal(path, {}).find("is not a shockgas checkpoint (an HDF5 file without /checkpoint)"),
              std::string::npos);
    fs::remove(path);
    std::ofstream(previous) << "text\n";
    EXPECT_NE(refusal(path, {}).find("'paths.checkpoint.previous' exists and is not a shockgas checkpoint (not an "
                                     "HDF5 file)"),
              std::string::npos);
    fs::remove(previous);
    fs::create_directory(previous);
    EXPECT_NE(refusal(path, {}).find("(not a regular file)"), std::string::npos);
    fs::remove(previous);
    std::ofstream(lock) << "a diary\n";
    EXPECT_NE(refusal(path, {}).find("is not a checkpoint lock"), std::string::npos);
    std::ofstream(lock) << "4242\n";  // a lock left by a killed run
    write_stopped_checkpoint(small_run(), path);
    EXPECT_EQ(refusal(path, {{"output", "paths.h5"}}), "") << "a checkpoint and a lock are what belong there";
    fs::resize_file(path, fs::file_size(path) / 2);
    EXPECT_EQ(refusal(path, {}), "") << "a damaged checkpoint is for --resume to pass over, not a refusal";
    shockgas::remove_checkpoints(path);
    fs::remove(lock);
}

// A full disk (ENOSPC), made real by pointing the temporary file at
// /dev/full, whose every write fails so: one error naming the target and the
// system's cause, the temporary file removed, no target left.
TEST(FullDisk, AWriteThatFailsNamesTheFileAndCauseAndLeavesNothing) {
    const std::string target = "full_disk.h5";
    const std::string temporary = target + ".tmp." + std::to_string(::getpid());
    std::filesystem::remove(target);
    std::filesystem::remove(temporary);
    std::filesystem::create_symlink("/dev/full", temporary);
    const std::vector<double> values(1 << 16, 1.0);
    try {
        shockgas::h5::write_atomically(target, [&](shockgas::h5::Group& root) { root.write("values", values); });
        FAIL() << "a write to a full disk succeeded";
    } catch (const shockgas::h5::Error& error) {
        EXPECT_EQ(error.cause, "No space left on device") << error.what();
        EXPECT_NE(std::string(error.what()).find("cannot write 'full_disk.h5': No space left on device"),
                  std::string::npos)
            << error.what();
    }
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(temporary))) << "temporary file left";
    EXPECT_FALSE(std::filesystem::exists(target));
}

// The documented costs (memory_plan.cpp, docs/reliability.md): 128 bytes per
// particle for a running realization's engine, 136 more with checkpoints,
// 16 MiB for the program, 32 bytes per particle per stored state.
constexpr double per_particle_with_checkpoints = 128.0 + 136.0;
constexpr double program = 16.0 * (1 << 20);

TEST(MemoryPlan, FewerRealizationsAtOnceWhenAllDoNotFitAndNoneWhenOneDoesNot) {
    SimulationParameters p = small_run();
    p.particles = 1000000;
    p.realizations = 4;
    p.snapshot_times = {10.0};
    const auto plan_for = [&](double budget) { return shockgas::plan_memory(p, 4, true, budget); };
    const auto probe = plan_for(1e15);
    EXPECT_EQ(probe.realizations_at_once, 4);
    EXPECT_EQ(probe.per_realization_bytes, 1e6 * per_particle_with_checkpoints);
    // Shared: the program plus one snapshot (32 bytes per particle) of each of
    // the 4 realizations, and their small time-series rows.
    EXPECT_GE(probe.shared_bytes, program + 4 * 32.0e6);
    EXPECT_LT(probe.shared_bytes, program + 4 * 32.0e6 + 1e5);
    EXPECT_EQ(plan_for(probe.need_bytes(2)).realizations_at_once, 2);
    EXPECT_EQ(plan_for(probe.need_bytes(2) - 1.0).realizations_at_once, 1);
    EXPECT_EQ(plan_for(probe.need_bytes(1) - 1.0).realizations_at_once, 0);
    EXPECT_EQ(shockgas::plan_memory(p, 4, false, 1e15).per_realization_bytes, 1e6 * 128.0)
        << "without checkpoints a realization needs only its engine";
    // delta = 0 (collapse possible): the event engine's copy to go back to, 176 bytes in all.
    p.collision.velocity_threshold = 0.0;
    EXPECT_EQ(shockgas::plan_memory(p, 4, false, 1e15).per_realization_bytes, 1e6 * 176.0);
}

// A refusal names what does not fit: many realizations of a small N keep
// records (time series rows) that do not fit although one realization does,
// and lowering N would not help; a single realization too large for the
// budget is N's (and its snapshots' and bins') to lower.
TEST(MemoryPlan, ARefusalNamesTheRealizationsRecordsWhenOneRealizationAloneFits) {
    SimulationParameters p = small_run();
    p.particles = 1000;
    p.realizations = 100000000;
    const double budget = 8.0 * (1 << 30);
    const auto many = shockgas::plan_memory(p, 1, false, budget);
    ASSERT_EQ(many.realizations_at_once, 0);
    const std::string records = shockgas::memory_refusal(p, many, budget, "--max-memory");
    EXPECT_NE(records.find("100000000 realizations need about"), std::string::npos) << records;
    EXPECT_NE(records.find("--first-realization"), std::string::npos) << records;
    EXPECT_NE(records.find("shockgas-merge"), std::string::npos) << records;
    EXPECT_EQ(records.find("lower N"), std::string::npos) << records;
    // The most it says to give each run fits, and one more does not.
    const auto most_start = records.find("at most ") + 8;
    const int most = std::stoi(records.substr(most_start));
    p.realizations = most;
    EXPECT_EQ(shockgas::plan_memory(p, 1, false, budget).realizations_at_once, 1);
    p.realizations = most + 1;
    EXPECT_EQ(shockgas::plan_memory(p, 1, false, budget).realizations_at_once, 0);

    p.particles = 1000000000;
    p.realizations = 2;
    const auto large = shockgas::plan_memory(p, 1, false, budget);
    ASSERT_EQ(large.realizations_at_once, 0);
    const std::string one = shockgas::memory_refusal(p, large, budget, "--max-memory");
    EXPECT_NE(one.find("one realization of N = 1000000000 needs about"), std::string::npos) << one;
    EXPECT_NE(one.find("lower N"), std::string::npos) << one;
}

// Histograms: 16 bytes per bin for each realization (its row and the output's
// copy) and 16 once (edges, the writer's buffer), as measured (memory_plan.cpp).
TEST(MemoryPlan, CountsTheHistogramsRowsAndTheirCopies) {
    SimulationParameters p = small_run();
    p.particles = 1000;
    p.realizations = 4;
    p.histogram_times = {10.0, 20.0};
    p.histogram_bins = 1000000;
    const auto plan = shockgas::plan_memory(p, 4, false, 1e15);
    const double bins = 2.0 * (1000000 + 2);
    EXPECT_GE(plan.shared_bytes, program + (16.0 + 4 * 16.0) * bins);
    EXPECT_LT(plan.shared_bytes, program + (16.0 + 4 * 16.0) * bins + 1e5);
}

TEST(MemoryPlan, SizesParseInPowersOf1024AndNonsenseIsRefused) {
    EXPECT_EQ(shockgas::parse_memory_size("123456"), 123456.0);
    EXPECT_EQ(shockgas::parse_memory_size("500M"), 500.0 * 1024 * 1024);
    EXPECT_EQ(shockgas::parse_memory_size("8G"), 8.0 * 1024 * 1024 * 1024);
    EXPECT_EQ(shockgas::parse_memory_size("1.5GiB"), 1.5 * 1024 * 1024 * 1024);
    EXPECT_EQ(shockgas::parse_memory_size("2kb"), 2048.0);
    for (const char* bad : {"", "3X", "-1G", "G", "nan", "0"})
        EXPECT_THROW(shockgas::parse_memory_size(bad), shockgas::InputError) << bad;
    std::string source;
    const double available = shockgas::available_memory_bytes(&source);
    EXPECT_GT(available, 0.0) << "Linux always has /proc/meminfo";
    EXPECT_FALSE(source.empty());
}

}  // namespace
