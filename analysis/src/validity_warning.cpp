// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-sim's warning from the validity map (validity_warning.hpp). Like
// validity_map.cpp it needs no GSL: the fuzz harness compiles both beside
// shockgas-sim's main.
#include "shockgas/analysis/validity_warning.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {

namespace {

// The observable and criterion of the warning: the temperature, the paper's
// observable, by the 1 % band a user reading T(t) would notice.
constexpr const char* warned_observable = "temperature";
constexpr const char* warned_criterion = "1percent";
// A delta typed as in the map's parameter files is that delta: doubles read
// back from them agree to rounding, far inside this relative band.
constexpr double same_delta_tolerance = 1e-9;

bool same_delta(double a, double b) { return std::abs(a - b) <= same_delta_tolerance * std::max(a, b); }

}  // namespace

std::string validity_warning(const ValidityMap& map, double restitution, double velocity_threshold,
                             const std::string& subthreshold, double t_max) {
    if (!(velocity_threshold > 0.0) || !(restitution > 0.0 && restitution < 1.0) || !(t_max > 0.0)) return "";
    // delta -> t* of the largest ring measured there (the one furthest from its
    // finite-size regime).
    std::map<double, std::pair<std::int64_t, double>> departures;
    for (const auto& run : map.runs) {
        if (!same_restitution(run.restitution, restitution) || run.subthreshold != subthreshold) continue;
        const ValidityDeparture* departure = find_departure(run, warned_observable, warned_criterion);
        if (departure == nullptr || !(run.velocity_threshold > 0.0)) continue;
        auto [entry, added] = departures.try_emplace(run.velocity_threshold, run.particles, departure->departure_time);
        if (!added && run.particles > entry->second.first) entry->second = {run.particles, departure->departure_time};
    }
    if (departures.empty()) return "";
    double departure_time = std::numeric_limits<double>::quiet_NaN();
    const auto above = departures.lower_bound(velocity_threshold);
    if (above != departures.end() && same_delta(above->first, velocity_threshold)) {
        departure_time = above->second.second;
    } else if (above != departures.begin() && same_delta(std::prev(above)->first, velocity_threshold)) {
        departure_time = std::prev(above)->second.second;
    } else {
        if (above == departures.end() || above == departures.begin()) return "";  // outside the measured deltas
        const auto below = std::prev(above);
        const double t_below = below->second.second, t_above = above->second.second;
        // Both must have departed within their runs: +inf (not by the run's end)
        // or NaN (never within) leaves no time to interpolate.
        if (!std::isfinite(t_below) || !std::isfinite(t_above)) return "";
        departure_time = log_log_interpolate(below->first, t_below, above->first, t_above, velocity_threshold);
    }
    if (!std::isfinite(departure_time) || !(t_max > departure_time)) return "";
    return fmt::format("t_max = {:g} lies past the measured validity of T for r = {:g}, delta = {:g} ({}): T leaves "
                       "the sticky gas by 1 % at t* \u2248 {:.3g} ({}; docs/validity.md)",
                       t_max, restitution, velocity_threshold, subthreshold, departure_time, map.version);
}

std::string validity_warning_for_run(const std::string& map_file, bool given_by_user, double restitution,
                                     double velocity_threshold, const std::string& subthreshold, double t_max) {
    if (map_file.empty()) return "";
    if (given_by_user) return validity_warning(read_validity_map(map_file), restitution, velocity_threshold,
                                               subthreshold, t_max);
    std::error_code ignored;
    if (!std::filesystem::exists(map_file, ignored)) return "";
    try {
        return validity_warning(read_validity_map(map_file), restitution, velocity_threshold, subthreshold, t_max);
    } catch (const InputError& error) {
        return fmt::format("the validity map was not checked: {} (--validity-map FILE names another, "
                           "--validity-map '' checks none)",
                           error.what());
    }
}

}  // namespace shockgas::analysis
