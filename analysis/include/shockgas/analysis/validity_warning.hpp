// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-sim's warning from the validity map (validity_map.hpp): a run of the
// delta > 0 gas asked to go past the time at which its temperature leaves the
// sticky gas by 1 %, as the map measured it. Advice only: the run is the same
// with or without it.
#pragma once

#include <string>

#include "shockgas/analysis/validity_map.hpp"

namespace shockgas::analysis {

// The warning's text (after "shockgas-sim: warning: "), or "" for none. It is
// given only for 0 < r < 1 and delta > 0, from the map's runs at that r (within
// same_restitution_tolerance) and mechanism that measured T by 1 %: for a
// measured delta (within a relative 1e-9) its t*, for a delta between two
// measured ones t* interpolated in log-log between them, when both departed
// within their runs. Nothing is said where the map does not reach (delta
// outside its deltas, another r or mechanism), where T had not left by the end
// of a run (t* = +inf: the map cannot say when it would), or where T was never
// within 1 % (t* = NaN).
std::string validity_warning(const ValidityMap& map, double restitution, double velocity_threshold,
                             const std::string& subthreshold, double t_max);

// What shockgas-sim prints before a run (after "shockgas-sim: warning: "), or ""
// for nothing. map_file: --validity-map's file when given (given_by_user), else
// default_validity_map's; empty: no lookup. A map the user named that cannot be
// read is refused as any other input (InputError). The default map is advice
// the user did not ask for: when it does not exist nothing is said, and when it
// cannot be read the line says so instead of stopping the run.
std::string validity_warning_for_run(const std::string& map_file, bool given_by_user, double restitution,
                                     double velocity_threshold, const std::string& subthreshold, double t_max);

}  // namespace shockgas::analysis
