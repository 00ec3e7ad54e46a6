// SPDX-License-Identifier: GPL-3.0-or-later
// Joining ensemble parts of the disk and sphere gas (ensemble.hpp,
// join_spheres_parts): what shockgas-merge does with shockgas-spheres files and
// what rank 0 does with the blocks of an MPI job (job.cpp).
#include <algorithm>
#include <iterator>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/spheres/ensemble.hpp"

namespace shockgas::spheres {

namespace {

// Appends `part`'s rows (a table of rows of any width) to `joined`.
void append(std::vector<double>& joined, const std::vector<double>& part) {
    joined.insert(joined.end(), part.begin(), part.end());
}

// The parts must be one run's: the same parameters but for which
// realizations, and the same engine. (The thread count is not among the
// parameters compared: no output records it, since no result depends on it.)
void check_joinable(const SphereOutput& first, const SphereOutput& part, const std::string& name,
                    std::int64_t expected_first_realization) {
    SphereParameters same = part.parameters;
    same.realizations = first.parameters.realizations;
    same.first_realization = first.parameters.first_realization;
    if (const auto differences = parameter_differences(first.parameters, same); !differences.empty())
        throw InputError(fmt::format("'{}' is a part of another run: {} (against the first part)", name,
                                     fmt::join(differences, ", ")));
    if (part.spheres_sha256 != first.spheres_sha256)
        throw InputError(fmt::format("'{}' was made by another build of the engine (spheres_sha256 {} vs {}): its "
                                     "realizations would not be the same run's",
                                     name, part.spheres_sha256.substr(0, 12), first.spheres_sha256.substr(0, 12)));
    if (part.parameters.first_realization != expected_first_realization)
        throw InputError(fmt::format("'{}' starts at realization {}, the parts before it end at {}: give the parts "
                                     "in realization order, without gaps or overlaps",
                                     name, part.parameters.first_realization, expected_first_realization - 1));
}

}  // namespace

JoinedParts join_spheres_parts(const std::vector<SphereOutput>& parts, const std::vector<std::string>& names) {
    if (parts.empty()) throw InputError("no parts to join");
    JoinedParts joined;
    joined.parameters = parts.front().parameters;
    joined.parameters.realizations = 0;
    SphereResult& result = joined.result;
    result.time = parts.front().result.time;
    result.histograms = parts.front().result.histograms;
    for (auto& histogram : result.histograms) {
        std::fill(histogram.counts.begin(), histogram.counts.end(), 0.0);
        histogram.outside = 0.0;
    }
    result.snapshots.resize(parts.front().result.snapshots.size());
    std::int64_t next_realization = joined.parameters.first_realization;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const SphereOutput& part = parts[i];
        check_joinable(parts.front(), part, names[i], next_realization);
        const SphereResult& r = part.result;
        joined.merged_from.push_back(fmt::format("{} (realizations {} to {}, shockgas {})", names[i],
                                                 part.parameters.first_realization,
                                                 part.parameters.first_realization + r.realizations - 1, part.version));
        next_realization += r.realizations;
        joined.parameters.realizations += part.parameters.realizations;
        result.realizations += r.realizations;
        append(result.temperature, r.temperature);
        append(result.collisions_per_particle, r.collisions_per_particle);
        append(result.velocity_kurtosis, r.velocity_kurtosis);
        append(result.end_time, r.end_time);
        result.status.insert(result.status.end(), r.status.begin(), r.status.end());
        // Counts of particles in bins: whole numbers, so their sum is exact in any order.
        for (std::size_t h = 0; h < result.histograms.size(); ++h) {
            for (std::size_t b = 0; b < result.histograms[h].counts.size(); ++b)
                result.histograms[h].counts[b] += r.histograms[h].counts[b];
            result.histograms[h].outside += r.histograms[h].outside;
        }
        for (std::size_t s = 0; s < result.snapshots.size(); ++s) {
            SphereSnapshot& snapshot = result.snapshots[s];
            snapshot.time = r.snapshots[s].time;
            if (i == 0) {  // realization 0's particles
                snapshot.positions = r.snapshots[s].positions;
                snapshot.velocities = r.snapshots[s].velocities;
            }
            append(snapshot.density, r.snapshots[s].density);
            append(snapshot.velocity_field, r.snapshots[s].velocity_field);
        }
        result.counts.inelastic += r.counts.inelastic;
        result.counts.elastic += r.counts.elastic;
        result.counts.cell_crossings += r.counts.cell_crossings;
        result.counts.stale_events += r.counts.stale_events;
        result.start_seconds += r.start_seconds;
        result.cpu_seconds += r.cpu_seconds;
        result.wall_seconds += r.wall_seconds;  // parts run one after another; MPI ranks take the slowest (job.cpp)
    }
    return joined;
}

}  // namespace shockgas::spheres
