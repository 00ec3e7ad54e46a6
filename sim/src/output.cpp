#include "shockgas/output.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/h5.hpp"
#include "shockgas/provenance.hpp"

namespace shockgas {

namespace {

void write_state(h5::Group& group, const ClusterState& state) {
    group.set_attribute("time", state.time);
    group.write("position", state.position);
    group.write("velocity", state.velocity);
    group.write("mass", state.mass);
    group.write("first_particle", state.first_particle);
}

std::string join(const std::vector<double>& values) { return fmt::format("{}", fmt::join(values, ",")); }

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
    root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
    root.set_attribute("init_file", p.init_file);
    root.set_attribute("initial_condition",
                       p.init_file.empty() ? "equally spaced, velocities uniform on [-1, 1], unit masses"
                                           : "from init_file");
}

void write_output(const std::string& path, const SimulationParameters& parameters, const EnsembleResult& result) {
    h5::AtomicFile file(path);
    auto root = file.root();
    write_provenance(root, "shockgas-sim");
    write_parameter_attributes(root, parameters);
    root.set_attribute("engine", result.engine);
    root.set_attribute("status", result.status);
    root.set_attribute("total_collisions", static_cast<std::int64_t>(result.total_collisions));
    root.set_attribute("cpu_seconds", result.cpu_seconds);
    root.set_attribute("wall_seconds", result.wall_seconds);

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
    series.set_attribute("temperature_definition", "T = sum m v^2 / M - (sum m v / M)^2, per realization");
    series.set_attribute("kinetic_energy_definition", "sum m v^2 / (2 M), lab frame");

    auto snapshots = root.create_group("snapshots");
    for (std::size_t s = 0; s < result.snapshots.size(); ++s) {
        auto group = snapshots.create_group(fmt::format("{}", s));
        group.set_attribute("realization", result.snapshots[s].realization);
        write_state(group, result.snapshots[s].state);
    }

    auto histograms = root.create_group("histograms");
    for (std::size_t h = 0; h < result.histograms.size(); ++h) {
        const HistogramRecord& record = result.histograms[h];
        auto group = histograms.create_group(fmt::format("{}", h));
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
            auto group = states.create_group(fmt::format("{}", c));
            group.set_attribute("realization", result.collapses[c].realization);
            group.set_attribute("criterion", result.collapses[c].report.criterion);
            write_state(group, result.collapses[c].state);
        }
    }
    file.commit();
}

TimeSeries read_timeseries(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
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
    out.status = root.attribute_string("status");
    return out;
}

}  // namespace shockgas
