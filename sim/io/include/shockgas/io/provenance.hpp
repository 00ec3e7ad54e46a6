// SPDX-License-Identifier: GPL-3.0-or-later
// Provenance: what made a file. Written as root attributes of every HDF5 file
// shockgas produces, and copied forward (prefixed "input_") into analysis
// outputs, so any figure can be traced to the run and code that made it.
#pragma once

#include <string>

namespace shockgas {

namespace h5 {
class Group;
}

struct BuildInfo {
    std::string version;         // git describe --always --dirty, taken at build time
    std::string compiler;        // id and version
    std::string compiler_flags;  // CMAKE_CXX_FLAGS plus the build type's flags
    std::string build_type;
    std::string hdf5_version;
    // SHA-256 over what decides the simulator's numbers (sim/model, sim/io,
    // sim/engines, sim/run) and how they are built (SHOCKGAS_SIM_COMPILER_INFO in the
    // top-level CMakeLists.txt; cmake/SourceHash.cmake).
    std::string simulator_sha256;
};

const BuildInfo& build_info();

// Whether two files (or a file and this build) were made by the same simulator
// code: the same simulator_sha256, or, for files of builds that did not record
// it (empty), the same version. The same code continues a
// checkpoint bit for bit, so a commit that changes only docs, analysis or tests
// (or a build marked -dirty by an edit there) does not throw away a run in
// progress; and two -dirty builds of one commit with different edits to the
// simulator are told apart, which their versions could not do.
bool same_simulator(const std::string& version, const std::string& simulator_sha256, const std::string& other_version,
                    const std::string& other_simulator_sha256);
// ... and this build.
bool made_by_this_simulator(const std::string& version, const std::string& simulator_sha256);
// How messages name a build: "shockgas <version> (simulator <first 12 hex digits>)", or
// "shockgas <version>" for a file without the hash. The version alone can be the same for
// two simulators (two -dirty builds, or one with an editor's file beside the sources).
std::string build_description(const std::string& version, const std::string& simulator_sha256);
std::string this_build_description();

// Schema version of the simulation output; bump on any incompatible change.
// 2: checksummed (HDF5 1.10 format, Fletcher32 on every non-empty dataset).
// 3: text attributes variable-length UTF-8; numbered groups
// (/snapshots, /histograms, /collapse/states) zero-padded; readers take 1-3.
// 4: the time series starts with t = 0 (the initial state); the
// groups and datasets are those of 3. Readers take 1-4.
constexpr long long output_schema_version = 4;

// Writes program, version, simulator_sha256, compiler, flags, build type, HDF5
// version, host and the current UTC date as root attributes.
void write_provenance(h5::Group& root, const std::string& program);

std::string utc_timestamp();
std::string host_name();

// The text outputs' counterpart of write_provenance (a gnuplot table, a
// profile): '#' comment lines, which gnuplot and numpy.loadtxt skip.
// "# <program> <version>, from <source>" and, when dated, "# date <UTC>" on a
// line of its own: the one line in which a rerun of the same code differs,
// which tools/reproduce-check leaves out of its comparison.
std::string provenance_comment(const std::string& program, const std::string& source, bool dated);

}  // namespace shockgas
