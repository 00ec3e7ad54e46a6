// SPDX-License-Identifier: GPL-3.0-or-later
// A validity map made by hand (tests only), with numbers chosen so that every
// answer of the planner and of shockgas-sim's warning can be worked out on paper:
// the unit tests (tests/unit/test_validity_map.cpp) and the map file of the cli
// tests (tests/cli/make_validity_map.cpp) both use it.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "shockgas/analysis/validity_map.hpp"
#include "shockgas/io/h5.hpp"

namespace shockgas::testing {

inline constexpr double never_left = std::numeric_limits<double>::infinity();  // t* = +inf: not by t_end
inline constexpr double never_within = std::numeric_limits<double>::quiet_NaN();  // t* = NaN

// Collisions per particle of each run: cost_factor * sqrt(t) at t = 1, 10, ...,
// 10^4. A power law, so log-log interpolation gives cost_factor * sqrt(t)
// exactly between samples, where linear interpolation would not (at t = 30 it
// would be 15% low).
inline analysis::ValidityRun fixture_run(std::string name, double restitution, double delta, std::string mechanism,
                                         std::int64_t particles, double cost_factor,
                                         std::vector<analysis::ValidityDeparture> departures) {
    analysis::ValidityRun run;
    run.name = std::move(name);
    run.restitution = restitution;
    run.velocity_threshold = delta;
    run.subthreshold = std::move(mechanism);
    run.particles = particles;
    run.realizations = 4;
    run.t_end = 1e4;
    run.cpu_seconds = 8.0;
    for (double t = 1.0; t <= 1e4; t *= 10.0) {
        run.time.push_back(t);
        run.collisions_per_particle.push_back(cost_factor * std::sqrt(t));
    }
    run.departures = std::move(departures);
    return run;
}

// r = 0.9 (N = 1000): delta = 0.1 elastic (cost 1), 0.01 elastic (cost 2) and
// sticky (cost 3), 0.001 sticky (cost 4); the cheaper, the sooner T leaves
// the sticky gas. r = 0.5 (N = 2000): delta = 0.1 and 0.01 elastic, the
// smaller one's T not leaving by 1 % within its run.
inline analysis::ValidityMap fixture_map() {
    using analysis::ValidityDeparture;
    analysis::ValidityMap map;
    map.version = "test map, shockgas fixture";
    map.fidelity = "quick";
    map.observables = {"temperature", "kurtosis"};
    map.runs.push_back(fixture_run("r0.9_elastic_d-1", 0.9, 0.1, "elastic", 1000, 1.0,
                                   {{"temperature", "3sigma", 50.0, 5.0, ""},
                                    {"temperature", "1percent", 20.0, 2.0, ""},
                                    {"temperature", "5percent", 200.0, 20.0, ""}}));
    map.runs.push_back(fixture_run("r0.9_elastic_d-2", 0.9, 0.01, "elastic", 1000, 2.0,
                                   {{"temperature", "3sigma", 500.0, 50.0, ""},
                                    {"temperature", "1percent", 300.0, 30.0, ""},
                                    {"temperature", "5percent", 3000.0, 300.0, ""},
                                    {"kurtosis", "3sigma", never_within, never_within, "never within 3 sigma"}}));
    map.runs.push_back(fixture_run("r0.9_sticky_d-2", 0.9, 0.01, "sticky", 1000, 3.0,
                                   {{"temperature", "3sigma", 400.0, 40.0, ""},
                                    {"temperature", "1percent", 100.0, 10.0, ""},
                                    {"temperature", "5percent", never_left, never_within, "had not left by t_end"},
                                    {"kurtosis", "3sigma", 2000.0, 200.0, ""}}));
    map.runs.push_back(fixture_run("r0.9_sticky_d-3", 0.9, 0.001, "sticky", 1000, 4.0,
                                   {{"temperature", "3sigma", 5000.0, 500.0, ""},
                                    {"temperature", "1percent", 3000.0, 300.0, ""},
                                    {"temperature", "5percent", never_left, never_within, "had not left by t_end"}}));
    map.runs.push_back(fixture_run("r0.5_elastic_d-1", 0.5, 0.1, "elastic", 2000, 1.0,
                                   {{"temperature", "3sigma", 60.0, 6.0, ""},
                                    {"temperature", "1percent", 40.0, 4.0, ""}}));
    map.runs.push_back(fixture_run("r0.5_elastic_d-2", 0.5, 0.01, "elastic", 2000, 2.0,
                                   {{"temperature", "3sigma", never_left, never_within, "had not left by t_end"},
                                    {"temperature", "1percent", never_left, never_within, "had not left by t_end"}}));
    analysis::ValidityFit fit;
    fit.observable = "temperature";
    fit.criterion = "1percent";
    fit.subthreshold = "elastic";
    fit.restitution = 0.9;
    fit.particles = 1000;
    fit.mu = 1.176;
    fit.mu_sigma = 0.05;
    fit.log_amplitude = 0.3;
    fit.log_amplitude_sigma = std::numeric_limits<double>::quiet_NaN();
    fit.points = 2;
    fit.follows = "delta^-1";
    map.fits.push_back(fit);
    fit.subthreshold = "sticky";
    fit.mu = std::numeric_limits<double>::quiet_NaN();
    fit.mu_sigma = std::numeric_limits<double>::quiet_NaN();
    fit.points = 1;
    fit.follows = "n/a (one delta departed)";
    map.fits.push_back(fit);
    return map;
}

// The map as a results file holds it: in the group /validity_map.
inline void write_map_file(const std::string& path, const analysis::ValidityMap& map) {
    h5::write_atomically(path, [&](h5::Group& root) {
        auto group = root.create_group("validity_map");
        analysis::write_validity_map(group, map);
    });
}

}  // namespace shockgas::testing
