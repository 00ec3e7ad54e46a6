// SPDX-License-Identifier: GPL-3.0-or-later
// The validity map of the threshold delta (docs/validity.md): for each run of
// the map (r, delta, sub-threshold mechanism, N), the time t* at which each
// observable leaves the sticky gas it stands in for, the run's measured cost,
// and the fits t* = A delta^(-mu). shockgas-analyze validity makes it from the
// pipeline's runs (fig_validity); the planner (shockgas-plan) and
// shockgas-sim's warning read it. It is data the pipeline makes: no number of
// it is typed into the code.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/io/h5.hpp"

namespace shockgas::analysis {

// When one observable of one run leaves the sticky gas by one criterion.
struct ValidityDeparture {
    std::string observable;  // "temperature", "kurtosis", "cluster_density", "small_gap_fraction",
                             // "structure_function", "fragmentation_rate"
    std::string criterion;   // "3sigma", "1percent" or "5percent"
    // t*: the first sample time from which on the observable stays outside the
    // criterion's band around the sticky gas; +inf when it had not left by the
    // run's t_end; NaN when it was never inside (note says so).
    double departure_time = 0.0;
    double departure_sigma = 0.0;  // jackknife sigma of t* (NaN when not measured)
    std::string note;
};

// One run of the map: its parameters, its measured cost, its departures.
struct ValidityRun {
    std::string name;  // the run's name in the pipeline, e.g. "r0.9_elastic_d-2"
    double restitution = 0.0;
    double velocity_threshold = 0.0;  // delta
    std::string subthreshold;         // "elastic" or "sticky"
    std::int64_t particles = 0;
    std::int64_t realizations = 0;
    double t_end = 0.0;        // the last time compared with the sticky gas
    double cpu_seconds = 0.0;  // the run's CPU time, all realizations
    // The cost model: the ensemble-mean collisions per particle at the run's
    // sample times (t > 0).
    std::vector<double> time;
    std::vector<double> collisions_per_particle;
    std::vector<ValidityDeparture> departures;
};

// t* = A delta^(-mu), fitted over the deltas of one (observable, criterion,
// r, mechanism) whose observable departed within the run.
struct ValidityFit {
    std::string observable, criterion, subthreshold;
    double restitution = 0.0;
    std::int64_t particles = 0;
    double mu = 0.0, mu_sigma = 0.0;
    double log_amplitude = 0.0, log_amplitude_sigma = 0.0;  // ln A
    std::int64_t points = 0;  // deltas in the fit
    std::string follows;      // "delta^-1", "delta^-3", "neither", or "n/a (<why>)"
};

struct ValidityMap {
    std::string version;   // "<fidelity> map, shockgas <git describe>"
    std::string fidelity;  // quick | paper
    std::vector<std::string> observables;  // in display order
    std::vector<ValidityRun> runs;
    std::vector<ValidityFit> fits;
};

// Writes the map into `group` (a results file's /validity_map; the layout is
// docs/cli-and-output.md, "Validity map"). Names are HDF5 group names, so a run
// name or observable holding '/' is a defect of the caller (std::invalid_argument).
void write_validity_map(h5::Group& group, const ValidityMap& map);
// Reads the map from a file that holds /validity_map; throws InputError naming
// the file and the object that is missing or malformed.
ValidityMap read_validity_map(const std::string& path);

// Two restitutions are the same run parameter when they agree within this
// (absolute): the map's r are the parameter files' numbers (0.5, 0.9), read back
// from doubles, and a user types them the same way.
inline constexpr double same_restitution_tolerance = 1e-9;
bool same_restitution(double a, double b);

// The run's departure of `observable` by `criterion`; nullptr when the run did
// not measure that pair.
const ValidityDeparture* find_departure(const ValidityRun& run, const std::string& observable,
                                        const std::string& criterion);

// y(x) between two measured points, linear in (ln x, ln y): t* against delta and
// collisions per particle against t are power laws locally. Linear in (x, y)
// where a y is not positive (no collision yet), where logarithms do not exist.
double log_log_interpolate(double x0, double y0, double x1, double y1, double x);

// The run's mean collisions per particle at t, interpolated in log-log between
// its sample times; NaN outside [time.front(), time.back()]: the map's cost is
// measured, never extrapolated.
double collisions_per_particle_at(const ValidityRun& run, double t);

// The map a program reads when none is given: the environment variable
// SHOCKGAS_VALIDITY_MAP when it is set (an empty value: none, which is how the
// test suite keeps every run independent of a map the figure pipeline may have
// made), else the first of build_tree_maps that exists (the build tree's paper
// map, then its quick one), else "".
std::string default_validity_map(const std::vector<std::string>& build_tree_maps);

}  // namespace shockgas::analysis
