// SPDX-License-Identifier: GPL-3.0-or-later
// Initial-condition files (--init): one exact start as HDF5 datasets.
#pragma once

#include <string>

#include "shockgas/model/state.hpp"

namespace shockgas {

// Reads --init FILE.h5: datasets position, velocity, optional mass, and the
// root attribute ring_length. Throws InputError with a one-line message for
// any problem (missing dataset, length mismatch, unsorted or out-of-range
// positions, non-finite values, non-positive masses).
InitialCondition read_initial_condition(const std::string& path);
void write_initial_condition(const std::string& path, const InitialCondition& initial);

}  // namespace shockgas
