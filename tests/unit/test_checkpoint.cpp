// SPDX-License-Identifier: GPL-3.0-or-later
// Checkpoints (stability issue, "runs that survive being killed"): a damaged
// engine state is refused; a run stopped mid-way and resumed from its
// checkpoint file gives the uninterrupted run's result exactly; a checkpoint
// of another run is refused, naming what differs; and the file keeps engine
// states bit for bit. That an engine restored from a snapshot continues bit
// for bit, and that pausing a run for checkpoints changes nothing, is every
// engine's contract (test_engine_contract.cpp).
//
// Every comparison here is exact (==, NaN == NaN): the same seeds and the
// same arithmetic must give the same doubles, so no tolerance is needed and
// any difference is a bug.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../test_support.hpp"

#include "shockgas/run/checkpoint.hpp"
#include "shockgas/engines/engine.hpp"
#include "shockgas/run/ensemble.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace {

using shockgas::CheckpointOptions;
using shockgas::EnsembleResult;
using shockgas::EngineSnapshot;
using shockgas::SimulationParameters;
using shockgas::Subthreshold;
using shockgas::testing::checkpoint_ensemble;
using shockgas::testing::expect_same_result;
using shockgas::testing::same;

SimulationParameters parameters(std::int64_t particles, double restitution, double threshold, Subthreshold mechanism) {
    SimulationParameters p;
    p.particles = particles;
    p.collision.restitution = restitution;
    p.collision.velocity_threshold = threshold;
    p.collision.subthreshold = mechanism;
    return p;
}

TEST(EngineSnapshot, DamagedStateIsRefused) {
    const SimulationParameters p = parameters(100, 0.5, 1e-2, Subthreshold::elastic);
    const auto initial = shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), 1, 0);
    auto engine = shockgas::make_engine(p, initial, nullptr);
    ASSERT_TRUE(engine->advance_to(5.0));
    auto snapshot = *engine->snapshot();
    auto short_array = snapshot;
    short_array.reals["velocity"].pop_back();
    EXPECT_THROW(shockgas::restore_engine(short_array, p, initial, nullptr), shockgas::InputError);
    auto bad_link = snapshot;
    bad_link.integers["next"][3] = 100000;
    EXPECT_THROW(shockgas::restore_engine(bad_link, p, initial, nullptr), shockgas::InputError);
    auto unknown = snapshot;
    unknown.kind = "warp";
    EXPECT_THROW(shockgas::restore_engine(unknown, p, initial, nullptr), shockgas::InputError);
}

TEST(Checkpoint, StoppedRunResumedFromItsFileEqualsUninterruptedRun) {
    const SimulationParameters p = checkpoint_ensemble();
    const EnsembleResult reference = shockgas::run_ensemble(p, nullptr);

    std::atomic<int> written{0};
    CheckpointOptions options = shockgas::testing::frequent_checkpoints("stopped", written);
    std::atomic<bool> stop{false};
    // Stopped at the first periodic checkpoint, so that most of the run is still ahead.
    shockgas::testing::stop_after_checkpoints(options, written, stop, 1);
    const EnsembleResult stopped = shockgas::run_ensemble(p, nullptr, &stop, {}, options);
    ASSERT_EQ(stopped.status, "interrupted") << "the run ended before it was stopped: the test did not test";
    ASSERT_TRUE(std::filesystem::exists(options.path));
    const auto checkpoint = shockgas::read_checkpoint(options.path);
    EXPECT_FALSE(checkpoint.engines.empty()) << "no realization was caught mid-way";

    CheckpointOptions resume = options;
    resume.resume = true;
    resume.interval_seconds = 0.0;
    std::string resumed_note;
    resume.note = [&](const std::string& text) {
        if (text.rfind("resuming", 0) == 0) resumed_note = text;
    };
    const EnsembleResult resumed = shockgas::run_ensemble(p, nullptr, nullptr, {}, resume);
    EXPECT_NE(resumed_note, "") << "the checkpoint was not used";
    expect_same_result(reference, resumed);
}

// --resume over an output that is already the run's finished result does
// nothing; anything else (no output, an interrupted one, another run's, one
// beside a checkpoint of either generation, a file that is no output) is not
// taken for one, and the run goes on as --resume always did.
TEST(Checkpoint, OnlyAFinishedOutputOfThisRunWithNoCheckpointLeftIsTakenAsDone) {
    namespace fs = std::filesystem;
    SimulationParameters p = parameters(200, 0.9, 1e-2, Subthreshold::elastic);
    p.t_max = 20.0;
    p.realizations = 2;
    p.threads = 1;
    const std::string stem = (fs::temp_directory_path() / ("shockgas_test_" + std::to_string(::getpid()) + "_done")).string();
    const std::string output = stem + ".h5", checkpoint = shockgas::checkpoint_path_for(output);
    for (const std::string& file : {output, checkpoint, checkpoint + ".previous"}) fs::remove(file);
    const std::vector<std::string> checkpoints{checkpoint};
    EXPECT_FALSE(shockgas::is_finished_output_of_run(output, checkpoints, p)) << "no output";

    EnsembleResult result = shockgas::run_ensemble(p, nullptr);
    ASSERT_EQ(result.status, "complete");
    shockgas::write_output(output, p, result);
    EXPECT_TRUE(shockgas::is_finished_output_of_run(output, checkpoints, p));
    // Only a regular file that reads as this output is taken for it: not a
    // link to it (check_writable refuses writing through one), nor what is
    // left of it when truncated or emptied, nor another program's file that
    // has a /timeseries.
    {
        const std::string other = stem + "_other.h5";
        fs::remove(other);
        fs::create_symlink(output, other);
        EXPECT_FALSE(shockgas::is_finished_output_of_run(other, checkpoints, p)) << "a symbolic link to it";
        fs::remove(other);
        fs::copy_file(output, other);
        fs::resize_file(other, fs::file_size(other) / 2);
        EXPECT_FALSE(shockgas::is_finished_output_of_run(other, checkpoints, p)) << "truncated";
        fs::resize_file(other, 0);
        EXPECT_FALSE(shockgas::is_finished_output_of_run(other, checkpoints, p)) << "empty";
        fs::remove(other);
        shockgas::h5::write_atomically(other, [](shockgas::h5::Group& root) { root.create_group("timeseries"); });
        EXPECT_FALSE(shockgas::is_finished_output_of_run(other, checkpoints, p)) << "another program's file";
        fs::remove(other);
    }
    for (const auto& [what, change] :
         std::vector<std::pair<std::string, void (*)(SimulationParameters&)>>{
             {"t_max", [](SimulationParameters& q) { q.t_max = 10.0; }},
             {"seed", [](SimulationParameters& q) { q.seed = 2; }},
             {"realizations", [](SimulationParameters& q) { q.realizations = 3; }},
             {"first_realization", [](SimulationParameters& q) { q.first_realization = 1; }},
             // The same run by another engine is another run (a user review, 2026-11-27: --resume
             // --engine passthrough took an event engine's output as its own).
             {"engine", [](SimulationParameters& q) { q.engine = "hybrid"; }}}) {
        SimulationParameters other = p;
        change(other);
        EXPECT_FALSE(shockgas::is_finished_output_of_run(output, checkpoints, other)) << "another " << what;
    }
    for (const std::string& generation : {checkpoint, checkpoint + ".previous"}) {
        { std::ofstream touch(generation); }
        EXPECT_FALSE(shockgas::is_finished_output_of_run(output, checkpoints, p)) << "beside " << generation;
        fs::remove(generation);
    }
    result.status = "interrupted";
    shockgas::write_output(output, p, result);
    EXPECT_FALSE(shockgas::is_finished_output_of_run(output, checkpoints, p)) << "interrupted";
    { std::ofstream text(output); text << "not an output\n"; }
    EXPECT_FALSE(shockgas::is_finished_output_of_run(output, checkpoints, p)) << "not an output";
    fs::remove(output);
}

// --resume with a checkpoint of another run (a mistyped option) is refused
// before any work, naming each parameter that differs with both values, and
// the checkpoint is kept: continuing would have overwritten it.
TEST(Checkpoint, CheckpointOfAnotherRunIsRefusedNamingTheDifferences) {
    SimulationParameters p = checkpoint_ensemble();
    p.realizations = 2;
    p.t_max = 60.0;
    p.histogram_times = {30.0};
    std::atomic<int> written{0};
    CheckpointOptions options = shockgas::testing::frequent_checkpoints("other_run", written);
    std::atomic<bool> stop{true};  // stopped at once: a checkpoint with nothing done
    shockgas::run_ensemble(p, nullptr, &stop, {}, options);
    ASSERT_TRUE(std::filesystem::exists(options.path));
    options.resume = true;
    std::string notes;
    options.note = [&](const std::string& text) { notes += text + "\n"; };
    const auto refusal = [&](const SimulationParameters& run) -> std::string {
        try {
            shockgas::run_ensemble(run, nullptr, nullptr, {}, options);
        } catch (const shockgas::InputError& error) {
            return error.what();
        }
        return "(not refused)";
    };

    SimulationParameters other = p;
    other.t_max = 50.0;
    other.seed = p.seed + 1;
    const std::string message = refusal(other);
    EXPECT_NE(message.find("checkpoint '" + options.path + "' belongs to a run with other parameters: t-max 50 vs 60, "
                           "seed 8 vs 7 in the checkpoint"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("to start anew, remove '" + options.path + "' and '" + options.path + ".previous'"),
              std::string::npos)
        << message;
    EXPECT_EQ(notes, "") << "refused before any work";
    EXPECT_TRUE(std::filesystem::exists(options.path)) << "the checkpoint must be kept";

    // Another engine: the checkpoint's states are the event engine's, and a file resumed under the
    // hybrid engine said "hybrid" while its realizations ran the event engine (user review, 2026-11-27).
    // "auto" is resolved before it is compared: here it is the hybrid engine too.
    for (const std::string engine : {"hybrid", "auto"}) {
        other = p;
        other.engine = engine;
        EXPECT_NE(refusal(other).find("belongs to a run with other parameters: engine hybrid vs event in the checkpoint"),
                  std::string::npos)
            << engine << ": " << refusal(other);
    }
    EXPECT_TRUE(std::filesystem::exists(options.path)) << "the checkpoint must be kept";

    // Fewer realizations than the checkpoint holds: the others would be lost.
    other = p;
    other.realizations = 1;
    EXPECT_NE(refusal(other).find("realizations 0 vs 0..1 in the checkpoint"), std::string::npos) << refusal(other);
    // Under MPI a rank's block is judged against the whole run.
    options.run_first_realization = 0;
    options.run_realizations = 3;
    other = p;
    other.realizations = 1;
    other.first_realization = 2;  // rank 1 of 2 now, with the checkpoint's 0..1 within the run
    EXPECT_NO_THROW(shockgas::run_ensemble(other, nullptr, nullptr, {}, options));
    std::filesystem::remove(options.path);
    std::filesystem::remove(options.path + ".previous");
}

// After --resume the progress line's collisions/s counts this process's
// collisions only, not those done before the checkpoint (they took no time
// of this process's elapsed time).
TEST(Checkpoint, ResumedRunReportsTheCollisionRateOfThisProcessOnly) {
    SimulationParameters p = checkpoint_ensemble();
    p.realizations = 1;
    p.threads = 1;
    p.t_max = 1e5;  // far longer than the test runs
    std::atomic<int> written{0};
    CheckpointOptions options = shockgas::testing::frequent_checkpoints("rate", written);
    std::atomic<bool> stop{false};
    shockgas::testing::stop_after_checkpoints(options, written, stop, 2);
    const EnsembleResult stopped = shockgas::run_ensemble(p, nullptr, &stop, {}, options);
    ASSERT_EQ(stopped.status, "interrupted") << "the run ended before it was stopped: the test did not test";
    const auto checkpoint = shockgas::read_checkpoint(options.path);
    ASSERT_EQ(checkpoint.engines.size(), 1u) << "the realization was not caught mid-way";
    const std::uint64_t before = checkpoint.result.total_collisions;
    ASSERT_GT(before, 0u);

    // Resumed, and stopped again at the first progress report: the collisions
    // the report counts are at most those this process did by its end.
    CheckpointOptions resume = options;
    resume.resume = true;
    resume.note = {};
    std::atomic<bool> stop_again{false};
    std::vector<shockgas::Progress> reports;
    const auto progress = [&](const shockgas::Progress& report) {
        reports.push_back(report);
        stop_again.store(true);
    };
    const EnsembleResult resumed = shockgas::run_ensemble(p, nullptr, &stop_again, progress, resume);
    ASSERT_FALSE(reports.empty()) << "no progress report: the test did not test";
    ASSERT_GE(resumed.total_collisions, before);
    const double by_this_process = static_cast<double>(resumed.total_collisions - before);
    for (const auto& report : reports)
        EXPECT_LE(report.collisions_per_second * report.elapsed_seconds, by_this_process * (1 + 1e-9))
            << "the rate counts the " << before << " collisions done before the resume";
    std::filesystem::remove(options.path);
    std::filesystem::remove(options.path + ".previous");
}

TEST(Checkpoint, FileRoundTripKeepsEngineStateBitForBit) {
    const SimulationParameters p = parameters(500, 0.9, 1e-2, Subthreshold::elastic);
    const auto initial = shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), 3, 0);
    auto engine = shockgas::make_engine(p, initial, nullptr);
    ASSERT_TRUE(engine->advance_to(30.0));
    shockgas::Checkpoint checkpoint;
    checkpoint.parameters = p;
    checkpoint.parameters.realizations = 1;
    checkpoint.result = shockgas::run_ensemble(checkpoint.parameters, nullptr);
    checkpoint.samples_done = {0};
    checkpoint.engines.emplace(0, *engine->snapshot());
    const std::string path = "roundtrip.checkpoint";
    shockgas::write_checkpoint(path, checkpoint);
    const auto back = shockgas::read_checkpoint(path);
    ASSERT_EQ(back.engines.size(), 1u);
    const EngineSnapshot& a = checkpoint.engines.at(0);
    const EngineSnapshot& b = back.engines.at(0);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.integers, b.integers);
    ASSERT_EQ(a.reals.size(), b.reals.size());
    for (const auto& [name, values] : a.reals) EXPECT_TRUE(same(values, b.reals.at(name))) << name;
    EXPECT_EQ(back.signature, shockgas::run_signature(checkpoint.parameters));
}

}  // namespace

// gather_checkpoint (an MPI job resumed with another number of ranks): each
// realization of the block comes from the checkpoint where it got furthest
// (finished beats in progress), realizations no file holds start anew, and
// files of another run contribute nothing. The end-to-end case under mpirun
// is tests/mpi (other_ranks).
TEST(Checkpoint, GatheredBlockTakesEachRealizationWhereItGotFurthest) {
    SimulationParameters p = checkpoint_ensemble();
    p.threads = 1;
    const EnsembleResult whole = shockgas::run_ensemble(p, nullptr);  // realizations 0, 1, 2
    const std::size_t samples = whole.times.size();
    const auto status_code = [](shockgas::RealizationStatus s) { return static_cast<std::int64_t>(s); };

    // A checkpoint of the block [first, first + count) in which realization
    // k of the run has the given status (in progress: 3 samples and its state).
    // Each file marks its records by engine_switch_time = tag + realization.
    const auto checkpoint_of = [&](int first, int count, const std::vector<shockgas::RealizationStatus>& status,
                                   double tag) {
        shockgas::Checkpoint c;
        c.parameters = p;
        c.parameters.first_realization = first;
        c.parameters.realizations = count;
        EnsembleResult& r = c.result;
        r = whole;
        r.realizations = count;
        for (const auto table : shockgas::sample_tables)
            (r.*table).assign((whole.*table).begin() + static_cast<std::ptrdiff_t>(first * samples),
                              (whole.*table).begin() + static_cast<std::ptrdiff_t>((first + count) * samples));
        r.realization_status.clear();
        r.engine_switch_time.assign(static_cast<std::size_t>(count), 0.0);
        r.snapshots.clear();
        const auto bins = static_cast<std::size_t>(p.histogram_bins) + 2;
        for (auto& h : r.histograms)
            h.counts.assign(h.counts.begin() + static_cast<std::ptrdiff_t>(first * bins),
                            h.counts.begin() + static_cast<std::ptrdiff_t>((first + count) * bins));
        for (int j = 0; j < count; ++j) {
            const int k = first + j;
            r.realization_status.push_back(status_code(status[static_cast<std::size_t>(j)]));
            r.engine_switch_time[static_cast<std::size_t>(j)] = tag + k;
            const bool running = status[static_cast<std::size_t>(j)] == shockgas::RealizationStatus::in_progress;
            c.samples_done.push_back(running ? 3 : static_cast<std::int64_t>(samples));
            if (running) {
                const auto initial =
                    shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), p.seed, k);
                auto engine = shockgas::make_engine(p, initial, nullptr);
                engine->advance_to(whole.times[2]);
                c.engines.emplace(j, *engine->snapshot());
            }
        }
        return c;
    };
    using S = shockgas::RealizationStatus;
    // Rank 0 of a 2-rank job: realization 0 done, 1 in progress.
    shockgas::write_checkpoint("gather.rank0", checkpoint_of(0, 2, {S::complete, S::in_progress}, 1000.0));
    // An older one-process checkpoint: realization 1 done, 0 and 2 not started.
    shockgas::write_checkpoint("gather.single", checkpoint_of(0, 3, {S::not_run, S::complete, S::not_run}, 2000.0));
    // Another run (other seed) that has everything: refused, not gathered (it would be removed with the others).
    shockgas::Checkpoint other = checkpoint_of(0, 3, {S::complete, S::complete, S::complete}, 3000.0);
    other.parameters.seed = p.seed + 1;
    shockgas::write_checkpoint("gather.other", other);
    const std::vector<std::string> files = {"gather.rank0", "gather.single"};

    SimulationParameters block = p;  // rank 1 of a 2-rank job now: realizations 1 and 2
    block.first_realization = 1;
    block.realizations = 2;
    std::vector<std::string> sources;
    const auto gathered = shockgas::gather_checkpoint(files, block, whole.times, {}, &sources);
    ASSERT_TRUE(gathered.has_value());
    EXPECT_EQ(gathered->result.realization_status,
              (std::vector<std::int64_t>{status_code(S::complete), status_code(S::not_run)}));
    EXPECT_EQ(gathered->result.engine_switch_time[0], 2001.0);  // realization 1 from the one-process file
    EXPECT_EQ(gathered->samples_done, (std::vector<std::int64_t>{static_cast<std::int64_t>(samples), 0}));
    EXPECT_TRUE(gathered->engines.empty());
    // Every file of this run is listed for removal, even one whose record was superseded; not the other run's.
    EXPECT_EQ(sources, (std::vector<std::string>{"gather.rank0", "gather.single"}));

    block.first_realization = 0;  // rank 0 of a 2-rank job: realizations 0 and 1
    sources.clear();
    const auto first_block = shockgas::gather_checkpoint(files, block, whole.times, {}, &sources);
    ASSERT_TRUE(first_block.has_value());
    EXPECT_EQ(first_block->result.realization_status,
              (std::vector<std::int64_t>{status_code(S::complete), status_code(S::complete)}));
    EXPECT_EQ(first_block->result.engine_switch_time, (std::vector<double>{1000.0, 2001.0}));
    EXPECT_EQ(sources, (std::vector<std::string>{"gather.rank0", "gather.single"}));
    // Without the one-process file, realization 1 continues from rank 0's state.
    const auto from_rank0 = shockgas::gather_checkpoint({"gather.rank0"}, block, whole.times, {});
    ASSERT_TRUE(from_rank0.has_value());
    EXPECT_EQ(from_rank0->samples_done, (std::vector<std::int64_t>{static_cast<std::int64_t>(samples), 3}));
    EXPECT_EQ(from_rank0->engines.count(1), 1u);
    try {
        shockgas::gather_checkpoint({"gather.rank0", "gather.other"}, block, whole.times, {}, nullptr, &p);
        ADD_FAILURE() << "a checkpoint of another run was gathered from";
    } catch (const shockgas::InputError& error) {
        EXPECT_NE(std::string(error.what()).find("'gather.other' belongs to a run with other parameters: seed 7 vs 8 in the checkpoint"),
                  std::string::npos)
            << error.what();
    }
    // With the whole run given, a block outside it is another run's too.
    SimulationParameters smaller = p;
    smaller.realizations = 2;
    EXPECT_THROW(shockgas::gather_checkpoint({"gather.single"}, block, whole.times, {}, nullptr, &smaller),
                 shockgas::InputError);
    for (const auto& file : files) std::filesystem::remove(file);
    std::filesystem::remove("gather.other");
}
