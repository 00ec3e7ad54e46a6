// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"

namespace shockgas {

namespace {

// Velocities in the lab: the engines' frame (ClusterState) is added back,
// rounded once (nothing changes where the frame is at rest).
void write_state(h5::Group& group, const ClusterState& state) {
    group.set_attribute("time", state.time);
    group.write("position", state.position);
    if (state.frame_velocity == 0.0) {
        group.write("velocity", state.velocity);
    } else {
        std::vector<double> lab(state.size());
        for (std::size_t k = 0; k < lab.size(); ++k) lab[k] = state.lab_velocity(k);
        group.write("velocity", lab);
    }
    group.write("mass", state.mass);
    group.write("first_particle", state.first_particle);
}

std::string join(const std::vector<double>& values) { return fmt::format("{}", fmt::join(values, ",")); }

std::string initial_law_description(const InitialLaw& law) {
    return fmt::format("{}, velocities {}, unit masses",
                       law.positions == PositionLaw::lattice ? "equally spaced" : "positions i.i.d. uniform on [0, L)",
                       law.velocities == VelocityLaw::uniform ? "uniform on [-1, 1]"
                                                              : "Gaussian with mean 0 and variance 1/3");
}

}  // namespace

void write_parameter_attributes(h5::Group& root, const SimulationParameters& p) {
    root.set_attribute("particles", static_cast<std::int64_t>(p.particles));
    root.set_attribute("ring_length", p.effective_ring_length());
    root.set_attribute("restitution", p.collision.restitution);
    root.set_attribute("inelasticity", (1.0 - p.collision.restitution) / 2.0);  // eps, r = 1 - 2 eps
    root.set_attribute("velocity_threshold", p.collision.velocity_threshold);
    root.set_attribute("subthreshold", to_string(p.collision.subthreshold));
    root.set_attribute("collapse_speed", p.collapse.collapse_speed);
    root.set_attribute("stall_time_fraction", p.collapse.stall_time_fraction);
    root.set_attribute("stall_events_min", static_cast<std::int64_t>(p.collapse.stall_events_min));
    root.set_attribute("t_max", p.t_max);
    root.set_attribute("samples_per_decade", static_cast<std::int64_t>(p.samples_per_decade));
    root.set_attribute("sample_times", join(p.sample_times));
    root.set_attribute("snapshot_times", join(p.snapshot_times));
    root.set_attribute("histogram_times", join(p.histogram_times));
    root.set_attribute("histogram_bins", static_cast<std::int64_t>(p.histogram_bins));
    root.set_attribute("histogram_range", p.histogram_range);
    root.set_attribute("realizations", static_cast<std::int64_t>(p.realizations));
    root.set_attribute("first_realization", p.first_realization);
    root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
    root.set_attribute("init_file", p.init_file);
    root.set_attribute("init_file_sha256", p.init_file_sha256);
    root.set_attribute("positions", p.init_file.empty() ? to_string(p.initial_law.positions) : "init_file");
    root.set_attribute("velocity_distribution",
                       p.init_file.empty() ? to_string(p.initial_law.velocities) : "init_file");
    root.set_attribute("initial_condition", p.init_file.empty() ? initial_law_description(p.initial_law)
                                                                : "from init_file");
}

namespace {

// The output schema, written into root: shared by the output file and the
// checkpoint, which is an output file of the partial result plus /checkpoint.
void write_result(h5::Group& root, const SimulationParameters& parameters, const EnsembleResult& result) {
    write_provenance(root, "shockgas-sim");
    write_parameter_attributes(root, parameters);
    root.set_attribute("engine", result.engine);
    root.set_attribute("status", result.status);
    root.set_attribute("total_collisions", static_cast<std::int64_t>(result.total_collisions));
    root.set_attribute("cpu_seconds", result.cpu_seconds);
    root.set_attribute("wall_seconds", result.wall_seconds);
    root.set_attribute("peak_memory_bytes", result.peak_memory_bytes);

    const auto realizations = static_cast<hsize_t>(result.realizations);
    const auto samples = static_cast<hsize_t>(result.times.size());
    auto series = root.create_group("timeseries");
    series.write("time", result.times);
    series.write("temperature", result.temperature, {realizations, samples});
    series.write("collisions_per_particle", result.collisions_per_particle, {realizations, samples});
    series.write("clusters", result.clusters, {realizations, samples});
    series.write("kinetic_energy", result.kinetic_energy, {realizations, samples});
    series.write("realization_status", result.realization_status);
    series.set_attribute("realization_status_codes", "0 complete, 1 collapsed, 2 interrupted, 3 not run");
    // A result assembled by hand (tests, tools) may leave it empty: no switch recorded.
    series.write("engine_switch_time", result.engine_switch_time.empty()
                                           ? std::vector<double>(realizations, std::numeric_limits<double>::quiet_NaN())
                                           : result.engine_switch_time);
    series.set_attribute("engine_switch_time_definition",
                         "time at which the hybrid engine handed over to the pass-through engine; inf: not "
                         "(yet), NaN: an engine that never switches");
    series.set_attribute("temperature_definition", "T = sum m v^2 / M - (sum m v / M)^2, per realization");
    series.set_attribute("kinetic_energy_definition", "sum m v^2 / (2 M), lab frame");

    auto snapshots = root.create_group("snapshots");
    for (std::size_t s = 0; s < result.snapshots.size(); ++s) {
        auto group = snapshots.create_group(h5::numbered_name(s, result.snapshots.size()));
        group.set_attribute("realization", result.snapshots[s].realization);
        write_state(group, result.snapshots[s].state);
    }

    auto histograms = root.create_group("histograms");
    for (std::size_t h = 0; h < result.histograms.size(); ++h) {
        const HistogramRecord& record = result.histograms[h];
        auto group = histograms.create_group(h5::numbered_name(h, result.histograms.size()));
        group.set_attribute("time", record.time);
        group.set_attribute("definition",
                            "mass-weighted counts of v - V (V the realization's mean velocity); "
                            "column 0 underflow, last column overflow");
        group.write("edges", record.edges);
        group.write("counts", record.counts, {realizations, static_cast<hsize_t>(record.edges.size() + 1)});
    }

    if (!result.collapses.empty()) {
        auto collapse = root.create_group("collapse");
        std::vector<double> time, relative_speed;
        std::vector<std::int64_t> realization, cluster_mass, collisions;
        for (const auto& record : result.collapses) {
            time.push_back(record.report.time);
            relative_speed.push_back(record.report.relative_speed);
            realization.push_back(record.realization);
            cluster_mass.push_back(record.report.cluster_mass);
            collisions.push_back(static_cast<std::int64_t>(record.collisions));
        }
        collapse.write("time", time);
        collapse.write("realization", realization);
        collapse.write("cluster_mass", cluster_mass);
        collapse.write("relative_speed", relative_speed);
        collapse.write("collisions", collisions);
        collapse.set_attribute("criterion", result.collapses.front().report.criterion);
        auto states = collapse.create_group("states");
        for (std::size_t c = 0; c < result.collapses.size(); ++c) {
            auto group = states.create_group(h5::numbered_name(c, result.collapses.size()));
            group.set_attribute("realization", result.collapses[c].realization);
            group.set_attribute("criterion", result.collapses[c].report.criterion);
            write_state(group, result.collapses[c].state);
        }
    }
}

}  // namespace

void write_output(const std::string& path, const SimulationParameters& parameters, const EnsembleResult& result) {
    h5::write_atomically(path, [&](h5::Group& root) { write_result(root, parameters, result); });
}

void write_merged_output(const std::string& path, const OutputFile& merged, const std::string& program) {
    h5::write_atomically(path, [&](h5::Group& root) {
        write_result(root, merged.parameters, merged.result);
        // date and host say when and where the run was made (docs/cli-and-output.md), not when
        // it was merged (merged_by, merged_date and merged_from say that).
        // A part read from a file without them (none is written so) keeps the merge's.
        // The version that ran the first part, as its date and host (parts of other
        // versions of the same simulator are named in merged_from).
        if (!merged.version.empty()) root.set_attribute("version", merged.version);
        if (!merged.date.empty()) root.set_attribute("date", merged.date);
        if (!merged.host.empty()) root.set_attribute("host", merged.host);
        root.set_attribute("merged_by", program + " " + build_info().version);
        root.set_attribute("merged_date", utc_timestamp());
        root.set_attribute("merged_from", fmt::format("{}", fmt::join(merged.merged_from, "\n")));
    });
}

namespace {

// Datasets of one file must agree in shape before any is indexed by
// another's: a damaged or hand-edited file with one dataset shorter than its
// neighbours would otherwise be read beyond its end (garbage numbers).
void expect_values(const std::string& file, const std::string& dataset, std::size_t got, std::size_t expected,
                   const std::string& because) {
    if (got != expected)
        throw h5::Error(fmt::format("'{}' is inconsistent: dataset {} has {} values, expected {} ({})", file, dataset,
                                    got, expected, because));
}

}  // namespace

TimeSeries read_timeseries(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    check_simulation_output(root, path);
    const auto series = root.open_group("timeseries");
    TimeSeries out;
    out.time = series.read_doubles("time");
    std::vector<hsize_t> dims;
    out.temperature = series.read_doubles("temperature", &dims);
    if (dims.size() != 2 || dims[1] != out.time.size())
        throw h5::Error(fmt::format("{}: /timeseries/temperature is not realizations x times", path));
    out.realizations = static_cast<std::int64_t>(dims[0]);
    out.collisions_per_particle = series.read_doubles("collisions_per_particle");
    out.clusters = series.read_doubles("clusters");
    out.kinetic_energy = series.read_doubles("kinetic_energy");
    // at() indexes every table as the temperature's realizations x times.
    const std::string shape = fmt::format("{} realizations x {} times", dims[0], dims[1]);
    expect_values(path, "/timeseries/collisions_per_particle", out.collisions_per_particle.size(),
                  out.temperature.size(), shape);
    expect_values(path, "/timeseries/clusters", out.clusters.size(), out.temperature.size(), shape);
    expect_values(path, "/timeseries/kinetic_energy", out.kinetic_energy.size(), out.temperature.size(), shape);
    out.status = root.attribute_string("status");
    return out;
}

namespace {

// The text attribute `name` ("10,100,1000", as write_parameter_attributes
// writes it) as numbers; each item must be a whole finite number, and a
// malformed one is named with its file (std::stod would say only "stod").
std::vector<double> split_times(const h5::Group& root, const std::string& file, const std::string& name) {
    const std::string text = root.attribute_string(name);
    std::vector<double> values;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        char* stop = nullptr;
        const double value = std::strtod(item.c_str(), &stop);
        if (item.empty() || stop != item.c_str() + item.size() || !std::isfinite(value))
            throw h5::Error(fmt::format("'{}': root attribute {} = '{}' is not a comma-separated list of times ('{}' "
                                        "is not a number)",
                                        file, name, text, item));
        values.push_back(value);
        start = end + 1;
    }
    return values;
}

}  // namespace

ClusterState read_cluster_state(const h5::Group& group, const std::string& file) {
    ClusterState state;
    state.time = group.attribute_double("time");
    state.position = group.read_doubles("position");
    state.velocity = group.read_doubles("velocity");
    state.mass = group.read_doubles("mass");
    state.first_particle = group.read_integers("first_particle");
    // One value per cluster in each: every reader walks them together.
    const std::string because = fmt::format("one per cluster, as {}/position", group.path());
    expect_values(file, group.path() + "/velocity", state.velocity.size(), state.position.size(), because);
    expect_values(file, group.path() + "/mass", state.mass.size(), state.position.size(), because);
    expect_values(file, group.path() + "/first_particle", state.first_particle.size(), state.position.size(), because);
    return state;
}

InitialLaw read_initial_law(const h5::Group& root) {
    // Files written before the initial laws existed hold the paper's law.
    if (!root.has_attribute("positions")) return {};
    return {position_law_from_string(root.attribute_string("positions")),
            velocity_law_from_string(root.attribute_string("velocity_distribution"))};
}

namespace {

// The output schema from root, checked for consistency: every dataset that
// is indexed by realization, time, cluster or bin has the size the others
// give it, so no reader of the result goes beyond a dataset's end.
OutputFile read_result(const h5::Group& root, const std::string& file) {
    OutputFile out;
    SimulationParameters& p = out.parameters;
    p.particles = root.attribute_integer("particles");
    p.ring_length = root.attribute_double("ring_length");
    p.collision.restitution = root.attribute_double("restitution");
    p.collision.velocity_threshold = root.attribute_double("velocity_threshold");
    p.collision.subthreshold = subthreshold_from_string(root.attribute_string("subthreshold"));
    p.collapse.collapse_speed = root.attribute_double("collapse_speed");
    p.collapse.stall_time_fraction = root.attribute_double("stall_time_fraction");
    p.collapse.stall_events_min = static_cast<std::uint64_t>(root.attribute_integer("stall_events_min"));
    p.t_max = root.attribute_double("t_max");
    p.samples_per_decade = static_cast<int>(root.attribute_integer("samples_per_decade"));
    p.sample_times = split_times(root, file, "sample_times");
    p.snapshot_times = split_times(root, file, "snapshot_times");
    p.histogram_times = split_times(root, file, "histogram_times");
    p.histogram_bins = static_cast<int>(root.attribute_integer("histogram_bins"));
    p.histogram_range = root.attribute_double("histogram_range");
    const std::int64_t realizations = root.attribute_integer("realizations");
    if (realizations < 0 || realizations > std::numeric_limits<int>::max())
        throw h5::Error(fmt::format("'{}': root attribute realizations = {} is not a number of realizations", file,
                                    realizations));
    p.realizations = static_cast<int>(realizations);
    p.first_realization = root.has_attribute("first_realization") ? root.attribute_integer("first_realization") : 0;
    p.seed = static_cast<std::uint64_t>(root.attribute_integer("seed"));
    p.init_file = root.attribute_string("init_file");
    if (root.has_attribute("init_file_sha256")) p.init_file_sha256 = root.attribute_string("init_file_sha256");
    if (p.init_file.empty()) p.initial_law = read_initial_law(root);
    p.engine = root.attribute_string("engine");
    out.version = root.attribute_string("version");
    if (root.has_attribute("simulator_sha256")) out.simulator_sha256 = root.attribute_string("simulator_sha256");
    if (root.has_attribute("date")) out.date = root.attribute_string("date");
    if (root.has_attribute("host")) out.host = root.attribute_string("host");
    if (root.has_attribute("merged_from")) {
        std::istringstream lines(root.attribute_string("merged_from"));
        for (std::string line; std::getline(lines, line);) out.merged_from.push_back(line);
    }

    EnsembleResult& r = out.result;
    r.engine = p.engine;
    r.status = root.attribute_string("status");
    r.total_collisions = static_cast<std::uint64_t>(root.attribute_integer("total_collisions"));
    r.cpu_seconds = root.attribute_double("cpu_seconds");
    r.wall_seconds = root.attribute_double("wall_seconds");
    r.peak_memory_bytes = root.has_attribute("peak_memory_bytes") ? root.attribute_double("peak_memory_bytes") : 0.0;
    const auto series = root.open_group("timeseries");
    r.times = series.read_doubles("time");
    r.realizations = p.realizations;
    r.temperature = series.read_doubles("temperature");
    r.collisions_per_particle = series.read_doubles("collisions_per_particle");
    r.clusters = series.read_doubles("clusters");
    r.kinetic_energy = series.read_doubles("kinetic_energy");
    r.realization_status = series.read_integers("realization_status");
    // Files of older versions did not record it: NaN, as for an engine that never switches.
    r.engine_switch_time = series.has("engine_switch_time")
                               ? series.read_doubles("engine_switch_time")
                               : std::vector<double>(r.realization_status.size(), std::numeric_limits<double>::quiet_NaN());
    const auto R = static_cast<std::size_t>(realizations);
    const std::string rows = fmt::format("{} realizations x {} times", R, r.times.size());
    expect_values(file, "/timeseries/temperature", r.temperature.size(), R * r.times.size(), rows);
    expect_values(file, "/timeseries/collisions_per_particle", r.collisions_per_particle.size(), R * r.times.size(),
                  rows);
    expect_values(file, "/timeseries/clusters", r.clusters.size(), R * r.times.size(), rows);
    expect_values(file, "/timeseries/kinetic_energy", r.kinetic_energy.size(), R * r.times.size(), rows);
    const std::string one_each = fmt::format("one per realization, {} realizations", R);
    expect_values(file, "/timeseries/realization_status", r.realization_status.size(), R, one_each);
    expect_values(file, "/timeseries/engine_switch_time", r.engine_switch_time.size(), R, one_each);
    const auto check_realization = [&](const std::string& where, std::int64_t k) {
        if (k < 0 || k >= realizations)
            throw h5::Error(fmt::format("'{}' is inconsistent: {} names realization {}, but the file has {}", file,
                                        where, k, realizations));
    };
    const auto snapshots = root.open_group("snapshots");
    // Groups are numbered (schemas 1-2: 0, 1, ...; schema 3 zero-padded): open them in numeric order.
    for (const auto& name : snapshots.numbered_children()) {
        const auto group = snapshots.open_group(name);
        const std::int64_t realization = group.attribute_integer("realization");
        check_realization(group.path(), realization);
        r.snapshots.push_back({realization, read_cluster_state(group, file)});
    }
    const auto histograms = root.open_group("histograms");
    for (const auto& name : histograms.numbered_children()) {
        const auto group = histograms.open_group(name);
        HistogramRecord record{group.attribute_double("time"), group.read_doubles("edges"), group.read_doubles("counts")};
        // bins + 1 edges, and per realization the bins with under- and overflow.
        expect_values(file, group.path() + "/counts", record.counts.size(), R * (record.edges.size() + 1),
                      fmt::format("{} realizations x {} bins + 2, from {}/edges", R,
                                  record.edges.empty() ? 0 : record.edges.size() - 1, group.path()));
        r.histograms.push_back(std::move(record));
    }
    if (root.has("collapse")) {
        const auto collapse = root.open_group("collapse");
        const auto time = collapse.read_doubles("time");
        const auto realization = collapse.read_integers("realization");
        const auto cluster_mass = collapse.read_integers("cluster_mass");
        const auto relative_speed = collapse.read_doubles("relative_speed");
        const auto collisions = collapse.read_integers("collisions");
        const auto states = collapse.open_group("states");
        const auto state_names = states.numbered_children();
        const std::string one_per_collapse = "one per collapse, as /collapse/time";
        expect_values(file, "/collapse/realization", realization.size(), time.size(), one_per_collapse);
        expect_values(file, "/collapse/cluster_mass", cluster_mass.size(), time.size(), one_per_collapse);
        expect_values(file, "/collapse/relative_speed", relative_speed.size(), time.size(), one_per_collapse);
        expect_values(file, "/collapse/collisions", collisions.size(), time.size(), one_per_collapse);
        if (state_names.size() != time.size())
            throw h5::Error(fmt::format("'{}' is inconsistent: /collapse has {} times but {} states", file, time.size(),
                                        state_names.size()));
        for (std::size_t c = 0; c < time.size(); ++c) {
            const auto group = states.open_group(state_names[c]);
            check_realization("/collapse/realization", realization[c]);
            CollapseRecord record;
            record.realization = realization[c];
            record.report = {time[c], 0, cluster_mass[c], relative_speed[c], group.attribute_string("criterion")};
            record.collisions = static_cast<std::uint64_t>(collisions[c]);
            record.state = read_cluster_state(group, file);
            r.collapses.push_back(std::move(record));
        }
    }
    return out;
}

}  // namespace

InputError checkpoint_given_as_output(const std::string& path) {
    return InputError(fmt::format("'{}' is a shockgas-sim checkpoint (a run in progress), not an output: "
                                  "continue the run with shockgas-sim --resume and the same options",
                                  path));
}

bool is_far_tail_file(const h5::Group& root) {
    return root.has_attribute("kind") && root.attribute_string("kind") == "far_tail";
}

std::string other_kind_of_file(const h5::Group& root) {
    const std::string program = root.has_attribute("program") ? root.attribute_string("program") : "";
    if (program == "shockgas-sim") return "";
    // As the files name themselves (write_provenance's program; shockgas-tail's kind).
    if (is_far_tail_file(root))
        return fmt::format("a far-tail sampler file (made by {}; shockgas-analyze far-tail reads it)",
                           program.empty() ? "shockgas-tail" : program);
    if (program.rfind("shockgas-analyze", 0) == 0) return fmt::format("an analysis results file (made by {})", program);
    if (!program.empty()) return fmt::format("a file made by {}", program);
    // write_initial_condition writes no provenance: its datasets say what it is.
    if (!root.has("timeseries") && root.has("position") && root.has("velocity"))
        return "an initial condition file (shockgas-sim --init reads it)";
    return "";
}

void check_simulation_output(const h5::Group& root, const std::string& path) {
    // A checkpoint holds the output schema too, but of a run in progress
    // (realization_status 4): read as an output it would pass for a result.
    if (root.has("checkpoint")) throw checkpoint_given_as_output(path);
    const std::string other = other_kind_of_file(root);
    if (!other.empty()) throw InputError(fmt::format("'{}' is not a shockgas-sim output: it is {}", path, other));
}

OutputFile read_output(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    check_simulation_output(root, path);
    OutputFile out = read_result(root, path);
    const std::string& status = out.result.status;
    if (status != "complete" && status != "collapsed" && status != "interrupted")
        throw h5::Error(fmt::format("'{}': root attribute status = '{}' is none of complete, collapsed, interrupted",
                                    path, status));
    for (const std::int64_t code : out.result.realization_status)
        if (code < 0 || code > static_cast<std::int64_t>(RealizationStatus::not_run))
            throw h5::Error(fmt::format("'{}': /timeseries/realization_status holds {}, which is not a status of an "
                                        "output (0 complete, 1 collapsed, 2 interrupted, 3 not run)",
                                        path, code));
    return out;
}

namespace {

// Every parameter that changes the physics or the sampling, by name (the
// long option's name), as text: parts of one ensemble must agree on all.
std::vector<std::pair<std::string, std::string>> physics_parameters(const SimulationParameters& p) {
    return {{"particles", fmt::format("{}", p.particles)},
            {"ring-length", fmt::format("{}", p.effective_ring_length())},
            {"restitution", fmt::format("{}", p.collision.restitution)},
            {"threshold", fmt::format("{}", p.collision.velocity_threshold)},
            {"subthreshold", to_string(p.collision.subthreshold)},
            {"t-max", fmt::format("{}", p.t_max)},
            {"samples-per-decade", fmt::format("{}", p.samples_per_decade)},
            {"sample-times", join(p.sample_times)},
            {"snapshot-times", join(p.snapshot_times)},
            {"histogram-times", join(p.histogram_times)},
            {"histogram-bins", fmt::format("{}", p.histogram_bins)},
            {"histogram-range", fmt::format("{}", p.histogram_range)},
            {"seed", fmt::format("{}", p.seed)},
            {"init", p.init_file},
            {"init-sha256", p.init_file_sha256},
            {"positions", to_string(p.initial_law.positions)},
            {"velocity-distribution", to_string(p.initial_law.velocities)},
            {"collapse-speed", fmt::format("{}", p.collapse.collapse_speed)},
            {"stall_time_fraction", fmt::format("{}", p.collapse.stall_time_fraction)},
            {"stall_events_min", fmt::format("{}", p.collapse.stall_events_min)}};
}

}  // namespace

namespace {

// A value as a message shows it beside the value it differs from. A long list of
// numbers (600 snapshot times made a refusal of 3 KB) is shown by its length and the
// first entry in which the two differ; anything else (a path, a hash) whole.
std::string shown(const std::string& value, const std::string& other) {
    constexpr std::size_t longest = 60;
    if (value.empty()) return "(none)";
    const bool list_of_numbers = value.find(',') != std::string::npos &&
                                 value.find_first_not_of("0123456789.eE+-,") == std::string::npos;
    if (value.size() <= longest || !list_of_numbers) return value;
    const auto entries = [](const std::string& list) {
        std::vector<std::string> out;
        std::size_t start = 0;
        for (std::size_t comma; (comma = list.find(',', start)) != std::string::npos; start = comma + 1)
            out.push_back(list.substr(start, comma - start));
        out.push_back(list.substr(start));
        return out;
    };
    const auto mine = entries(value), theirs = other.empty() ? std::vector<std::string>{} : entries(other);
    std::size_t k = 0;
    while (k < mine.size() && k < theirs.size() && mine[k] == theirs[k]) ++k;
    std::string text = fmt::format("{} values from {}", mine.size(), mine.front());
    if (k < mine.size() && k > 0) text += fmt::format(", value {} = {}", k + 1, mine[k]);
    if (k == mine.size() && k < theirs.size()) text += fmt::format(", none after value {}", k);
    return "(" + text + ")";
}

}  // namespace

std::string parameter_differences(const SimulationParameters& a, const SimulationParameters& b) {
    const auto first = physics_parameters(a), second = physics_parameters(b);
    std::vector<std::string> differences;
    for (std::size_t i = 0; i < first.size(); ++i)
        if (first[i].second != second[i].second)
            differences.push_back(fmt::format("{} {} vs {}", first[i].first, shown(second[i].second, first[i].second),
                                              shown(first[i].second, second[i].second)));
    return fmt::format("{}", fmt::join(differences, ", "));
}

std::string physics_signature(const SimulationParameters& p) {
    std::string signature;
    for (const auto& [name, value] : physics_parameters(p)) signature += fmt::format("{}=[{}] ", name, value);
    return signature;
}

OutputFile merge_outputs(const std::vector<OutputFile>& parts, const std::vector<std::string>& names) {
    if (parts.empty()) throw InputError("merge: no input files");
    // Only the statuses a finished run writes; anything else (a checkpoint's
    // "checkpoint", a damaged attribute) must not come out as "complete".
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const std::string& status = parts[i].result.status;
        if (status != "complete" && status != "collapsed" && status != "interrupted")
            throw InputError(fmt::format("merge: '{}' has status '{}', none of complete, collapsed, interrupted",
                                         i < names.size() ? names[i] : std::to_string(i), status));
    }
    OutputFile merged = parts.front();
    EnsembleResult& r = merged.result;
    // A part that was itself merged brings its own parts along, indented under
    // its line, so that a merge of merges still names every file it came from.
    merged.merged_from.clear();
    const auto record_part = [&](std::size_t i) {
        const SimulationParameters& p = parts[i].parameters;
        merged.merged_from.push_back(fmt::format("{} (realizations {} to {}, shockgas {})",
                                                 i < names.size() ? names[i] : std::to_string(i), p.first_realization,
                                                 p.first_realization + p.realizations - 1, parts[i].version));
        for (const auto& line : parts[i].merged_from) merged.merged_from.push_back("  " + line);
    };
    record_part(0);
    const std::string signature = physics_signature(parts.front().parameters);
    std::int64_t next_realization = parts.front().parameters.first_realization + parts.front().parameters.realizations;
    bool interrupted = r.status == "interrupted", collapsed = r.status == "collapsed";
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const OutputFile& part = parts[i];
        const std::string& name = names[i];
        if (physics_signature(part.parameters) != signature)
            throw InputError(fmt::format("merge: '{}' was run with different parameters than '{}': {}", name, names[0],
                                         parameter_differences(parts.front().parameters, part.parameters)));
        if (part.result.engine != r.engine)
            throw InputError(fmt::format("merge: '{}' used engine {}, '{}' used {}", name, part.result.engine, names[0],
                                         r.engine));
        if (!same_simulator(part.version, part.simulator_sha256, merged.version, merged.simulator_sha256))
            throw InputError(fmt::format("merge: '{}' was made by {}, '{}' by {}, another simulator", name,
                                         build_description(part.version, part.simulator_sha256), names[0],
                                         build_description(merged.version, merged.simulator_sha256)));
        if (part.parameters.first_realization != next_realization)
            throw InputError(fmt::format("merge: '{}' starts at realization {}, expected {}", name,
                                         part.parameters.first_realization, next_realization));
        next_realization += part.parameters.realizations;
        record_part(i);
        const EnsembleResult& p = part.result;
        const std::int64_t offset = r.realizations;
        grow_realizations(r, offset + p.realizations);
        for (std::int64_t j = 0; j < p.realizations; ++j) copy_realization(p, j, r, offset + j);
        r.total_collisions += p.total_collisions;
        r.cpu_seconds += p.cpu_seconds;
        r.wall_seconds += p.wall_seconds;
        r.peak_memory_bytes = std::max(r.peak_memory_bytes, p.peak_memory_bytes);
        interrupted |= p.status == "interrupted";
        collapsed |= p.status == "collapsed";
    }
    r.status = interrupted ? "interrupted" : collapsed ? "collapsed" : "complete";
    merged.parameters.realizations = static_cast<int>(r.realizations);
    return merged;
}

std::string checkpoint_path_for(const std::string& output_path) { return output_path + ".checkpoint"; }

std::string run_signature(const SimulationParameters& p) {
    return fmt::format("{} R={} first={}", physics_signature(p), p.realizations, p.first_realization);
}

// /checkpoint holds what the output schema has no place for: the run's
// signature, the samples each realization has done, the CPU and wall time
// spent so far, and one group per unfinished realization with its engine
// state (reals and integers as datasets, doubles stored bit for bit).
namespace {

void write_checkpoint_into(h5::Group& root, const Checkpoint& checkpoint) {
    write_result(root, checkpoint.parameters, checkpoint.result);
    auto group = root.create_group("checkpoint");
    group.set_attribute("run_signature", run_signature(checkpoint.parameters));
    group.set_attribute("description",
                        "a shockgas-sim run in progress: the datasets above hold what is done "
                        "(realization_status 4: in progress); shockgas-sim --resume continues it");
    group.write("samples_done", checkpoint.samples_done);
    auto engines = group.create_group("engines");
    for (const auto& [realization, snapshot] : checkpoint.engines) {
        auto state = engines.create_group(fmt::format("{}", realization));
        state.set_attribute("kind", snapshot.kind);
        auto reals = state.create_group("reals");
        for (const auto& [name, values] : snapshot.reals) reals.write(name, values);
        auto integers = state.create_group("integers");
        for (const auto& [name, values] : snapshot.integers) integers.write(name, values);
    }
}

}  // namespace

void write_checkpoint(const std::string& path, const Checkpoint& checkpoint, const std::string& keep_previous_as) {
    h5::write_atomically(path, [&](h5::Group& root) { write_checkpoint_into(root, checkpoint); }, keep_previous_as);
}

Checkpoint read_checkpoint(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    if (!root.has("checkpoint")) throw InputError(fmt::format("'{}' is not a shockgas checkpoint", path));
    OutputFile partial = read_result(root, path);
    Checkpoint out;
    out.parameters = std::move(partial.parameters);
    out.result = std::move(partial.result);
    out.version = std::move(partial.version);
    out.simulator_sha256 = std::move(partial.simulator_sha256);
    out.source = path;
    const auto group = root.open_group("checkpoint");
    out.signature = group.attribute_string("run_signature");
    out.samples_done = group.read_integers("samples_done");
    if (out.samples_done.size() != static_cast<std::size_t>(out.result.realizations))
        throw InputError(fmt::format("checkpoint '{}': samples_done has {} entries for {} realizations", path,
                                     out.samples_done.size(), out.result.realizations));
    const auto engines = group.open_group("engines");
    for (const std::string& name : engines.children()) {
        const auto state = engines.open_group(name);
        EngineSnapshot snapshot;
        snapshot.kind = state.attribute_string("kind");
        const auto reals = state.open_group("reals");
        for (const std::string& array : reals.children()) snapshot.reals[array] = reals.read_doubles(array);
        const auto integers = state.open_group("integers");
        for (const std::string& array : integers.children()) snapshot.integers[array] = integers.read_integers(array);
        std::int64_t realization = -1;
        try {
            realization = std::stoll(name);
        } catch (const std::exception&) {
        }
        if (realization < 0 || realization >= out.result.realizations)
            throw InputError(fmt::format("checkpoint '{}': engine state for unknown realization '{}'", path, name));
        out.engines.emplace(realization, std::move(snapshot));
    }
    return out;
}

}  // namespace shockgas
