// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/shocks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"

#include "shockgas/io/output.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::analysis {

double Snapshot::total_mass() const { return std::accumulate(mass.begin(), mass.end(), 0.0); }

std::vector<Snapshot> snapshots_from(const EnsembleResult& result, double ring_length) {
    std::vector<Snapshot> out;
    for (const auto& record : result.snapshots)
        out.push_back({record.state.time, record.realization, ring_length, record.state.position,
                       record.state.velocity, record.state.mass});
    return out;
}

std::vector<Snapshot> read_snapshots(const std::string& path) {
    // The schema is read in one place (shockgas::read_output).
    const OutputFile file = read_output(path);
    auto snapshots = snapshots_from(file.result, file.parameters.effective_ring_length());
    // A damaged or hand-made snapshot would give nan (no mass: v_rms = 0/0)
    // or read past the end of a short dataset: refused, named.
    for (std::size_t i = 0; i < snapshots.size(); ++i) {
        const Snapshot& snapshot = snapshots[i];
        std::string problem;
        if (snapshot.position.size() != snapshot.velocity.size() || snapshot.mass.size() != snapshot.velocity.size())
            problem = fmt::format("position, velocity and mass hold {}, {} and {} values", snapshot.position.size(),
                                  snapshot.velocity.size(), snapshot.mass.size());
        else if (!std::all_of(snapshot.mass.begin(), snapshot.mass.end(), [](double m) { return m > 0.0 && std::isfinite(m); }))
            problem = "mass holds a value that is not positive and finite";
        else if (!(snapshot.total_mass() > 0.0))
            problem = "mass is empty: no particle to find shocks among";
        else if (!std::all_of(snapshot.velocity.begin(), snapshot.velocity.end(), [](double v) { return std::isfinite(v); }) ||
                 !std::all_of(snapshot.position.begin(), snapshot.position.end(), [](double x) { return std::isfinite(x); }))
            problem = "position or velocity holds a value that is not finite";
        else if (!(snapshot.time > 0.0) || !std::isfinite(snapshot.time))
            problem = fmt::format("its time {} is not positive and finite", snapshot.time);
        if (problem.empty()) continue;
        // The group's name as stored (schemas 1-2 unpadded, 3 on zero-padded).
        const auto names = h5::File::open_read(path).root().open_group("snapshots").numbered_children();
        throw h5::Error(fmt::format("/snapshots/{}: {} in '{}'", i < names.size() ? names[i] : std::to_string(i),
                                    problem, path));
    }
    return snapshots;
}

Snapshot coarse_grained(const Snapshot& snapshot, double cell_mass) {
    Snapshot out = snapshot;
    out.position.clear();
    out.velocity.clear();
    out.mass.clear();
    const double half_ring = 0.5 * snapshot.ring_length;
    double mass = 0.0, moment = 0.0, momentum = 0.0, first = 0.0;
    auto flush = [&] {
        if (mass <= 0.0) return;
        double x = moment / mass;
        if (x >= snapshot.ring_length) x -= snapshot.ring_length;
        out.position.push_back(x);
        out.velocity.push_back(momentum / mass);
        out.mass.push_back(mass);
        mass = moment = momentum = 0.0;
    };
    for (std::size_t i = 0; i < snapshot.velocity.size(); ++i) {
        double x = snapshot.position[i];
        if (mass == 0.0) first = x;
        if (x < first - half_ring) x += snapshot.ring_length;  // the cell crosses the seam
        mass += snapshot.mass[i];
        moment += snapshot.mass[i] * x;
        momentum += snapshot.mass[i] * snapshot.velocity[i];
        if (mass >= cell_mass) flush();
    }
    flush();
    return out;
}

ShockProfile find_shocks(const Snapshot& input, const ShockRule& rule) {
    if (rule.coarse_grain_mass > 0.0) {
        // The segments from the cells, the shocks from the clusters themselves (ShockRule).
        ShockRule on_clusters = rule;
        on_clusters.coarse_grain_mass = 0.0;
        ShockProfile profile = find_shocks(coarse_grained(input, rule.coarse_grain_mass), on_clusters);
        ShockProfile shocks = find_shocks(input, on_clusters);
        profile.shock_position = std::move(shocks.shock_position);
        profile.shock_drop = std::move(shocks.shock_drop);
        return profile;
    }
    const Snapshot& snapshot = input;
    const std::size_t n = snapshot.velocity.size();
    ShockProfile profile;
    profile.time = snapshot.time;
    if (n < 3) return profile;
    const double total = snapshot.total_mass();
    double mean_velocity = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean_velocity += snapshot.mass[i] * snapshot.velocity[i];
    mean_velocity /= total;
    double temperature = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        temperature += snapshot.mass[i] * std::pow(snapshot.velocity[i] - mean_velocity, 2);
    const double v_rms = std::sqrt(temperature / total);
    const double spacing = snapshot.ring_length / total;  // initial spacing per unit mass
    // Pair i joins point i and i+1 (cyclically), unwrapped by +L where the
    // ring closes. That is wherever the list crosses x = L -> 0, not
    // necessarily between its last point and its first: shockgas-sim lists
    // from the smallest slot, and particle 0 drifts.
    const std::size_t seam = closing_pair(snapshot.position);
    auto gap = [&](std::size_t i) {
        const std::size_t j = (i + 1) % n;
        return snapshot.position[j] - snapshot.position[i] + (i == seam ? snapshot.ring_length : 0.0);
    };
    auto drop = [&](std::size_t i) { return snapshot.velocity[(i + 1) % n] - snapshot.velocity[i]; };
    auto compressive = [&](std::size_t i) { return drop(i) < 0.0 || gap(i) < rule.cluster_gap * spacing; };
    // Start the walk just after an expanding pair, so no run is cut by the wrap.
    std::size_t start = n;
    for (std::size_t i = 0; i < n; ++i)
        if (!compressive(i)) {
            start = (i + 1) % n;
            break;
        }
    if (start == n) return profile;  // everything compressive: one cluster, no profile
    // One walk round the ring from `start`: the points in walk order, their positions made monotone
    // along it, which of them lie in a segment-breaking run, and the counted shocks.
    struct Walk {
        std::vector<std::size_t> order;  // walk order: point index at step s
        std::vector<double> unwrapped;
        std::vector<bool> in_shock;
        std::vector<double> shock_position, shock_drop;
    };
    auto walk_from = [&](std::size_t first) {
        Walk walk;
        walk.order.resize(n);
        walk.in_shock.assign(n, false);
        for (std::size_t s = 0; s < n; ++s) walk.order[s] = (first + s) % n;
        const auto& order = walk.order;
        walk.unwrapped.resize(n);
        walk.unwrapped[0] = snapshot.position[order[0]];
        for (std::size_t s = 1; s < n; ++s) walk.unwrapped[s] = walk.unwrapped[s - 1] + gap(order[s - 1]);
        std::size_t s = 0;
        while (s + 1 < n) {  // pair s joins steps s and s + 1
            if (!compressive(order[s])) {
                ++s;
                continue;
            }
            const std::size_t run_begin = s;
            double velocity_change = 0.0;
            for (;;) {
                while (s + 1 < n && compressive(order[s])) {
                    velocity_change += drop(order[s]);
                    ++s;
                }
                // A compressive run resuming within merge_gap_points expanding
                // pairs belongs to the same shock (a cluster whose members have
                // not all merged yet): the net velocity change spans both.
                std::size_t next = s;
                while (next + 1 < n && next - s < rule.merge_gap_points && !compressive(order[next])) ++next;
                if (next == s || next + 1 >= n || !compressive(order[next])) break;
                for (; s < next; ++s) velocity_change += drop(order[s]);
            }
            // Points run_begin..s form the run.
            if (-velocity_change >= rule.segment_break_fraction * v_rms)
                for (std::size_t k = run_begin; k <= s; ++k) walk.in_shock[k] = true;
            if (-velocity_change >= rule.jump_fraction * v_rms) {
                double mass = 0.0, centre = 0.0;
                for (std::size_t k = run_begin; k <= s; ++k) {
                    mass += snapshot.mass[order[k]];
                    centre += snapshot.mass[order[k]] * walk.unwrapped[k];
                }
                walk.shock_position.push_back(centre / mass);
                walk.shock_drop.push_back(-velocity_change);
            }
        }
        return walk;
    };
    Walk walk = walk_from(start);
    // The walk must begin where a segment begins: just after a segment-breaking run, followed by more
    // expanding pairs than a merge bridges. Begun inside a segment (e.g. at the first expanding pair's
    // point), it would split that segment in two, and with --merge-gap it could count a shock whose
    // parts lay at both ends of the walk twice (306 segments for a 300-tooth sawtooth, 51 shocks for
    // 50). So the first walk finds such a point and a second walk
    // starts there; without one (no segment break at all) the first walk stands.
    auto expanding_stretch_from = [&](std::size_t point) {
        for (std::size_t j = 0; j <= rule.merge_gap_points; ++j)
            if (compressive((point + j) % n)) return false;
        return true;
    };
    for (std::size_t p = 1; p < n; ++p)
        if (walk.in_shock[p - 1] && !walk.in_shock[p] && expanding_stretch_from(walk.order[p - 1])) {
            walk = walk_from(walk.order[p]);
            break;
        }
    profile.shock_position = std::move(walk.shock_position);
    profile.shock_drop = std::move(walk.shock_drop);
    const auto& order = walk.order;
    const auto& unwrapped = walk.unwrapped;
    const auto& in_shock = walk.in_shock;
    // Segments: maximal stretches of points outside shocks; Eq. (7) line fitted to each.
    std::size_t k = 0;
    while (k < n) {
        if (in_shock[k]) {
            ++k;
            continue;
        }
        const std::size_t begin = k;
        while (k < n && !in_shock[k]) ++k;
        if (k - begin < rule.min_segment_points) continue;
        std::vector<double> x, v, unit;
        double segment_mass = 0.0;
        for (std::size_t m = begin; m < k; ++m) {
            segment_mass += snapshot.mass[order[m]];
            x.push_back(unwrapped[m]);
            v.push_back(snapshot.velocity[order[m]]);
            unit.push_back(1.0);
        }
        try {
            const LinearFit line = weighted_linear_fit(x, v, unit, ErrorModel::scale_by_residuals);
            // Each point stands for the mass up to its neighbour: n - 1 gaps hold n - 1 masses' worth.
            const double density = (segment_mass - snapshot.mass[order[k - 1]]) / (x.back() - x.front());
            profile.segments.push_back({x.front(), x.back(), x.size(), line.slope, line.slope_sigma(), density});
        } catch (const InsufficientData&) {
            // Coincident positions: no slope to measure.
        }
    }
    return profile;
}

ShockSummary summarize_shocks(const std::vector<Snapshot>& snapshots, const ShockRule& rule) {
    if (snapshots.empty()) throw InsufficientData("no snapshots to look for shocks in");
    ShockSummary summary;
    summary.time = snapshots.front().time;
    summary.snapshots = snapshots.size();
    std::vector<double> counts, slopes, corrected;
    for (const auto& snapshot : snapshots) {
        const auto profile = find_shocks(snapshot, rule);
        counts.push_back(static_cast<double>(profile.shock_position.size()));
        // Only sparse stretches (rho < 1/2) are the sawtooth's rarefaction
        // segments. A dense run is a cluster whose internal velocity drops
        // stay below the segment break: its fitted "slope" is the spread of
        // velocities across a length of ~0.1 spacing (+-50 / t in the paper
        // size Fig. 5), which says nothing about Eq. (7) and, averaged in,
        // swamped the raw mean (-0.79 +- 6.3 there, 0.80 +- 0.04 without).
        for (const auto& segment : profile.segments) {
            if (!(segment.density < 0.5)) {
                ++summary.dense_segments;
                continue;
            }
            slopes.push_back(segment.slope * snapshot.time);
            corrected.push_back(segment.slope * snapshot.time / (1.0 - segment.density));
        }
    }
    summary.shocks = mean_and_standard_error(counts);
    if (counts.size() < 2) summary.shocks.note = "one snapshot at this time: no scatter between realizations";
    summary.expected_shocks = snapshots.front().total_mass() * std::pow(summary.time, -2.0 / 3.0);
    summary.segments = slopes.size();
    if (slopes.empty()) {
        // No sparse segment: the slope was not measured (it is not 0).
        const std::string why = fmt::format("no sparse segment: no run of >= {} points between drops of {:g} v_rms "
                                            "with density < 1/2",
                                            rule.min_segment_points, rule.segment_break_fraction);
        summary.slope_times_t = Estimate::missing(why);
        summary.density_corrected_slope_times_t = Estimate::missing(why);
        return summary;
    }
    summary.slope_times_t = mean_and_standard_error(slopes);
    summary.density_corrected_slope_times_t = mean_and_standard_error(corrected);
    if (slopes.size() < 2) {
        summary.slope_times_t.note = "one sparse segment: no scatter to estimate an error from";
        summary.density_corrected_slope_times_t.note = summary.slope_times_t.note;
    }
    return summary;
}

}  // namespace shockgas::analysis
