// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/spheres/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace shockgas::spheres {

std::string to_string(StartMethod method) { return method == StartMethod::insertion ? "insertion" : "lattice"; }

StartMethod start_method_from_string(const std::string& name) {
    if (name == "insertion") return StartMethod::insertion;
    if (name == "lattice") return StartMethod::lattice;
    throw InputError(fmt::format("unknown start method '{}' (insertion or lattice)", name));
}

// Random sequential insertion is offered to 0.35 (d = 3) and 0.50 (d = 2),
// safely below its jamming limits 0.384 and 0.547 (Cooper, Phys. Rev. A 38, 522
// (1988); Feder, J. Theor. Biol. 87, 237 (1980)), where it still takes a few
// attempts per sphere.
double insertion_packing_limit(int dimension) { return dimension == 2 ? 0.50 : 0.35; }

double lattice_packing_limit(int dimension) { return sphere_volume(dimension); }

// pi/4 and pi/6: the area of a disk and the volume of a sphere of diameter 1.
double sphere_volume(int dimension) { return dimension == 2 ? std::numbers::pi / 4.0 : std::numbers::pi / 6.0; }

double box_length(int dimension, std::int64_t particles, double packing_fraction) {
    return std::pow(static_cast<double>(particles) * sphere_volume(dimension) / packing_fraction, 1.0 / dimension);
}

// Cells at least one diameter (and a part in 10^9 more, so that a particle a
// round-off outside its cell is still within reach of the 3^d cells around it).
int cells_per_side(double box_length) {
    return static_cast<int>(std::min(1e6, std::floor(box_length / (1.0 + 1e-9))));
}

void validate(const SphereParameters& p) {
    if (p.dimension != 2 && p.dimension != 3)
        throw InputError(fmt::format("--dimension {} is not 2 or 3", p.dimension));
    if (p.particles < 2 || p.particles > (std::int64_t{1} << 30))
        throw InputError(fmt::format("--particles {} is outside [2, 2^30]", p.particles));
    const double limit = p.start == StartMethod::insertion ? insertion_packing_limit(p.dimension)
                                                           : lattice_packing_limit(p.dimension);
    if (!(p.packing_fraction > 0.0) || !(p.packing_fraction <= limit))
        throw InputError(fmt::format("--packing-fraction {} is outside (0, {:.4g}], what the {} start reaches in {}D{}",
                                     p.packing_fraction, limit, to_string(p.start), p.dimension,
                                     p.start == StartMethod::insertion && p.packing_fraction > limit &&
                                             p.packing_fraction <= lattice_packing_limit(p.dimension)
                                         ? " (--start lattice goes further)"
                                         : ""));
    if (p.start == StartMethod::lattice) {
        // The lattice's spacing L / ceil(N^(1/d)) must be at least one diameter.
        const double side = box_length(p.dimension, p.particles, p.packing_fraction);
        const double sites_per_side = std::ceil(std::pow(static_cast<double>(p.particles), 1.0 / p.dimension) - 1e-9);
        if (side / sites_per_side < 1.0)
            throw InputError(fmt::format("--packing-fraction {} is too high for a lattice start of {} particles: "
                                         "its spacing {:.6g} is below one diameter",
                                         p.packing_fraction, p.particles, side / sites_per_side));
    }
    const double side = box_length(p.dimension, p.particles, p.packing_fraction);
    if (cells_per_side(side) < 3)
        throw InputError(fmt::format("{} particles at packing fraction {} make a box of side {:.4g}, less than 3 "
                                     "diameters: use more particles",
                                     p.particles, p.packing_fraction, side));
    if (!(p.collision.restitution > 0.0 && p.collision.restitution <= 1.0))
        throw InputError(fmt::format("--restitution {} is outside (0, 1] (disks and spheres do not merge)",
                                     p.collision.restitution));
    if (!(p.collision.velocity_threshold >= 0.0) || !std::isfinite(p.collision.velocity_threshold))
        throw InputError(fmt::format("--threshold {} must be finite and >= 0", p.collision.velocity_threshold));
    if (p.collision.subthreshold != Subthreshold::elastic)
        throw InputError("--subthreshold sticky is the ring's rule; disks and spheres take elastic");
    if (!(p.collapse_speed > 0.0)) throw InputError(fmt::format("--collapse-speed {} must be > 0", p.collapse_speed));
    if (!(p.melt_collisions_per_particle >= 0.0) || !(p.melt_collisions_per_particle <= 1e6))
        throw InputError(fmt::format("--melt {} is outside [0, 10^6] collisions per particle",
                                     p.melt_collisions_per_particle));
    if (!(p.t_max > 0.0) || !std::isfinite(p.t_max) || p.t_max > 1e15)
        throw InputError(fmt::format("--t-max {} is outside (0, 10^15]", p.t_max));
    if (p.samples_per_decade < 1 || p.samples_per_decade > 1000)
        throw InputError(fmt::format("--samples-per-decade {} is outside [1, 1000]", p.samples_per_decade));
    for (const auto* times : {&p.sample_times, &p.snapshot_times, &p.histogram_times})
        for (double t : *times)
            if (!(t >= 0.0 && t <= p.t_max))
                throw InputError(fmt::format("time {} is outside [0, t-max = {}]", t, p.t_max));
    if (p.histogram_bins < 2 || p.histogram_bins > 100000)
        throw InputError(fmt::format("--histogram-bins {} is outside [2, 10^5]", p.histogram_bins));
    if (!(p.histogram_range > 0.0) || !std::isfinite(p.histogram_range))
        throw InputError(fmt::format("--histogram-range {} must be finite and > 0", p.histogram_range));
    if (p.field_cells < 1 || p.field_cells > 4096)
        throw InputError(fmt::format("--field-cells {} is outside [1, 4096]", p.field_cells));
    if (p.realizations < 1) throw InputError(fmt::format("--realizations {} must be >= 1", p.realizations));
    if (p.first_realization < 0)
        throw InputError(fmt::format("--first-realization {} must be >= 0", p.first_realization));
}

std::vector<double> sample_grid(const SphereParameters& p) {
    std::vector<double> times{0.0};
    const double first = -2.0, last = std::log10(p.t_max);
    for (int step = 0;; ++step) {
        const double exponent = first + static_cast<double>(step) / p.samples_per_decade;
        if (exponent > last + 1e-12) break;
        times.push_back(std::pow(10.0, exponent));
    }
    times.push_back(p.t_max);
    for (const auto* extra : {&p.sample_times, &p.snapshot_times, &p.histogram_times})
        times.insert(times.end(), extra->begin(), extra->end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    while (!times.empty() && times.back() > p.t_max) times.pop_back();
    return times;
}

}  // namespace shockgas::spheres
