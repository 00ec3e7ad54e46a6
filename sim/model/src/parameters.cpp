// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/model/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace shockgas {

std::string to_string(Subthreshold mechanism) {
    return mechanism == Subthreshold::elastic ? "elastic" : "sticky";
}

Subthreshold subthreshold_from_string(const std::string& name) {
    if (name == "elastic") return Subthreshold::elastic;
    if (name == "sticky") return Subthreshold::sticky;
    throw InputError(fmt::format("sub-threshold mechanism must be 'elastic' or 'sticky', got '{}'", name));
}

std::string to_string(PositionLaw law) { return law == PositionLaw::lattice ? "lattice" : "uniform"; }
std::string to_string(VelocityLaw law) { return law == VelocityLaw::uniform ? "uniform" : "gaussian"; }

PositionLaw position_law_from_string(const std::string& name) {
    if (name == "lattice") return PositionLaw::lattice;
    if (name == "uniform") return PositionLaw::uniform;
    throw InputError(fmt::format("positions must be 'lattice' or 'uniform', got '{}'", name));
}

VelocityLaw velocity_law_from_string(const std::string& name) {
    if (name == "uniform") return VelocityLaw::uniform;
    if (name == "gaussian") return VelocityLaw::gaussian;
    throw InputError(fmt::format("velocity distribution must be 'uniform' or 'gaussian', got '{}'", name));
}

namespace {
void check_times(const std::vector<double>& times, double t_max, const char* what) {
    for (double t : times) {
        if (!std::isfinite(t) || t <= 0.0)
            throw InputError(fmt::format("{} must be positive and finite, got {}", what, t));
        if (t > t_max)
            throw InputError(fmt::format("{} {} is beyond t_max = {}", what, t, t_max));
    }
}
}  // namespace

void validate(const SimulationParameters& p) {
    const auto& c = p.collision;
    if (!(c.restitution >= 0.0 && c.restitution <= 1.0))
        throw InputError(fmt::format("restitution r must lie in [0, 1], got {}", c.restitution));
    if (!(c.velocity_threshold >= 0.0) || !std::isfinite(c.velocity_threshold))
        throw InputError(fmt::format("velocity threshold delta must be finite and >= 0, got {}",
                                     c.velocity_threshold));
    if (p.particles < 2)
        throw InputError(fmt::format("particles N must be at least 2, got {}", p.particles));
    if (p.particles > (std::int64_t{1} << 31) - 2)
        throw InputError(fmt::format("particles N must be below 2^31, got {}", p.particles));
    if (p.ring_length < 0.0 || !std::isfinite(p.ring_length))
        throw InputError(fmt::format("ring length L must be positive, got {}", p.ring_length));
    if (!(p.t_max > 0.0) || !std::isfinite(p.t_max))
        throw InputError(fmt::format("t_max must be positive and finite, got {}", p.t_max));
    // The scales double precision must resolve (docs/reliability.md, "Scales
    // and shifts"). The model is invariant under x -> lambda x, t -> lambda t,
    // so a ring outside them is the same physics as one scaled into them.
    const double length = p.effective_ring_length();
    const double spacing = length / static_cast<double>(p.particles);
    constexpr double smallest_spacing = std::numeric_limits<double>::min();
    if (spacing < smallest_spacing)
        throw InputError(fmt::format(
            "ring length L = {} gives a spacing L/N = {:.3g}, below the smallest normal double {:.3g}, where "
            "gaps lose significant bits; the model is scale-invariant (x -> lambda x, t -> lambda t): give L at "
            "least {:.3g} and scale t_max with it",
            length, spacing, smallest_spacing, smallest_spacing * static_cast<double>(p.particles)));
    if (length > largest_ring_length)
        throw InputError(fmt::format(
            "ring length L = {} is beyond {:.3g} (2^1020): the engines form coordinates of a few ring lengths, "
            "which would overflow double precision; the model is scale-invariant (x -> lambda x, t -> lambda t): "
            "give a smaller L and scale t_max with it",
            length, largest_ring_length));
    if (p.t_max > largest_t_max)
        throw InputError(fmt::format(
            "t_max = {} is beyond {:.3g} (2^1018): positions move by up to |v| t_max, which would overflow double "
            "precision; the model is scale-invariant (x -> lambda x, t -> lambda t): give a smaller t_max, and "
            "L with it",
            p.t_max, largest_t_max));
    if (p.samples_per_decade < 1 || p.samples_per_decade > 1000)
        throw InputError(fmt::format("samples per decade must lie in [1, 1000], got {}", p.samples_per_decade));
    if (p.realizations < 1)
        throw InputError(fmt::format("realizations must be at least 1, got {}", p.realizations));
    if (p.first_realization < 0)
        throw InputError(fmt::format("first realization must be >= 0, got {}", p.first_realization));
    // Realization F + k seeds its own stream (and is stored as a signed 64-bit
    // number): the last one, F + R - 1, must not pass 2^63 - 1.
    if (p.first_realization > std::numeric_limits<std::int64_t>::max() - (p.realizations - 1))
        throw InputError(fmt::format("first realization {} with {} realizations runs past 2^63 - 1", p.first_realization,
                                     p.realizations));
    // Stored as a signed 64-bit attribute (output.cpp): larger seeds would
    // read back negative everywhere but in shockgas's own reader.
    if (p.seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        throw InputError(fmt::format("seed must be below 2^63, got {}", p.seed));
    if (p.threads < 0) throw InputError(fmt::format("threads must be >= 0, got {}", p.threads));
    // At most 10^7 bins: already 10^-6 of the range per bin, finer than the
    // N R samples of any run can fill (the paper's Fig. 4 has 2·10^7), and a
    // row of 80 MB per realization and time. A billion bins took 23 GiB and
    // then failed in HDF5 (a chunk is at most 4 GiB).
    constexpr int most_histogram_bins = 10'000'000;
    if (p.histogram_bins < 1 || p.histogram_bins > most_histogram_bins)
        throw InputError(fmt::format("histogram bins must lie in [1, {}], got {}", most_histogram_bins, p.histogram_bins));
    if (!(p.histogram_range > 0.0) || !std::isfinite(p.histogram_range))
        throw InputError(fmt::format("histogram range must be positive, got {}", p.histogram_range));
    if (!(p.collapse.collapse_speed >= 0.0))
        throw InputError(fmt::format("collapse speed must be >= 0, got {}", p.collapse.collapse_speed));
    // Above delta > 0 the criterion would fire on ordinary inelastic collisions (g >= delta) and declare
    // a collapse that the threshold forbids: the analysis then refuses the run as one that cannot
    // collapse, and the pass-through engine refuses these parameters.
    if (p.collision.velocity_threshold > 0.0 && p.collapse.collapse_speed > p.collision.velocity_threshold)
        throw InputError(fmt::format("collapse speed {} exceeds the threshold delta = {}: every inelastic collision "
                                     "is then at least delta, so no collapse can happen, and one would be declared "
                                     "falsely; give --collapse-speed at most delta (the default is {})",
                                     p.collapse.collapse_speed, p.collision.velocity_threshold,
                                     CollapseCriterion{}.collapse_speed));
    check_times(p.sample_times, p.t_max, "sample time");
    check_times(p.snapshot_times, p.t_max, "snapshot time");
    check_times(p.histogram_times, p.t_max, "histogram time");
    if (p.engine != "event" && p.engine != "reference" && p.engine != "exact" && p.engine != "passthrough" &&
        p.engine != "hybrid" && p.engine != "auto")
        throw InputError(fmt::format(
            "engine must be 'event', 'reference', 'exact', 'passthrough', 'hybrid' or 'auto', got '{}'", p.engine));
}

std::vector<double> sample_grid(const SimulationParameters& p) {
    // t = 0 first: the start's temperature (1/3 for the uniform law) belongs in
    // the time series a notebook reads. Log-log analyses drop it (analysis's
    // TemperatureHistory keeps t > 0 only).
    std::vector<double> grid{0.0};
    // Log grid t_k = 10^(k / K), k = 0, 1, ... while t_k < t_max; computed from
    // k (not by repeated multiplication) so every run has identical times.
    for (int k = 0;; ++k) {
        const double t = std::pow(10.0, static_cast<double>(k) / p.samples_per_decade);
        if (t >= p.t_max * (1.0 - 1e-12)) break;
        grid.push_back(t);
    }
    grid.push_back(p.t_max);
    for (const auto* list : {&p.sample_times, &p.snapshot_times, &p.histogram_times})
        grid.insert(grid.end(), list->begin(), list->end());
    std::sort(grid.begin(), grid.end());
    grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
    return grid;
}

std::vector<double> evenly_spaced_times(double interval, double t_max) {
    if (!(interval > 0.0) || !std::isfinite(interval))
        throw InputError(fmt::format("snapshot interval must be positive, got {}", interval));
    if (t_max / interval > 1e6)
        throw InputError(fmt::format("snapshot interval {} gives more than 10^6 snapshots", interval));
    // As a --snapshot-times entry past t_max is refused: asked for, none would be taken, without a word.
    if (interval > t_max * (1.0 + 1e-12))
        throw InputError(fmt::format("snapshot interval {} exceeds t_max = {}: no snapshot would be taken", interval,
                                     t_max));
    std::vector<double> times;
    for (std::int64_t k = 1; static_cast<double>(k) * interval <= t_max * (1.0 + 1e-12); ++k)
        times.push_back(std::min(static_cast<double>(k) * interval, t_max));
    return times;
}

}  // namespace shockgas
