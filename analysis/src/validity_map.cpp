// SPDX-License-Identifier: GPL-3.0-or-later
// The validity map's HDF5 layout (docs/cli-and-output.md, "Validity map") and the
// small measured-data helpers its readers share: the planner (plan_command.cpp)
// and shockgas-sim's warning (validity_warning.cpp). Nothing here needs GSL, so
// that the fuzz harness, which builds shockgas-sim's main from sources, can
// compile it beside the simulator's rooms.
#include "shockgas/analysis/validity_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {

namespace {

// The criteria in the order a reader lists them: the statistical one first, then
// the relative ones from tight to loose. Any other name follows, by name.
const std::vector<std::string> known_criteria = {"3sigma", "1percent", "5percent"};

// A name that becomes one HDF5 group: not empty, no '/', not "." (the group itself).
void check_group_name(const std::string& name, const std::string& what) {
    if (name.empty() || name == "." || name.find('/') != std::string::npos)
        throw std::invalid_argument(fmt::format("validity map: {} '{}' cannot name an HDF5 group", what, name));
}

std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> parts;
    if (text.empty()) return parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return parts;
}

// `preferred` names first, in their order, where `present` has them; then the rest by name.
std::vector<std::string> in_order(std::vector<std::string> present, const std::vector<std::string>& preferred) {
    std::sort(present.begin(), present.end());
    std::vector<std::string> ordered;
    for (const auto& name : preferred)
        if (std::find(present.begin(), present.end(), name) != present.end() &&
            std::find(ordered.begin(), ordered.end(), name) == ordered.end())
            ordered.push_back(name);
    for (const auto& name : present)
        if (std::find(ordered.begin(), ordered.end(), name) == ordered.end()) ordered.push_back(name);
    return ordered;
}

void write_run(h5::Group& runs, const ValidityRun& run, std::int64_t index) {
    check_group_name(run.name, "run name");
    if (run.time.size() != run.collisions_per_particle.size())
        throw std::invalid_argument(fmt::format("validity map: run '{}' has {} times but {} collision counts",
                                                run.name, run.time.size(), run.collisions_per_particle.size()));
    auto group = runs.create_group(run.name);
    // HDF5 lists a group's members by name; the index keeps the map's own order.
    group.set_attribute("index", index);
    group.set_attribute("restitution", run.restitution);
    group.set_attribute("velocity_threshold", run.velocity_threshold);
    group.set_attribute("subthreshold", run.subthreshold);
    group.set_attribute("particles", run.particles);
    group.set_attribute("realizations", run.realizations);
    group.set_attribute("t_end", run.t_end);
    group.set_attribute("cpu_seconds", run.cpu_seconds);
    group.write("time", run.time);
    group.write("collisions_per_particle", run.collisions_per_particle);
    auto departures = group.create_group("departures");
    for (const auto& departure : run.departures) {
        check_group_name(departure.observable, "observable");
        check_group_name(departure.criterion, "criterion");
        auto observable = departures.has(departure.observable) ? departures.open_group(departure.observable)
                                                               : departures.create_group(departure.observable);
        if (observable.has(departure.criterion))
            throw std::invalid_argument(fmt::format("validity map: run '{}' has two departures of {} by {}", run.name,
                                                    departure.observable, departure.criterion));
        auto criterion = observable.create_group(departure.criterion);
        criterion.set_attribute("departure_time", departure.departure_time);
        criterion.set_attribute("departure_sigma", departure.departure_sigma);
        criterion.set_attribute("note", departure.note);
    }
}

ValidityRun read_run(const h5::Group& group, const std::string& name, const std::vector<std::string>& observables,
                     const std::string& path) {
    ValidityRun run;
    run.name = name;
    run.restitution = group.attribute_double("restitution");
    run.velocity_threshold = group.attribute_double("velocity_threshold");
    run.subthreshold = group.attribute_string("subthreshold");
    run.particles = group.attribute_integer("particles");
    run.realizations = group.attribute_integer("realizations");
    run.t_end = group.attribute_double("t_end");
    run.cpu_seconds = group.attribute_double("cpu_seconds");
    run.time = group.read_doubles("time");
    run.collisions_per_particle = group.read_doubles("collisions_per_particle");
    if (run.time.size() != run.collisions_per_particle.size())
        throw InputError(fmt::format(
            "'{}' is inconsistent: dataset {}/collisions_per_particle has {} values, expected {} (one per time)", path,
            group.path(), run.collisions_per_particle.size(), run.time.size()));
    for (std::size_t k = 1; k < run.time.size(); ++k)
        if (!(run.time[k] > run.time[k - 1]))
            throw InputError(fmt::format("'{}' is inconsistent: dataset {}/time is not increasing at index {}", path,
                                         group.path(), k));
    const auto departures = group.open_group("departures");
    for (const auto& observable_name : in_order(departures.children(), observables)) {
        const auto observable = departures.open_group(observable_name);
        for (const auto& criterion_name : in_order(observable.children(), known_criteria)) {
            const auto criterion = observable.open_group(criterion_name);
            ValidityDeparture departure;
            departure.observable = observable_name;
            departure.criterion = criterion_name;
            departure.departure_time = criterion.attribute_double("departure_time");
            departure.departure_sigma = criterion.attribute_double("departure_sigma");
            departure.note = criterion.attribute_string("note");
            run.departures.push_back(std::move(departure));
        }
    }
    return run;
}

ValidityFit read_fit(const h5::Group& group) {
    ValidityFit fit;
    fit.observable = group.attribute_string("observable");
    fit.criterion = group.attribute_string("criterion");
    fit.subthreshold = group.attribute_string("subthreshold");
    fit.restitution = group.attribute_double("restitution");
    fit.particles = group.attribute_integer("particles");
    fit.mu = group.attribute_double("mu");
    fit.mu_sigma = group.attribute_double("mu_sigma");
    fit.log_amplitude = group.attribute_double("log_amplitude");
    fit.log_amplitude_sigma = group.attribute_double("log_amplitude_sigma");
    fit.points = group.attribute_integer("points");
    fit.follows = group.attribute_string("follows");
    return fit;
}

}  // namespace

void write_validity_map(h5::Group& group, const ValidityMap& map) {
    for (const auto& observable : map.observables) {
        check_group_name(observable, "observable");
        if (observable.find(',') != std::string::npos)
            throw std::invalid_argument(
                fmt::format("validity map: observable '{}' holds a comma, which separates them", observable));
    }
    group.set_attribute("version", map.version);
    group.set_attribute("fidelity", map.fidelity);
    group.set_attribute("observables", fmt::format("{}", fmt::join(map.observables, ",")));
    auto runs = group.create_group("runs");
    for (std::size_t i = 0; i < map.runs.size(); ++i) write_run(runs, map.runs[i], static_cast<std::int64_t>(i));
    auto fits = group.create_group("fits");
    for (std::size_t i = 0; i < map.fits.size(); ++i) {
        const ValidityFit& fit = map.fits[i];
        auto g = fits.create_group(h5::numbered_name(i, map.fits.size()));
        g.set_attribute("observable", fit.observable);
        g.set_attribute("criterion", fit.criterion);
        g.set_attribute("subthreshold", fit.subthreshold);
        g.set_attribute("restitution", fit.restitution);
        g.set_attribute("particles", fit.particles);
        g.set_attribute("mu", fit.mu);
        g.set_attribute("mu_sigma", fit.mu_sigma);
        g.set_attribute("log_amplitude", fit.log_amplitude);
        g.set_attribute("log_amplitude_sigma", fit.log_amplitude_sigma);
        g.set_attribute("points", fit.points);
        g.set_attribute("follows", fit.follows);
    }
}

ValidityMap read_validity_map(const std::string& path) {
    ValidityMap map;
    try {
        const h5::File file = h5::File::open_read(path);
        const h5::Group root = file.root();
        if (!root.has("validity_map") || !root.is_group("validity_map"))
            throw InputError(fmt::format("'{}' holds no validity map (no group /validity_map): shockgas-analyze "
                                         "validity writes one",
                                         path));
        const h5::Group group = root.open_group("validity_map");
        map.version = group.attribute_string("version");
        map.fidelity = group.attribute_string("fidelity");
        map.observables = split_commas(group.attribute_string("observables"));
        const h5::Group runs = group.open_group("runs");
        std::vector<std::pair<std::int64_t, ValidityRun>> indexed;
        for (const auto& name : runs.children()) {
            const h5::Group run = runs.open_group(name);
            indexed.emplace_back(run.attribute_integer("index"), read_run(run, name, map.observables, path));
        }
        std::stable_sort(indexed.begin(), indexed.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& entry : indexed) map.runs.push_back(std::move(entry.second));
        const h5::Group fits = group.open_group("fits");
        for (const auto& name : fits.numbered_children()) map.fits.push_back(read_fit(fits.open_group(name)));
    } catch (const h5::Error& error) {
        // h5's messages name the object and the file; a user needs to know what was being read.
        throw InputError(fmt::format("cannot read the validity map: {}", error.what()));
    }
    return map;
}

bool same_restitution(double a, double b) { return std::abs(a - b) <= same_restitution_tolerance; }

const ValidityDeparture* find_departure(const ValidityRun& run, const std::string& observable,
                                        const std::string& criterion) {
    for (const auto& departure : run.departures)
        if (departure.observable == observable && departure.criterion == criterion) return &departure;
    return nullptr;
}

double log_log_interpolate(double x0, double y0, double x1, double y1, double x) {
    if (x == x0) return y0;
    if (x == x1) return y1;
    if (x0 > 0.0 && x1 > 0.0 && y0 > 0.0 && y1 > 0.0 && x > 0.0) {
        const double w = std::log(x / x0) / std::log(x1 / x0);
        return std::exp(std::log(y0) + w * std::log(y1 / y0));
    }
    return y0 + (y1 - y0) * (x - x0) / (x1 - x0);
}

double collisions_per_particle_at(const ValidityRun& run, double t) {
    const auto& time = run.time;
    if (time.empty() || !(t >= time.front()) || !(t <= time.back())) return std::numeric_limits<double>::quiet_NaN();
    const auto upper = std::lower_bound(time.begin(), time.end(), t);
    const auto k = static_cast<std::size_t>(upper - time.begin());
    if (time[k] == t) return run.collisions_per_particle[k];
    return log_log_interpolate(time[k - 1], run.collisions_per_particle[k - 1], time[k], run.collisions_per_particle[k],
                               t);
}

std::string default_validity_map(const std::vector<std::string>& build_tree_maps) {
    if (const char* chosen = std::getenv("SHOCKGAS_VALIDITY_MAP"); chosen != nullptr) return chosen;
    for (const auto& candidate : build_tree_maps) {
        std::error_code ignored;
        if (!candidate.empty() && std::filesystem::is_regular_file(candidate, ignored)) return candidate;
    }
    return "";
}

}  // namespace shockgas::analysis
