// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/cooling.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/kinetic_theory.hpp"

namespace shockgas::analysis {

namespace {

// The realization's temperatures (NaN after a collapse) at sample k, or the
// mean over all realizations but `left_out`.
double mean_temperature(const spheres::SphereResult& r, std::size_t k, std::optional<std::size_t> left_out) {
    double sum = 0.0;
    int count = 0;
    for (std::int64_t i = 0; i < r.realizations; ++i) {
        if (left_out && static_cast<std::size_t>(i) == *left_out) continue;
        sum += r.at(r.temperature, i, k);
        ++count;
    }
    return sum / count;
}

}  // namespace

std::size_t field_cell_count(const spheres::SphereParameters& p) {
    std::size_t cells = 1;
    for (int k = 0; k < p.dimension; ++k) cells *= static_cast<std::size_t>(p.field_cells);
    return cells;
}

double clustering_index(const std::vector<double>& density, std::size_t first_cell, std::size_t cells,
                        double mean_count) {
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t c = first_cell; c < first_cell + cells; ++c) {
        sum += density[c];
        sum2 += density[c] * density[c];
    }
    const double mean = sum / static_cast<double>(cells);
    return mean_count * (sum2 / static_cast<double>(cells) - mean * mean);
}

CoolingSummary summarize_cooling(const spheres::SphereOutput& run) {
    const auto& p = run.parameters;
    const auto& r = run.result;
    CoolingSummary summary;
    summary.haff_time = spheres::haff_time(p.dimension, p.packing_fraction, p.collision.restitution);
    std::vector<std::size_t> window;
    for (std::size_t k = 0; k < r.time.size(); ++k)
        if (r.time[k] > 0.0 && r.time[k] <= summary.haff_time * (1.0 + 1e-12)) window.push_back(k);
    if (window.size() < 3) throw InsufficientData("fewer than 3 samples in 0 < t <= t0 for the Haff fit");
    for (std::size_t k : window) {
        const double ratio = mean_temperature(r, k, std::nullopt) / spheres::haff_temperature(r.time[k], summary.haff_time);
        summary.largest_haff_deviation = std::max(summary.largest_haff_deviation, std::abs(ratio - 1.0));
    }
    // T^(-1/2) = 1 + t / t0 (Haff): the slope of T^(-1/2) against t is 1/t0.
    auto fitted = [&](std::optional<std::size_t> left_out) {
        std::vector<double> x, y, sigma;
        for (std::size_t k : window) {
            x.push_back(r.time[k]);
            y.push_back(1.0 / std::sqrt(mean_temperature(r, k, left_out)));
            sigma.push_back(1.0);
        }
        return 1.0 / weighted_linear_fit(x, y, sigma, ErrorModel::scale_by_residuals).slope;
    };
    summary.fitted_haff_time = jackknife(static_cast<std::size_t>(r.realizations), fitted);
    if (!r.snapshots.empty()) {
        const auto& last = r.snapshots.back();
        const std::size_t cells = field_cell_count(p);
        const double mean_count = static_cast<double>(p.particles) / static_cast<double>(cells);
        std::vector<double> values;
        for (std::int64_t i = 0; i < r.realizations; ++i)
            values.push_back(clustering_index(last.density, static_cast<std::size_t>(i) * cells, cells, mean_count));
        summary.final_clustering_index = mean_and_standard_error(values);
    }
    return summary;
}

void run_cooling(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                 const std::string& output, const std::string& data, const std::string& clustering,
                 const std::string& picture) {
    std::vector<spheres::SphereOutput> runs;
    for (const auto& input : inputs) runs.push_back(spheres::read_spheres_output(input));
    ResultsFile results(output, invocation, inputs);
    std::optional<DataFile> table, clusters, positions;
    if (!data.empty())
        table.emplace(data, "T(t) of disk and sphere gases against Haff's law with Enskog's t0; a block per input",
                      inputs,
                      std::vector<std::string>{"t", "t_over_t0", "T", "T_sigma", "T_haff", "T_over_haff",
                                               "T_over_haff_sigma"});
    if (!clustering.empty())
        clusters.emplace(clustering, "clustering index (count variance over mean per field cell); a block per input",
                         inputs, std::vector<std::string>{"t", "t_over_t0", "index", "index_sigma"});
    for (std::size_t f = 0; f < runs.size(); ++f) {
        const auto& run = runs[f];
        const auto& p = run.parameters;
        const auto& r = run.result;
        const CoolingSummary summary = summarize_cooling(run);
        auto section = results.section(fmt::format("input{}", f));
        section.set_attribute("dimension", static_cast<std::int64_t>(p.dimension));
        section.set_attribute("restitution", p.collision.restitution);
        section.set_attribute("packing_fraction", p.packing_fraction);
        section.set_attribute("haff_time", summary.haff_time);
        set_estimate(section, "fitted_haff_time", summary.fitted_haff_time);
        section.set_attribute("largest_haff_deviation", summary.largest_haff_deviation);
        set_estimate(section, "final_clustering_index", summary.final_clustering_index);
        if (table) {
            if (f > 0) table->blank_line(), table->blank_line();
            table->comment(fmt::format("{}D r = {} phi = {} N = {}: t0 = {:.6g}", p.dimension, p.collision.restitution,
                                       p.packing_fraction, p.particles, summary.haff_time));
            for (std::size_t k = 1; k < r.time.size(); ++k) {
                std::vector<double> values;
                for (std::int64_t i = 0; i < r.realizations; ++i) values.push_back(r.at(r.temperature, i, k));
                const Estimate temperature = mean_and_standard_error(values);
                const double haff = spheres::haff_temperature(r.time[k], summary.haff_time);
                const double sigma = temperature.sigma;
                table->row({r.time[k], r.time[k] / summary.haff_time, temperature.value, sigma, haff,
                            temperature.value / haff, sigma / haff});
            }
        }
        if (clusters) {
            if (f > 0) clusters->blank_line(), clusters->blank_line();
            clusters->comment(fmt::format("{}D r = {} phi = {} N = {}, {}^{} field cells", p.dimension,
                                          p.collision.restitution, p.packing_fraction, p.particles, p.field_cells,
                                          p.dimension));
            const std::size_t cells = field_cell_count(p);
            const double mean_count = static_cast<double>(p.particles) / static_cast<double>(cells);
            for (const auto& snapshot : r.snapshots) {
                std::vector<double> values;
                for (std::int64_t i = 0; i < r.realizations; ++i)
                    values.push_back(
                        clustering_index(snapshot.density, static_cast<std::size_t>(i) * cells, cells, mean_count));
                const Estimate index = mean_and_standard_error(values);
                clusters->row({snapshot.time, snapshot.time / summary.haff_time, index.value,
                               index.sigma});
            }
        }
        fmt::print("{}D r = {} phi = {}: t0 = {:.4g} (Enskog), {} (fit); |T/T_Haff - 1| <= {:.4f} for t <= t0; "
                   "clustering index {}\n",
                   p.dimension, p.collision.restitution, p.packing_fraction, summary.haff_time,
                   format_estimate(summary.fitted_haff_time, "{:.4g}"), summary.largest_haff_deviation,
                   format_estimate(summary.final_clustering_index, "{:.3g}"));
    }
    if (!picture.empty()) {
        const spheres::SphereOutput* first_2d = nullptr;
        for (const auto& run : runs)
            if (run.parameters.dimension == 2 && !run.result.snapshots.empty() && first_2d == nullptr) first_2d = &run;
        if (first_2d == nullptr) throw InputError("--picture needs a 2D input with snapshots");
        const auto& snapshot = first_2d->result.snapshots.back();
        positions.emplace(picture, fmt::format("disk centres of realization 0 at t = {:.6g}; box side {:.10g}",
                                               snapshot.time,
                                               spheres::box_length(2, first_2d->parameters.particles,
                                                                   first_2d->parameters.packing_fraction)),
                          inputs, std::vector<std::string>{"x", "y", "speed"});
        for (std::size_t i = 0; i + 1 < snapshot.positions.size(); i += 2)
            positions->row({snapshot.positions[i], snapshot.positions[i + 1],
                            std::hypot(snapshot.velocities[i], snapshot.velocities[i + 1])});
    }
    commit_outputs(&results, {table ? &*table : nullptr, clusters ? &*clusters : nullptr,
                              positions ? &*positions : nullptr});
}

}  // namespace shockgas::analysis
