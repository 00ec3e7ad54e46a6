// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace shockgas::analysis {

namespace {

// Paired realizations 0..n-1: the ratio of the sums minus 1 (relative) or
// the difference of the means (absolute), and its delete-one-pair jackknife
// error (the analysis library's jackknife, Efron & Tibshirani 1993, Eq. 11.5;
// sigma NaN with one pair).
Estimate paired_deviation(const TemperatureHistory& run, std::size_t k, const TemperatureHistory& reference,
                          std::size_t j, std::size_t n, Deviation deviation) {
    double sum = 0.0, reference_sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        sum += run.at(i, k);
        reference_sum += reference.at(i, j);
    }
    return jackknife(n, [&](std::optional<std::size_t> left_out) {
        const double a = left_out ? sum - run.at(*left_out, k) : sum;
        const double b = left_out ? reference_sum - reference.at(*left_out, j) : reference_sum;
        const double count = static_cast<double>(left_out ? n - 1 : n);
        return deviation == Deviation::relative ? a / b - 1.0 : (a - b) / count;
    });
}

// Independent ensembles: the ratio of the means minus 1, or their
// difference, its error by first-order propagation of both standard errors.
Estimate independent_deviation(const TemperatureHistory& run, std::size_t k, const TemperatureHistory& reference,
                               std::size_t j, Deviation deviation) {
    const double mean = run.mean(k), reference_mean = reference.mean(j);
    if (deviation == Deviation::absolute) {
        const double error = std::hypot(run.standard_error(k), reference.standard_error(j));
        return {mean - reference_mean, std::isfinite(error) ? error : std::numeric_limits<double>::quiet_NaN()};
    }
    const double value = mean / reference_mean;
    const double relative_error =
        std::hypot(run.standard_error(k) / mean, reference.standard_error(j) / reference_mean);
    return {value - 1.0, std::isfinite(relative_error) ? std::abs(value) * relative_error
                                                       : std::numeric_limits<double>::quiet_NaN()};
}

}  // namespace

TemperatureComparison compare_temperatures(const TemperatureHistory& run, const TemperatureHistory& reference,
                                           Realizations realizations, double k_sigma, double floor) {
    return compare_histories(run, reference, realizations, Deviation::relative, k_sigma, floor);
}

TemperatureComparison compare_histories(const TemperatureHistory& run, const TemperatureHistory& reference,
                                        Realizations realizations, Deviation mode, double k_sigma, double floor) {
    TemperatureComparison out;
    const bool paired = realizations == Realizations::paired;
    const std::size_t common = std::min(run.realizations, reference.realizations);
    if (paired) {
        out.realizations_compared = common;
        if (run.realizations != reference.realizations)
            out.pairing_note = fmt::format("compared over realizations 0..{} (paired, the same initial states in both "
                                           "runs); the run has {}, the reference {}",
                                           common - 1, run.realizations, reference.realizations);
    }
    std::vector<bool> beyond;
    for (std::size_t k = 0; k < run.time.size(); ++k) {
        std::size_t j = 0;
        while (j < reference.time.size() && reference.time[j] != run.time[k]) ++j;
        if (j == reference.time.size()) continue;
        const Estimate estimate = paired ? paired_deviation(run, k, reference, j, common, mode)
                                         : independent_deviation(run, k, reference, j, mode);
        const double sigma = estimate.sigma;
        // One realization (in common): no standard error, not a zero one.
        if (std::isnan(sigma))
            out.sigma_note = std::string(paired ? "one realization in common" : "a run of one realization") +
                             " has no standard error; departure judged by the " +
                             std::to_string(static_cast<int>(std::lround(100.0 * floor))) + "% floor alone";
        const double deviation = estimate.value;
        out.time.push_back(run.time[k]);
        out.relative_deviation.push_back(deviation);
        out.relative_sigma.push_back(sigma);
        // The first common time starts the search (identical runs: 0 there, not at t = 0).
        if (out.time.size() == 1 || std::abs(deviation) > out.max_abs_deviation) {
            out.max_abs_deviation = std::abs(deviation);
            out.time_of_max = run.time[k];
        }
        beyond.push_back(std::abs(deviation) > (std::isnan(sigma) ? floor : std::max(k_sigma * sigma, floor)));
    }
    if (out.time.empty())
        throw InsufficientData("no sample time in common with the reference run (compare needs runs sampled on the "
                               "same times; the reference has " +
                               std::to_string(reference.time.size()) + " sample times, this run " +
                               std::to_string(run.time.size()) + ")");
    // Departure: the start of the final run of "beyond" samples.
    out.departure_time = std::numeric_limits<double>::infinity();
    for (std::size_t k = beyond.size(); k-- > 0;) {
        if (!beyond[k]) break;
        out.departure_time = out.time[k];
    }
    return out;
}

namespace {

enum class Stored { integer, number, text };

// A root attribute as text in its stored type (HDF5 would convert a double
// read as an integer, 0.9 to 0); numbers in the shortest form that reads back
// exactly, so that 0.9 and 0.9000000001 differ.
std::string attribute_text(const h5::Group& root, const std::string& name, Stored stored) {
    switch (stored) {
        case Stored::integer: return fmt::format("{}", root.attribute_integer(name));
        case Stored::number: return fmt::format("{}", root.attribute_double(name));
        case Stored::text: break;
    }
    return root.attribute_string(name);
}

}  // namespace

std::string comparison_differences(const std::string& reference_path, const std::string& run_path,
                                   bool same_restitution) {
    // The parameters that make two runs one ensemble up to delta and the
    // sub-threshold rule (compare.hpp), as write_parameter_attributes stores them.
    static const std::pair<const char*, Stored> shared[] = {
        {"particles", Stored::integer},       {"ring_length", Stored::number},
        {"restitution", Stored::number},      {"seed", Stored::integer},
        {"first_realization", Stored::integer}, {"positions", Stored::text},
        {"velocity_distribution", Stored::text}, {"init_file_sha256", Stored::text}};
    const auto reference_file = h5::File::open_read(reference_path);
    const auto run_file = h5::File::open_read(run_path);
    const auto reference = reference_file.root();
    const auto run = run_file.root();
    check_simulation_output(reference, reference_path);
    check_simulation_output(run, run_path);
    std::vector<std::string> differences;
    for (const auto& [name, stored] : shared) {
        if (!same_restitution && std::string(name) == "restitution") continue;
        if (!reference.has_attribute(name) || !run.has_attribute(name)) continue;
        const std::string ours = attribute_text(run, name, stored), theirs = attribute_text(reference, name, stored);
        if (ours != theirs)
            differences.push_back(fmt::format("{} {} vs {}", name, ours.empty() ? "(none)" : ours,
                                              theirs.empty() ? "(none)" : theirs));
    }
    return fmt::format("{}", fmt::join(differences, ", "));
}

}  // namespace shockgas::analysis
