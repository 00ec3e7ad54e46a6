// SPDX-License-Identifier: GPL-3.0-or-later
// The output of shockgas-spheres (schema in docs/spheres.md, "Output"), written
// and read in one place.
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/spheres/ensemble.hpp"

namespace shockgas::spheres {

namespace {
// 1: /timeseries, /histograms, /snapshots as written below.
constexpr std::int64_t spheres_schema_version = 1;
using hsize = unsigned long long;
}  // namespace

void write_parameter_attributes(h5::Group& root, const SphereParameters& p) {
    root.set_attribute("dimension", static_cast<std::int64_t>(p.dimension));
    root.set_attribute("particles", p.particles);
    root.set_attribute("packing_fraction", p.packing_fraction);
    root.set_attribute("box_length", box_length(p.dimension, p.particles, p.packing_fraction));
    root.set_attribute("restitution", p.collision.restitution);
    root.set_attribute("velocity_threshold", p.collision.velocity_threshold);
    root.set_attribute("subthreshold", to_string(p.collision.subthreshold));
    root.set_attribute("collapse_speed", p.collapse_speed);
    root.set_attribute("start", to_string(p.start));
    root.set_attribute("melt_collisions_per_particle", p.melt_collisions_per_particle);
    root.set_attribute("t_max", p.t_max);
    root.set_attribute("samples_per_decade", static_cast<std::int64_t>(p.samples_per_decade));
        if (!p.sample_times.empty()) root.set_attribute("sample_times", p.sample_times);  // HDF5 has no empty attribute
        if (!p.snapshot_times.empty()) root.set_attribute("snapshot_times", p.snapshot_times);  // HDF5 has no empty attribute
        if (!p.histogram_times.empty()) root.set_attribute("histogram_times", p.histogram_times);  // HDF5 has no empty attribute
    root.set_attribute("histogram_bins", static_cast<std::int64_t>(p.histogram_bins));
    root.set_attribute("histogram_range", p.histogram_range);
    root.set_attribute("field_cells", static_cast<std::int64_t>(p.field_cells));
    root.set_attribute("realizations", static_cast<std::int64_t>(p.realizations));
    root.set_attribute("first_realization", p.first_realization);
    root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
}

SphereParameters read_parameter_attributes(const h5::Group& root) {
    SphereParameters p;
    p.dimension = static_cast<int>(root.attribute_integer("dimension"));
    p.particles = root.attribute_integer("particles");
    p.packing_fraction = root.attribute_double("packing_fraction");
    p.collision.restitution = root.attribute_double("restitution");
    p.collision.velocity_threshold = root.attribute_double("velocity_threshold");
    p.collision.subthreshold = subthreshold_from_string(root.attribute_string("subthreshold"));
    p.collapse_speed = root.attribute_double("collapse_speed");
    p.start = start_method_from_string(root.attribute_string("start"));
    p.melt_collisions_per_particle = root.attribute_double("melt_collisions_per_particle");
    p.t_max = root.attribute_double("t_max");
    p.samples_per_decade = static_cast<int>(root.attribute_integer("samples_per_decade"));
    if (root.has_attribute("sample_times")) p.sample_times = root.attribute_doubles("sample_times");
    if (root.has_attribute("snapshot_times")) p.snapshot_times = root.attribute_doubles("snapshot_times");
    if (root.has_attribute("histogram_times")) p.histogram_times = root.attribute_doubles("histogram_times");
    p.histogram_bins = static_cast<int>(root.attribute_integer("histogram_bins"));
    p.histogram_range = root.attribute_double("histogram_range");
    p.field_cells = static_cast<int>(root.attribute_integer("field_cells"));
    p.realizations = static_cast<int>(root.attribute_integer("realizations"));
    p.first_realization = root.attribute_integer("first_realization");
    p.seed = static_cast<std::uint64_t>(root.attribute_integer("seed"));
    return p;
}

std::vector<std::string> parameter_differences(const SphereParameters& a, const SphereParameters& b) {
    std::vector<std::string> out;
    auto differ = [&](const char* name, auto x, auto y) {
        if (x != y) out.push_back(fmt::format("{} {} vs {}", name, x, y));
    };
    auto differ_list = [&](const char* name, const std::vector<double>& x, const std::vector<double>& y) {
        if (x != y) out.push_back(fmt::format("{} {} vs {}", name, fmt::join(x, ","), fmt::join(y, ",")));
    };
    differ("dimension", a.dimension, b.dimension);
    differ("particles", a.particles, b.particles);
    differ("packing-fraction", a.packing_fraction, b.packing_fraction);
    differ("restitution", a.collision.restitution, b.collision.restitution);
    differ("threshold", a.collision.velocity_threshold, b.collision.velocity_threshold);
    differ("subthreshold", to_string(a.collision.subthreshold), to_string(b.collision.subthreshold));
    differ("collapse-speed", a.collapse_speed, b.collapse_speed);
    differ("start", to_string(a.start), to_string(b.start));
    differ("melt", a.melt_collisions_per_particle, b.melt_collisions_per_particle);
    differ("t-max", a.t_max, b.t_max);
    differ("samples-per-decade", a.samples_per_decade, b.samples_per_decade);
    differ_list("sample-times", a.sample_times, b.sample_times);
    differ_list("snapshot-times", a.snapshot_times, b.snapshot_times);
    differ_list("histogram-times", a.histogram_times, b.histogram_times);
    differ("histogram-bins", a.histogram_bins, b.histogram_bins);
    differ("histogram-range", a.histogram_range, b.histogram_range);
    differ("field-cells", a.field_cells, b.field_cells);
    differ("realizations", a.realizations, b.realizations);
    differ("first-realization", a.first_realization, b.first_realization);
    differ("seed", a.seed, b.seed);
    return out;
}

void write_spheres_output(const std::string& path, const SphereParameters& p, const SphereResult& result,
                          const JoinRecord& joined) {
    h5::write_atomically(path, [&](h5::Group& root) {
        write_provenance(root, "shockgas-spheres");
        // How the file was joined (same attribute names as shockgas-sim's files).
        if (joined.mpi_ranks > 1) root.set_attribute("mpi_ranks", joined.mpi_ranks);
        if (!joined.merged_by.empty()) {
            root.set_attribute("merged_by", joined.merged_by);
            root.set_attribute("merged_date", utc_timestamp());
            root.set_attribute("merged_from", fmt::format("{}", fmt::join(joined.merged_from, "\n")));
        }
        root.set_attribute("spheres_sha256", spheres_sha256());
        root.set_attribute("schema", "spheres");
        root.set_attribute("schema_version", spheres_schema_version);
        write_parameter_attributes(root, p);
        bool collapsed = false;
        for (const auto& s : result.status) collapsed = collapsed || s == "collapsed";
        root.set_attribute("status", collapsed ? "collapsed" : "complete");
        root.set_attribute("collisions", static_cast<std::int64_t>(result.counts.collisions()));
        root.set_attribute("inelastic_collisions", static_cast<std::int64_t>(result.counts.inelastic));
        root.set_attribute("cell_crossings", static_cast<std::int64_t>(result.counts.cell_crossings));
        root.set_attribute("stale_events", static_cast<std::int64_t>(result.counts.stale_events));
        root.set_attribute("start_cpu_seconds", result.start_seconds);
        root.set_attribute("cpu_seconds", result.cpu_seconds);
        root.set_attribute("wall_seconds", result.wall_seconds);

        const auto samples = static_cast<hsize>(result.time.size());
        const auto realizations = static_cast<hsize>(result.realizations);
        auto series = root.create_group("timeseries");
        series.write("time", result.time);
        series.write("temperature", result.temperature, {realizations, samples});
        series.write("collisions_per_particle", result.collisions_per_particle, {realizations, samples});
        series.write("velocity_kurtosis", result.velocity_kurtosis, {realizations, samples});
        series.write("end_time", result.end_time);
        std::vector<std::int64_t> collapsed_flags;
        for (const auto& s : result.status) collapsed_flags.push_back(s == "collapsed" ? 1 : 0);
        series.write("collapsed", collapsed_flags);

        auto histograms = root.create_group("histograms");
        for (std::size_t h = 0; h < result.histograms.size(); ++h) {
            auto group = histograms.create_group(h5::numbered_name(h, result.histograms.size()));
            group.set_attribute("time", result.histograms[h].time);
            group.set_attribute("outside", result.histograms[h].outside);
            group.write("counts", result.histograms[h].counts);
        }
        auto snapshots = root.create_group("snapshots");
        std::size_t cells = 1;
        for (int k = 0; k < p.dimension; ++k) cells *= static_cast<std::size_t>(p.field_cells);
        for (std::size_t s = 0; s < result.snapshots.size(); ++s) {
            const SphereSnapshot& snapshot = result.snapshots[s];
            auto group = snapshots.create_group(h5::numbered_name(s, result.snapshots.size()));
            group.set_attribute("time", snapshot.time);
            const auto d = static_cast<hsize>(p.dimension);
            if (!snapshot.positions.empty()) {
                group.write("positions", snapshot.positions, {snapshot.positions.size() / d, d});
                group.write("velocities", snapshot.velocities, {snapshot.velocities.size() / d, d});
            }
            group.write("density", snapshot.density, {realizations, static_cast<hsize>(cells)});
            group.write("velocity_field", snapshot.velocity_field, {realizations, static_cast<hsize>(cells), d});
        }
    });
}

bool is_spheres_output(const std::string& path) {
    const auto root = h5::File::open_read(path).root();
    return root.has_attribute("schema") && root.attribute_string("schema") == "spheres";
}

SphereOutput read_spheres_output(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    if (!root.has_attribute("schema") || root.attribute_string("schema") != "spheres")
        throw InputError(fmt::format("{} is not an output of shockgas-spheres", path));
    SphereOutput out;
    SphereParameters& p = out.parameters;
    p = read_parameter_attributes(root);
    out.version = root.attribute_string("version");
    out.spheres_sha256 = root.attribute_string("spheres_sha256");

    SphereResult& r = out.result;
    r.realizations = p.realizations;
    r.counts.inelastic = static_cast<std::uint64_t>(root.attribute_integer("inelastic_collisions"));
    r.counts.elastic = static_cast<std::uint64_t>(root.attribute_integer("collisions")) - r.counts.inelastic;
    r.counts.cell_crossings = static_cast<std::uint64_t>(root.attribute_integer("cell_crossings"));
    r.counts.stale_events = static_cast<std::uint64_t>(root.attribute_integer("stale_events"));
    r.start_seconds = root.attribute_double("start_cpu_seconds");
    r.cpu_seconds = root.attribute_double("cpu_seconds");
    r.wall_seconds = root.attribute_double("wall_seconds");
    const auto series = root.open_group("timeseries");
    r.time = series.read_doubles("time");
    r.temperature = series.read_doubles("temperature");
    r.collisions_per_particle = series.read_doubles("collisions_per_particle");
    r.velocity_kurtosis = series.read_doubles("velocity_kurtosis");
    r.end_time = series.read_doubles("end_time");
    for (auto flag : series.read_integers("collapsed")) r.status.push_back(flag != 0 ? "collapsed" : "complete");
    const auto histograms = root.open_group("histograms");
    for (const auto& name : histograms.numbered_children()) {
        const auto group = histograms.open_group(name);
        r.histograms.push_back({group.attribute_double("time"), group.read_doubles("counts"), group.attribute_double("outside")});
    }
    const auto snapshots = root.open_group("snapshots");
    for (const auto& name : snapshots.numbered_children()) {
        const auto group = snapshots.open_group(name);
        SphereSnapshot snapshot;
        snapshot.time = group.attribute_double("time");
        if (group.has("positions")) {
            snapshot.positions = group.read_doubles("positions");
            snapshot.velocities = group.read_doubles("velocities");
        }
        snapshot.density = group.read_doubles("density");
        snapshot.velocity_field = group.read_doubles("velocity_field");
        r.snapshots.push_back(std::move(snapshot));
    }
    return out;
}

}  // namespace shockgas::spheres
