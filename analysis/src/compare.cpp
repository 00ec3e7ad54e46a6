#include "shockgas/analysis/compare.hpp"

#include <cmath>
#include <limits>

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
        const double sigma = std::abs(ratio) * (std::isfinite(relative_error) ? relative_error : 0.0);
        const double deviation = ratio - 1.0;
        out.time.push_back(run.time[k]);
        out.relative_deviation.push_back(deviation);
        out.relative_sigma.push_back(sigma);
        if (std::abs(deviation) > out.max_abs_deviation) {
            out.max_abs_deviation = std::abs(deviation);
            out.time_of_max = run.time[k];
        }
        beyond.push_back(std::abs(deviation) > std::max(k_sigma * sigma, floor));
    }
    // Departure: the start of the final run of "beyond" samples.
    out.departure_time = std::numeric_limits<double>::infinity();
    for (std::size_t k = beyond.size(); k-- > 0;) {
        if (!beyond[k]) break;
        out.departure_time = out.time[k];
    }
    return out;
}

}  // namespace shockgas::analysis
