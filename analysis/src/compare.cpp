#include "shockgas/analysis/compare.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace shockgas::analysis {

TemperatureComparison compare_temperatures(const TemperatureHistory& run, const TemperatureHistory& reference,
                                           double k_sigma, double floor) {
    TemperatureComparison out;
    std::vector<bool> beyond;
    for (std::size_t k = 0; k < run.time.size(); ++k) {
        std::size_t j = 0;
        while (j < reference.time.size() && reference.time[j] != run.time[k]) ++j;
        if (j == reference.time.size()) continue;
        const double mean = run.mean(k), reference_mean = reference.mean(j);
        const double ratio = mean / reference_mean;
        const double relative_error = std::hypot(run.standard_error(k) / mean,
                                                 reference.standard_error(j) / reference_mean);
        // One realization in either run: no standard error, not a zero one.
        const double sigma = std::isfinite(relative_error) ? std::abs(ratio) * relative_error
                                                           : std::numeric_limits<double>::quiet_NaN();
        if (!std::isfinite(relative_error))
            out.sigma_note = "a run of one realization has no standard error; departure judged by the " +
                             std::to_string(static_cast<int>(std::lround(100.0 * floor))) + "% floor alone";
        const double deviation = ratio - 1.0;
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

}  // namespace shockgas::analysis
