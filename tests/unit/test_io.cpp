// SPDX-License-Identifier: GPL-3.0-or-later
// The HDF5 layer, init files and the output schema.
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "shockgas/io/initial_condition.hpp"
#include "shockgas/run/ensemble.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/observables.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/model/state.hpp"

namespace {

namespace fs = std::filesystem;
using shockgas::InitialCondition;
using shockgas::InputError;

std::string temp_path(const std::string& name) { return (fs::path(testing::TempDir()) / name).string(); }

TEST(H5, AttributesAndDatasetsRoundTrip) {
    const auto path = temp_path("roundtrip.h5");
    {
        shockgas::h5::AtomicFile file(path);
        auto root = file.root();
        root.set_attribute("text", "hello");
        root.set_attribute("number", 2.5);
        root.set_attribute("integer", std::int64_t{42});
        auto group = root.create_group("g");
        group.write("table", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3});
        group.write("ids", std::vector<std::int64_t>{7, 8});
        file.commit();
    }
    const auto file = shockgas::h5::File::open_read(path);
    const auto root = file.root();
    EXPECT_EQ(root.attribute_string("text"), "hello");
    EXPECT_EQ(root.attribute_double("number"), 2.5);
    EXPECT_EQ(root.attribute_integer("integer"), 42);
    std::vector<hsize_t> dims;
    EXPECT_EQ(root.open_group("g").read_doubles("table", &dims), (std::vector<double>{1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3}));
    EXPECT_EQ(root.open_group("g").read_integers("ids"), (std::vector<std::int64_t>{7, 8}));
    EXPECT_THROW(root.read_doubles("absent"), shockgas::h5::Error);
}

// A committed file is closed, so its bytes are whole, even while the writer still holds its groups (the
// usual `auto root = file.root(); ...; file.commit();`): byte 11 of the superblock (version 3, the 1.10
// format) is the file consistency flags (HDF5 File Format Specification, section II.A), bit 0 "open for
// write". A file renamed to its target with that bit set is unreadable if the process dies before it
// releases the groups.
TEST(H5, CommittedFileIsClosedWhileItsGroupsAreStillHeld) {
    const auto path = temp_path("held.h5");
    shockgas::h5::AtomicFile file(path);
    auto root = file.root();
    auto group = root.create_group("g");
    group.write("values", std::vector<double>{1, 2, 3});
    file.commit();
    std::ifstream bytes(path, std::ios::binary);
    std::array<char, 12> superblock{};
    ASSERT_TRUE(bytes.read(superblock.data(), superblock.size()));
    EXPECT_EQ(std::string(superblock.data() + 1, 3), "HDF");
    EXPECT_EQ(static_cast<int>(superblock[8]), 3) << "superblock version";
    EXPECT_EQ(static_cast<int>(superblock[11]), 0) << "file consistency flags: the file is still open for write";
}

TEST(H5, UncommittedAtomicFileLeavesNothing) {
    const auto path = temp_path("never.h5");
    fs::remove(path);
    {
        shockgas::h5::AtomicFile file(path);
        file.root().set_attribute("status", "half-written");
    }
    EXPECT_FALSE(fs::exists(path));
    for (const auto& entry : fs::directory_iterator(testing::TempDir()))
        EXPECT_EQ(entry.path().filename().string().find("never.h5.tmp"), std::string::npos);
}

// What may be replaced or removed as an output or a checkpoint generation is
// decided from one probe (shockgas-sim -o, may_be_generation): an empty file
// holds nothing to lose, a file with any other bytes is not HDF5.
TEST(H5, ProbeTellsAnEmptyFileFromOneThatIsNotHdf5) {
    using Kind = shockgas::h5::Probe::Kind;
    const auto path = temp_path("probe.txt");
    fs::remove(path);
    EXPECT_EQ(shockgas::h5::probe(path).kind, Kind::absent);
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    std::fclose(file);
    EXPECT_EQ(shockgas::h5::probe(path).kind, Kind::empty);
    file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    std::fputs("x", file);
    std::fclose(file);
    EXPECT_EQ(shockgas::h5::probe(path).kind, Kind::not_hdf5);
    fs::remove(path);
    EXPECT_EQ(shockgas::h5::probe(testing::TempDir()).kind, Kind::not_regular);
}

TEST(InitFile, RoundTripAndValidation) {
    const auto path = temp_path("init.h5");
    const InitialCondition initial = shockgas::generate_initial_condition(16, 16.0, 3, 0);
    shockgas::write_initial_condition(path, initial);
    const InitialCondition back = shockgas::read_initial_condition(path);
    EXPECT_EQ(back.position, initial.position);
    EXPECT_EQ(back.velocity, initial.velocity);
    EXPECT_EQ(back.ring_length, 16.0);

    auto broken = initial;
    broken.position[3] = broken.position[5];
    EXPECT_THROW(shockgas::validate(broken), InputError);  // unsorted
    broken = initial;
    broken.position[0] = -1.0;
    EXPECT_THROW(shockgas::validate(broken), InputError);  // outside [0, L)
    broken = initial;
    broken.velocity[2] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(shockgas::validate(broken), InputError);
    broken = initial;
    broken.velocity.pop_back();
    EXPECT_THROW(shockgas::validate(broken), InputError);  // length mismatch
}

TEST(InitialCondition, PaperInitialConditionIsReproducible) {
    const auto a = shockgas::generate_initial_condition(1000, 1000.0, 42, 3);
    const auto b = shockgas::generate_initial_condition(1000, 1000.0, 42, 3);
    const auto c = shockgas::generate_initial_condition(1000, 1000.0, 42, 4);
    EXPECT_EQ(a.velocity, b.velocity);
    EXPECT_NE(a.velocity, c.velocity);
    for (std::size_t i = 0; i < a.position.size(); ++i) {
        EXPECT_EQ(a.position[i], static_cast<double>(i));
        EXPECT_GE(a.velocity[i], -1.0);
        EXPECT_LT(a.velocity[i], 1.0);
    }
    // Pinned values: a seed must mean the same velocities on every platform
    // and in every future version (archived runs regenerate bit for bit).
    EXPECT_EQ(shockgas::realization_seed(1, 0), 6791897765849424158ULL);
}

TEST(Output, SchemaAndBitIdenticalReruns) {
    shockgas::SimulationParameters p;
    p.particles = 200;
    p.t_max = 50;
    p.realizations = 3;
    p.snapshot_times = {10};
    p.histogram_times = {20};
    p.histogram_bins = 20;
    const auto first = shockgas::run_ensemble(p, nullptr);
    p.threads = 1;
    const auto serial = shockgas::run_ensemble(p, nullptr);
    EXPECT_EQ(first.temperature, serial.temperature);  // thread count does not matter
    EXPECT_EQ(first.collisions_per_particle, serial.collisions_per_particle);
    const auto path = temp_path("output.h5");
    shockgas::write_output(path, p, first);
    const auto series = shockgas::read_timeseries(path);
    EXPECT_EQ(series.realizations, 3);
    EXPECT_EQ(series.temperature, first.temperature);
    EXPECT_EQ(series.status, "complete");
    const auto file = shockgas::h5::File::open_read(path);
    const auto root = file.root();
    for (const char* name : {"version", "simulator_sha256", "compiler", "compiler_flags", "host", "date",
                             "schema_version", "seed", "restitution", "velocity_threshold", "subthreshold", "particles",
                             "engine"})
        EXPECT_TRUE(root.has_attribute(name)) << name;
    EXPECT_EQ(root.attribute_string("simulator_sha256"), shockgas::build_info().simulator_sha256);
    EXPECT_EQ(root.open_group("snapshots").open_group("0").attribute_double("time"), 10.0);
    std::vector<hsize_t> dims;
    root.open_group("histograms").open_group("0").read_doubles("counts", &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{3, 22}));
}

// Schema 4: the time series starts with the initial state, t = 0, for every
// engine (the event engine here, the exact engine at r = 0); its T is the start's
// own, bit for bit, no collision has happened and every particle is its own cluster.
TEST(Output, TimeSeriesStartsWithTheInitialState) {
    for (const double restitution : {0.9, 0.0}) {
        shockgas::SimulationParameters p;
        p.particles = 300;
        p.collision.restitution = restitution;
        p.t_max = 20;
        p.realizations = 2;
        const auto result = shockgas::run_ensemble(p, nullptr);
        ASSERT_FALSE(result.times.empty());
        EXPECT_EQ(result.times.front(), 0.0);
        EXPECT_GT(result.times[1], 0.0);
        const std::size_t samples = result.times.size();
        for (std::int64_t r = 0; r < p.realizations; ++r) {
            const auto start = shockgas::generate_initial_condition(p.particles, p.effective_ring_length(), p.seed,
                                                                    p.first_realization + r, p.initial_law);
            const auto cell = static_cast<std::size_t>(r) * samples;
            EXPECT_EQ(result.temperature[cell], shockgas::velocity_moments(start.velocity, start.mass).temperature);
            EXPECT_EQ(result.collisions_per_particle[cell], 0.0);
            EXPECT_EQ(result.clusters[cell], static_cast<double>(p.particles));
            EXPECT_LT(result.temperature[cell + samples - 1], result.temperature[cell]);  // it did cool
        }
        const auto path = temp_path("starts_at_zero.h5");
        shockgas::write_output(path, p, result);
        EXPECT_EQ(shockgas::read_timeseries(path).time.front(), 0.0);
    }
}

TEST(Output, PartsMergeIntoTheSingleRunResult) {
    shockgas::SimulationParameters p;
    p.particles = 300;
    p.t_max = 30;
    p.realizations = 5;
    p.snapshot_times = {10};
    p.histogram_times = {20};
    p.histogram_bins = 10;
    const auto whole = shockgas::run_ensemble(p, nullptr);
    std::vector<shockgas::OutputFile> parts;
    std::vector<std::string> names;
    for (const auto& [first, count] : {std::pair{0, 2}, std::pair{2, 3}}) {
        auto part_parameters = p;
        part_parameters.first_realization = first;
        part_parameters.realizations = count;
        const auto path = temp_path(fmt::format("part{}.h5", first));
        shockgas::write_output(path, part_parameters, shockgas::run_ensemble(part_parameters, nullptr));
        parts.push_back(shockgas::read_output(path));
        names.push_back(path);
    }
    const auto merged = shockgas::merge_outputs(parts, names);
    EXPECT_EQ(merged.result.temperature, whole.temperature);
    EXPECT_EQ(merged.result.clusters, whole.clusters);
    EXPECT_EQ(merged.result.histograms[0].counts, whole.histograms[0].counts);
    ASSERT_EQ(merged.result.snapshots.size(), whole.snapshots.size());
    EXPECT_EQ(merged.result.snapshots[4].realization, 4);
    EXPECT_EQ(merged.result.snapshots[4].state.velocity, whole.snapshots[4].state.velocity);
    EXPECT_EQ(merged.parameters.realizations, 5);
    // A gap in the realization sequence is refused.
    EXPECT_THROW(shockgas::merge_outputs({parts[1], parts[0]}, {names[1], names[0]}), shockgas::InputError);
}

// A refusal naming a long list (600 snapshot times) would run to 3 KB: a
// list longer than 60 characters is shown by its length and the first entry in which the two
// differ; other values (paths, hashes) whole, however long.
TEST(Output, ParameterDifferencesShowLongListsByWhereTheyDiffer) {
    shockgas::SimulationParameters a, b;
    for (int k = 1; k <= 600; ++k) a.snapshot_times.push_back(k);
    b.t_max = 500;
    std::string differences = shockgas::parameter_differences(a, b);
    EXPECT_LT(differences.size(), 200u) << differences;
    EXPECT_NE(differences.find("snapshot-times (none) vs (600 values from 1)"), std::string::npos) << differences;
    EXPECT_NE(differences.find("t-max 500 vs "), std::string::npos) << differences;
    // Two lists that differ in their last entry: the entry shown, not two identical prefixes.
    b = a;
    b.snapshot_times.back() = 605;
    differences = shockgas::parameter_differences(a, b);
    EXPECT_NE(differences.find("snapshot-times (600 values from 1, value 600 = 605) vs (600 values from 1, value 600 "
                               "= 600)"),
              std::string::npos)
        << differences;
    // One list a prefix of the other.
    b = a;
    b.snapshot_times.pop_back();
    differences = shockgas::parameter_differences(a, b);
    EXPECT_NE(differences.find("(599 values from 1, none after value 599) vs (600 values from 1, value 600 = 600)"),
              std::string::npos)
        << differences;
    // A long path is shown whole.
    a = shockgas::SimulationParameters{};
    b = a;
    a.init_file = "/a/rather/long/directory/name/for/the/initial/conditions/of/this/study/start_a.h5";
    b.init_file = "/a/rather/long/directory/name/for/the/initial/conditions/of/this/study/start_b.h5";
    differences = shockgas::parameter_differences(a, b);
    EXPECT_NE(differences.find(b.init_file + " vs " + a.init_file), std::string::npos) << differences;
}

// simulator_sha256 (the simulator's sources, compiler and flags) decides whether a checkpoint or a
// part was made by the same simulator, whatever the versions say; files written before it was
// recorded fall back to the version.
TEST(Provenance, TheSameSimulatorIsTheSameSourceHash) {
    const std::string a(64, 'a'), b(64, 'b');
    EXPECT_TRUE(shockgas::same_simulator("v1", a, "v2", a));            // a docs-only commit
    EXPECT_FALSE(shockgas::same_simulator("v1-dirty", a, "v1-dirty", b));  // two edits of the simulator
    EXPECT_TRUE(shockgas::same_simulator("v1", "", "v1", a));           // an older file: its version
    EXPECT_FALSE(shockgas::same_simulator("v1", "", "v2", a));
    EXPECT_FALSE(shockgas::same_simulator("v1", a, "v2", ""));
    const auto& build = shockgas::build_info();
    EXPECT_EQ(build.simulator_sha256.size(), 64u);
    EXPECT_TRUE(shockgas::made_by_this_simulator("another version", build.simulator_sha256));
    EXPECT_FALSE(shockgas::made_by_this_simulator(build.version, b));
}

// A merged file merged again must name the parts it came from, not only the
// merged file: each part's own merged_from follows its line.
TEST(Output, MergeOfMergedFilesNamesEveryPart) {
    shockgas::SimulationParameters p;
    p.particles = 100;
    p.t_max = 5;
    std::vector<std::string> names;
    std::vector<shockgas::OutputFile> parts;
    for (const int first : {0, 1, 2}) {
        auto part_parameters = p;
        part_parameters.first_realization = first;
        part_parameters.realizations = 1;
        names.push_back(temp_path(fmt::format("nested_part{}.h5", first)));
        shockgas::write_output(names.back(), part_parameters, shockgas::run_ensemble(part_parameters, nullptr));
        parts.push_back(shockgas::read_output(names.back()));
    }
    const auto inner_path = temp_path("nested_inner.h5");
    shockgas::write_merged_output(inner_path, shockgas::merge_outputs({parts[0], parts[1]}, {names[0], names[1]}),
                                  "test");
    const auto inner = shockgas::read_output(inner_path);
    const std::string version = ", shockgas " + shockgas::build_info().version + ")";
    EXPECT_EQ(inner.merged_from, (std::vector<std::string>{names[0] + " (realizations 0 to 0" + version,
                                                           names[1] + " (realizations 1 to 1" + version}));
    EXPECT_TRUE(parts[2].merged_from.empty());
    // Parts of two versions of the same simulator merge; the file's version is the first part's
    // (as its date and host), each part's is in merged_from (not the merge's own).
    {
        auto first = parts[0];
        first.version = "docsonly/1";
        const auto mixed_path = temp_path("nested_mixed.h5");
        shockgas::write_merged_output(mixed_path, shockgas::merge_outputs({first, parts[1]}, {names[0], names[1]}),
                                      "test");
        const auto mixed = shockgas::read_output(mixed_path);
        EXPECT_EQ(mixed.version, "docsonly/1");
        EXPECT_EQ(mixed.merged_from.front(), names[0] + " (realizations 0 to 0, shockgas docsonly/1)");
    }
    const auto outer = shockgas::merge_outputs({inner, parts[2]}, {inner_path, names[2]});
    EXPECT_EQ(outer.merged_from,
              (std::vector<std::string>{inner_path + " (realizations 0 to 1" + version,
                                        "  " + names[0] + " (realizations 0 to 0" + version,
                                        "  " + names[1] + " (realizations 1 to 1" + version,
                                        names[2] + " (realizations 2 to 2" + version}));
}

// copy_realization is how merge_outputs and gather_checkpoint move a
// realization: it must replace the target's records of that realization where
// they stood (EnsembleResult keeps snapshots by (realization, time) and
// collapses by realization; the writer and the resume rely on it), drop those
// the source does not have, and leave every other realization alone.
TEST(Output, CopiedRealizationReplacesItsRecordsInOrder) {
    using shockgas::EnsembleResult;
    const auto snapshot = [](std::int64_t realization, double time) {
        shockgas::SnapshotRecord s;
        s.realization = realization;
        s.state.time = time;
        return s;
    };
    const auto collapse = [](std::int64_t realization) {
        shockgas::CollapseRecord c;
        c.realization = realization;
        return c;
    };
    EnsembleResult to;
    to.times = {0.0, 1.0};
    shockgas::grow_realizations(to, 3);
    to.snapshots = {snapshot(0, 1), snapshot(0, 2), snapshot(1, 1), snapshot(1, 2), snapshot(2, 1)};
    to.collapses = {collapse(0), collapse(1), collapse(2)};
    EnsembleResult from;
    from.times = to.times;
    shockgas::grow_realizations(from, 2);
    from.temperature = {5, 6, 7, 8};
    from.realization_status[1] = static_cast<std::int64_t>(shockgas::RealizationStatus::complete);
    from.engine_switch_time[1] = 3.5;
    from.snapshots = {snapshot(0, 9), snapshot(1, 7), snapshot(1, 8)};
    from.histograms = {{20.0, {0.0, 1.0}, {1, 2, 3, 4, 5, 6}}};  // one bin: 3 counts per realization

    shockgas::copy_realization(from, 1, to, 1);
    std::vector<std::pair<std::int64_t, double>> order;
    for (const auto& s : to.snapshots) order.emplace_back(s.realization, s.state.time);
    EXPECT_EQ(order, (std::vector<std::pair<std::int64_t, double>>{{0, 1}, {0, 2}, {1, 7}, {1, 8}, {2, 1}}));
    ASSERT_EQ(to.collapses.size(), 2u);  // realization 1's collapse record is gone: the source has none
    EXPECT_EQ(to.collapses[0].realization, 0);
    EXPECT_EQ(to.collapses[1].realization, 2);
    EXPECT_EQ(to.temperature[2], 7.0);
    EXPECT_EQ(to.temperature[3], 8.0);
    EXPECT_TRUE(std::isnan(to.temperature[0]) && std::isnan(to.temperature[5]));
    EXPECT_EQ(to.realization_status[1], static_cast<std::int64_t>(shockgas::RealizationStatus::complete));
    EXPECT_EQ(to.realization_status[0], static_cast<std::int64_t>(shockgas::RealizationStatus::not_run));
    EXPECT_EQ(to.engine_switch_time[1], 3.5);
    ASSERT_EQ(to.histograms.size(), 1u);
    EXPECT_EQ(to.histograms[0].counts, (std::vector<double>{0, 0, 0, 4, 5, 6, 0, 0, 0}));

    // Room for one more: a realization that never ran.
    shockgas::grow_realizations(to, 4);
    EXPECT_EQ(to.temperature.size(), 8u);
    EXPECT_TRUE(std::isnan(to.temperature[7]));
    EXPECT_EQ(to.realization_status[3], static_cast<std::int64_t>(shockgas::RealizationStatus::not_run));
    EXPECT_EQ(to.histograms[0].counts.size(), 12u);
    EXPECT_EQ(to.histograms[0].counts[5], 6.0);
}

TEST(InitFile, HostileFilesFoundByFuzzingAreRefusedBeforeAllocating) {
    // Two 2 kB files from the libFuzzer run (tests/fuzz): one declares a
    // dataset of 1.7e11 bytes, the other an element type of 4 GB per value.
    // Both must be a one-line InputError, not an allocation of that size.
    for (const char* name : {"hostile-regression-huge-dims.h5", "hostile-regression-huge-element-type.h5"}) {
        const std::string path = std::string(SHOCKGAS_TEST_DATA_DIR) + "/" + name;
        ASSERT_TRUE(fs::exists(path)) << path;
        EXPECT_THROW(shockgas::read_initial_condition(path), InputError) << name;
    }
}

}  // namespace

namespace {

TEST(H5, NumberedGroupsReadInNumericOrderPaddedOrNot) {
    // Schemas 1-2 wrote 0, 1, ..., 10 (HDF5 lists them 0, 1, 10, 2); schema 3 pads them.
    EXPECT_EQ(shockgas::h5::numbered_name(7, 12), "07");
    EXPECT_EQ(shockgas::h5::numbered_name(0, 1), "0");
    EXPECT_EQ(shockgas::h5::numbered_name(99, 100), "99");
    EXPECT_EQ(shockgas::h5::numbered_name(5, 101), "005");
    const auto path = temp_path("numbered.h5");
    {
        shockgas::h5::AtomicFile file(path);
        auto root = file.root();
        auto old = root.create_group("old");
        for (const char* name : {"0", "1", "10", "2"}) old.create_group(name);
        auto padded = root.create_group("padded");
        for (std::size_t k = 0; k < 11; ++k) padded.create_group(shockgas::h5::numbered_name(k, 11));
        file.commit();
    }
    const auto file = shockgas::h5::File::open_read(path);
    EXPECT_EQ(file.root().open_group("old").numbered_children(), (std::vector<std::string>{"0", "1", "2", "10"}));
    const auto padded = file.root().open_group("padded");
    EXPECT_EQ(padded.children(), padded.numbered_children());  // zero-padded: the name order is the numeric order
}

}  // namespace

namespace {

// Rewrites one dataset (or a root attribute) of a file in place, as damage or
// a hand edit would leave it: the readers must notice rather than index the
// other datasets beyond its end.
void rewrite_dataset(const std::string& file, const std::string& group, const std::string& name,
                     const std::vector<double>& data) {
    namespace h5 = shockgas::h5;
    const h5::Handle handle(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
    ASSERT_TRUE(handle.valid()) << file;
    h5::Group target(h5::Handle(H5Gopen2(handle.id(), group.c_str(), H5P_DEFAULT), H5Gclose), group);
    ASSERT_GE(H5Ldelete(target.id(), name.c_str(), H5P_DEFAULT), 0) << group << "/" << name;
    target.write(name, data);
}

void rewrite_root_attribute(const std::string& file, const std::string& name, const std::string& value) {
    namespace h5 = shockgas::h5;
    const h5::Handle handle(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
    ASSERT_TRUE(handle.valid()) << file;
    h5::Group root(h5::Handle(H5Gopen2(handle.id(), "/", H5P_DEFAULT), H5Gclose), "/");
    root.set_attribute(name, value);
}

template <typename Read>
std::string read_error(Read&& read) {
    try {
        read();
    } catch (const std::exception& error) {
        return error.what();
    }
    return "(no error)";
}

// A snapshot whose velocity is shorter than its positions would print heap
// garbage (1.89e+168), and a run whose collisions are shorter than its times
// 1e-314. Every dataset indexed by another's size is checked, and the error
// names the file and the dataset.
TEST(Output, InconsistentDatasetsAreRefusedNamingFileAndDataset) {
    shockgas::SimulationParameters p;
    p.particles = 100;
    p.t_max = 20;
    p.realizations = 2;
    p.snapshot_times = {5};
    p.histogram_times = {10};
    p.histogram_bins = 8;
    const auto result = shockgas::run_ensemble(p, nullptr);
    const auto good = temp_path("consistent.h5");
    shockgas::write_output(good, p, result);
    ASSERT_NO_THROW(shockgas::read_output(good));
    const auto damaged = [&](const std::string& name) {
        const auto path = temp_path(name);
        fs::copy_file(good, path, fs::copy_options::overwrite_existing);
        return path;
    };
    const auto expect_named = [](const std::string& message, const std::string& path, const std::string& what) {
        EXPECT_NE(message.find("'" + path + "'"), std::string::npos) << message;
        EXPECT_NE(message.find(what), std::string::npos) << message;
    };

    const auto short_velocity = damaged("short_velocity.h5");
    rewrite_dataset(short_velocity, "/snapshots/0", "velocity", {0.5, -0.5});
    expect_named(read_error([&] { shockgas::read_output(short_velocity); }), short_velocity,
                 "dataset /snapshots/0/velocity has 2 values");

    const auto short_collisions = damaged("short_collisions.h5");
    rewrite_dataset(short_collisions, "/timeseries", "collisions_per_particle", {1.0, 2.0, 3.0});
    for (const auto& message : {read_error([&] { shockgas::read_output(short_collisions); }),
                                read_error([&] { shockgas::read_timeseries(short_collisions); })})
        expect_named(message, short_collisions, "dataset /timeseries/collisions_per_particle has 3 values");

    const auto short_status = damaged("short_status.h5");
    rewrite_dataset(short_status, "/timeseries", "realization_status", {0.0});
    expect_named(read_error([&] { shockgas::read_output(short_status); }), short_status,
                 "/timeseries/realization_status has 1 values, expected 2");

    const auto short_counts = damaged("short_counts.h5");
    rewrite_dataset(short_counts, "/histograms/0", "counts", std::vector<double>(10, 1.0));
    expect_named(read_error([&] { shockgas::read_output(short_counts); }), short_counts,
                 "/histograms/0/counts has 10 values, expected 20");

    // Named in words, not only as "error: stod".
    const auto bad_times = damaged("bad_sample_times.h5");
    rewrite_root_attribute(bad_times, "sample_times", "10,abc");
    expect_named(read_error([&] { shockgas::read_output(bad_times); }), bad_times,
                 "attribute sample_times = '10,abc' is not a comma-separated list of times ('abc' is not a number)");

    const auto bad_status = damaged("bad_status.h5");
    rewrite_root_attribute(bad_status, "status", "checkpoint");
    expect_named(read_error([&] { shockgas::read_output(bad_status); }), bad_status,
                 "status = 'checkpoint' is none of complete, collapsed, interrupted");
}

// shockgas-merge must not take a checkpoint (realization_status 4, status
// "checkpoint") as a part and call the result "complete".
TEST(Output, ACheckpointIsNoOutputAndAnUnknownStatusNeverMerges) {
    shockgas::SimulationParameters p;
    p.particles = 100;
    p.t_max = 20;
    p.realizations = 2;
    const auto checkpoint = temp_path("a_run.checkpoint");
    shockgas::CheckpointOptions options;
    options.path = checkpoint;
    options.interval_seconds = 0.0;
    std::atomic<bool> stop{true};
    shockgas::run_ensemble(p, nullptr, &stop, {}, options);
    ASSERT_TRUE(fs::exists(checkpoint));
    const std::string message = read_error([&] { shockgas::read_output(checkpoint); });
    EXPECT_NE(message.find("is a shockgas-sim checkpoint (a run in progress), not an output"), std::string::npos)
        << message;
    EXPECT_THROW(shockgas::read_output(checkpoint), InputError);

    const auto output = temp_path("merge_status.h5");
    shockgas::write_output(output, p, shockgas::run_ensemble(p, nullptr));
    auto part = shockgas::read_output(output);
    part.result.status = "checkpoint";
    const std::string merged = read_error([&] { shockgas::merge_outputs({part}, {output}); });
    EXPECT_NE(merged.find("has status 'checkpoint', none of complete, collapsed, interrupted"), std::string::npos)
        << merged;
}

// Seeds are stored as signed 64-bit attributes: one from 2^63 on would read
// back negative (h5py, h5dump), so the parameters refuse it.
TEST(Parameters, SeedsFromTwoToTheSixtyThreeOnAreRefused) {
    shockgas::SimulationParameters p;
    p.seed = (std::uint64_t{1} << 63) - 1;
    EXPECT_NO_THROW(shockgas::validate(p));
    p.seed = std::uint64_t{1} << 63;
    EXPECT_THROW(shockgas::validate(p), InputError);
}

}  // namespace
