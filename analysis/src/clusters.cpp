// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/clusters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "shockgas/analysis/cooling.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/spheres/ensemble.hpp"

namespace shockgas::analysis {

namespace {

// Disjoint sets of cells with union by size and path compression, near-linear
// in the cells (Tarjan, J. ACM 22, 215 (1975)). Joining each dense cell to its
// dense neighbours is the cluster labelling of Hoshen & Kopelman (Phys. Rev. B
// 14, 3438 (1976)), here with the neighbours across the periodic faces too.
class DisjointCells {
public:
    explicit DisjointCells(std::size_t cells) : parent_(cells), size_(cells, 1) {
        std::iota(parent_.begin(), parent_.end(), std::size_t{0});
    }
    std::size_t root(std::size_t cell) {
        std::size_t top = cell;
        while (parent_[top] != top) top = parent_[top];
        while (parent_[cell] != top) cell = std::exchange(parent_[cell], top);  // compress the path
        return top;
    }
    void join(std::size_t a, std::size_t b) {
        a = root(a), b = root(b);
        if (a == b) return;
        if (size_[a] < size_[b]) std::swap(a, b);
        parent_[b] = a;
        size_[a] += size_[b];
    }

private:
    std::vector<std::size_t> parent_, size_;
};

// sum numerator / sum denominator over the realizations but `left_out`, and its
// delete-one jackknife (fit.hpp); 0 where the denominator is 0 (no cluster: a
// mass-weighted mean of nothing is reported 0, as the cluster count is). A mean
// is the ratio with unit denominators.
Estimate ratio_of_sums(const std::vector<double>& numerator, const std::vector<double>& denominator) {
    return jackknife(numerator.size(), [&](std::optional<std::size_t> left_out) {
        double top = 0.0, bottom = 0.0;
        for (std::size_t i = 0; i < numerator.size(); ++i)
            if (i != left_out) top += numerator[i], bottom += denominator[i];
        return bottom > 0.0 ? top / bottom : 0.0;
    });
}

// Log bins 10^(j / cluster_bins_per_decade) from below the smallest possible
// cluster (one cell at the threshold, at least one particle) to above N.
std::vector<double> mass_bin_edges(double smallest, double particles) {
    const double per_decade = cluster_bins_per_decade;
    const int lo = static_cast<int>(std::floor(per_decade * std::log10(smallest)));
    const int hi = std::max(lo + 1, static_cast<int>(std::ceil(per_decade * std::log10(particles))));
    std::vector<double> edges;
    for (int j = lo; j <= hi; ++j) edges.push_back(std::pow(10.0, j / per_decade));
    return edges;
}

}  // namespace

std::vector<Cluster> cluster_field(std::span<const double> density, int dimension, int cells_per_side,
                                   double mean_count, double threshold) {
    if (dimension < 1 || cells_per_side < 1)
        throw std::invalid_argument(fmt::format("a field of {}^{} cells has no cells", cells_per_side, dimension));
    const auto side = static_cast<std::size_t>(cells_per_side);
    std::size_t cells = 1;
    for (int k = 0; k < dimension; ++k) cells *= side;
    if (density.size() != cells)
        throw std::invalid_argument(fmt::format("a density field of {} values is not one of {}^{} = {} cells",
                                                density.size(), cells_per_side, dimension, cells));
    const auto dense = [&](std::size_t cell) { return density[cell] >= threshold; };  // NaN is never dense
    DisjointCells sets(cells);
    // Each face once: every dense cell with its +k neighbour; the last cell
    // along k has the first as its neighbour (periodic box).
    std::size_t stride = 1;
    for (int k = 0; k < dimension; ++k, stride *= side)
        for (std::size_t cell = 0; cell < cells; ++cell) {
            if (!dense(cell)) continue;
            const std::size_t along = (cell / stride) % side;
            const std::size_t next = along + 1 < side ? cell + stride : cell - along * stride;
            if (dense(next)) sets.join(cell, next);
        }
    std::vector<Cluster> clusters;
    std::vector<std::size_t> label(cells, cells);  // root -> cluster; cells: none yet
    for (std::size_t cell = 0; cell < cells; ++cell) {
        if (!dense(cell)) continue;
        const std::size_t top = sets.root(cell);
        if (label[top] == cells) label[top] = clusters.size(), clusters.emplace_back();
        clusters[label[top]].mass += density[cell] * mean_count;
        ++clusters[label[top]].cells;
    }
    return clusters;
}

ClusterSummary summarize_clusters(const spheres::SphereOutput& run, double threshold) {
    if (!(threshold > 0.0) || !std::isfinite(threshold))
        throw std::invalid_argument(fmt::format("the density threshold must be positive and finite, not {}", threshold));
    const auto& p = run.parameters;
    const int d = p.dimension;
    const std::size_t cells = field_cell_count(p);
    const auto particles = static_cast<double>(p.particles);
    ClusterSummary summary;
    summary.threshold = threshold;
    summary.mean_count = particles / static_cast<double>(cells);
    // N_c ~ eps^(-2d/(4-d)): eps^-2 for disks, eps^-6 for spheres (Ben-Naim et al. 1999).
    const double eps = (1.0 - p.collision.restitution) / 2.0;
    summary.critical_size_scale = eps > 0.0 ? Measured{std::pow(eps, -2.0 * d / (4.0 - d)), ""}
                                            : Measured::missing("elastic gas (r = 1): no critical cluster size");
    const std::vector<double> edges = mass_bin_edges(std::max(1.0, threshold * summary.mean_count), particles);
    for (const auto& snapshot : run.result.snapshots) {
        ClusterSnapshot out;
        out.time = snapshot.time;
        out.bin_edges = edges;
        out.bin_clusters.assign(edges.size() - 1, 0.0);
        std::vector<double> count, largest, mass, mass_squared;
        for (std::int64_t r = 0; r < run.result.realizations; ++r) {
            const std::span<const double> field(snapshot.density.data() + static_cast<std::size_t>(r) * cells, cells);
            if (std::any_of(field.begin(), field.end(), [](double x) { return std::isnan(x); })) continue;
            const std::vector<Cluster> clusters = cluster_field(field, d, p.field_cells, summary.mean_count, threshold);
            double sum = 0.0, sum_squares = 0.0, biggest = 0.0;
            for (const Cluster& c : clusters) {
                sum += c.mass, sum_squares += c.mass * c.mass, biggest = std::max(biggest, c.mass);
                // Masses are whole particle counts up to rounding: bin the whole number.
                const std::ptrdiff_t above = std::upper_bound(edges.begin(), edges.end(), std::round(c.mass)) - edges.begin();
                out.bin_clusters[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(above - 1, 0, std::ssize(edges) - 2))] += 1.0;
            }
            count.push_back(static_cast<double>(clusters.size()));
            largest.push_back(biggest);
            mass.push_back(sum);
            mass_squared.push_back(sum_squares);
        }
        if (count.empty()) continue;  // no realization reached this snapshot
        out.realizations = count.size();
        const std::vector<double> ones(count.size(), 1.0), totals(count.size(), particles);
        out.clusters = ratio_of_sums(count, ones);
        out.largest_mass = ratio_of_sums(largest, ones);
        out.mean_mass = ratio_of_sums(mass_squared, mass);  // sum m^2 / sum m over the pooled clusters
        out.clustered_fraction = ratio_of_sums(mass, totals);
        summary.snapshots.push_back(std::move(out));
    }
    return summary;
}

void run_clusters(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, double threshold, const std::string& data,
                  const std::string& distribution, const std::string& maps) {
    std::vector<spheres::SphereOutput> runs;
    for (const auto& input : inputs) runs.push_back(spheres::read_spheres_output(input));
    ResultsFile results(output, invocation, inputs);
    std::optional<DataFile> table, histogram;
    if (!data.empty())
        table.emplace(data, "clusters of field cells at density >= threshold x mean, per snapshot; a block per input",
                      inputs,
                      std::vector<std::string>{"t", "clusters", "clusters_sigma", "mean_mass", "mean_mass_sigma",
                                               "largest_mass", "largest_mass_sigma", "clustered_fraction",
                                               "clustered_fraction_sigma"});
    if (!distribution.empty())
        histogram.emplace(distribution,
                          "cluster masses in log bins, pooled over realizations; a block per input and snapshot",
                          inputs,
                          std::vector<std::string>{"mass_lo", "mass_hi", "mass_centre", "clusters_per_realization",
                                                   "clusters_per_unit_mass_per_realization"});
    for (std::size_t f = 0; f < runs.size(); ++f) {
        const auto& p = runs[f].parameters;
        const ClusterSummary summary = summarize_clusters(runs[f], threshold);
        const std::string label = fmt::format("{}D r = {} phi = {} N = {}, {}^{} field cells, threshold {}",
                                              p.dimension, p.collision.restitution, p.packing_fraction, p.particles,
                                              p.field_cells, p.dimension, threshold);
        auto section = results.section(fmt::format("clusters{}", f));
        section.set_attribute("dimension", static_cast<std::int64_t>(p.dimension));
        section.set_attribute("particles", static_cast<std::int64_t>(p.particles));
        section.set_attribute("restitution", p.collision.restitution);
        section.set_attribute("packing_fraction", p.packing_fraction);
        section.set_attribute("field_cells", static_cast<std::int64_t>(p.field_cells));
        section.set_attribute("threshold", threshold);
        section.set_attribute("mean_count", summary.mean_count);
        set_measured(section, "critical_size_scale", summary.critical_size_scale);
        auto snapshots = section.create_group("snapshots");
        if (table) {
            if (f > 0) table->blank_line();  // two empty lines: gnuplot's next index
            table->comment(label);
        }
        fmt::print("{}; eps^(-2d/(4-d)) = {}\n", label, format_measured(summary.critical_size_scale, "{:.4g}"));
        for (std::size_t s = 0; s < summary.snapshots.size(); ++s) {
            const ClusterSnapshot& at = summary.snapshots[s];
            auto group = snapshots.create_group(h5::numbered_name(s, summary.snapshots.size()));
            group.set_attribute("time", at.time);
            group.set_attribute("realizations", static_cast<std::int64_t>(at.realizations));
            set_estimate(group, "clusters", at.clusters);
            set_estimate(group, "mean_mass", at.mean_mass);
            set_estimate(group, "largest_mass", at.largest_mass);
            set_estimate(group, "clustered_fraction", at.clustered_fraction);
            group.write("bin_edges", at.bin_edges);
            group.write("bin_clusters", at.bin_clusters);
            if (table)
                table->row({at.time, at.clusters.value, at.clusters.sigma, at.mean_mass.value, at.mean_mass.sigma,
                            at.largest_mass.value, at.largest_mass.sigma, at.clustered_fraction.value,
                            at.clustered_fraction.sigma});
            if (histogram) {
                if (f > 0 || s > 0) histogram->blank_line();
                histogram->comment(fmt::format("{}; t = {:.6g}, {} realizations", label, at.time, at.realizations));
                const auto realizations = static_cast<double>(at.realizations);
                for (std::size_t b = 0; b + 1 < at.bin_edges.size(); ++b) {
                    const double lo = at.bin_edges[b], hi = at.bin_edges[b + 1];
                    histogram->row({lo, hi, std::sqrt(lo * hi), at.bin_clusters[b] / realizations,
                                    at.bin_clusters[b] / realizations / (hi - lo)});
                }
            }
            fmt::print("  t = {:.6g}: {} clusters, largest {} particles, mass-weighted mean {}, fraction in clusters {}\n",
                       at.time, format_estimate(at.clusters, "{:.4g}", "{:.2g}"),
                       format_estimate(at.largest_mass, "{:.4g}", "{:.2g}"),
                       format_estimate(at.mean_mass, "{:.4g}", "{:.2g}"),
                       format_estimate(at.clustered_fraction, "{:.4f}"));
        }
    }
    std::optional<DataFile> density_maps;
    if (!maps.empty()) {
        const auto first_2d = std::find_if(runs.begin(), runs.end(), [](const spheres::SphereOutput& run) {
            return run.parameters.dimension == 2 && !run.result.snapshots.empty();
        });
        if (first_2d == runs.end()) throw InputError("--maps needs a 2D input with snapshots");
        const auto& p = first_2d->parameters;
        const double cell = spheres::box_length(2, p.particles, p.packing_fraction) / p.field_cells;
        const auto side = static_cast<std::size_t>(p.field_cells);
        density_maps.emplace(maps,
                             fmt::format("density / mean of realization 0 on {}^2 cells of side {:.6g}, 2D r = {} "
                                         "N = {}; a block per snapshot (times in the block comments)",
                                         side, cell, p.collision.restitution, p.particles),
                             inputs, std::vector<std::string>{"x", "y", "density"});
        for (std::size_t s = 0; s < first_2d->result.snapshots.size(); ++s) {
            const auto& snapshot = first_2d->result.snapshots[s];
            if (s > 0) density_maps->blank_line();
            density_maps->comment(fmt::format("t = {:.6g}", snapshot.time));
            for (std::size_t iy = 0; iy < side; ++iy) {  // cell index ix + side iy: x fastest (realization 0's row)
                for (std::size_t ix = 0; ix < side; ++ix)
                    density_maps->row({(static_cast<double>(ix) + 0.5) * cell, (static_cast<double>(iy) + 0.5) * cell,
                                       snapshot.density[ix + side * iy]});
            }
        }
    }
    commit_outputs(&results, {table ? &*table : nullptr, histogram ? &*histogram : nullptr,
                              density_maps ? &*density_maps : nullptr});
}

}  // namespace shockgas::analysis
