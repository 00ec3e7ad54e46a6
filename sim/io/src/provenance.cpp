// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/provenance.hpp"

#include <ctime>

#include <unistd.h>

#include "shockgas/io/h5.hpp"

namespace shockgas {

std::string utc_timestamp() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

std::string host_name() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

bool same_simulator(const std::string& version, const std::string& simulator_sha256, const std::string& other_version,
                    const std::string& other_simulator_sha256) {
    if (!simulator_sha256.empty() && !other_simulator_sha256.empty()) return simulator_sha256 == other_simulator_sha256;
    return version == other_version;
}

bool made_by_this_simulator(const std::string& version, const std::string& simulator_sha256) {
    return same_simulator(version, simulator_sha256, build_info().version, build_info().simulator_sha256);
}

std::string build_description(const std::string& version, const std::string& simulator_sha256) {
    if (simulator_sha256.empty()) return "shockgas " + version;
    return "shockgas " + version + " (simulator " + simulator_sha256.substr(0, 12) + ")";
}

std::string this_build_description() {
    return build_description(build_info().version, build_info().simulator_sha256);
}

std::string provenance_comment(const std::string& program, const std::string& source, bool dated) {
    std::string text = "# " + program + " " + build_info().version;
    if (!source.empty()) text += ", from " + source;
    text += '\n';
    if (dated) text += "# date " + utc_timestamp() + '\n';
    return text;
}

void write_provenance(h5::Group& root, const std::string& program) {
    const BuildInfo& info = build_info();
    root.set_attribute("program", program);
    root.set_attribute("version", info.version);
    root.set_attribute("simulator_sha256", info.simulator_sha256);
    root.set_attribute("compiler", info.compiler);
    root.set_attribute("compiler_flags", info.compiler_flags);
    root.set_attribute("build_type", info.build_type);
    root.set_attribute("hdf5_version", info.hdf5_version);
    root.set_attribute("host", host_name());
    root.set_attribute("date", utc_timestamp());
    root.set_attribute("schema_version", static_cast<std::int64_t>(output_schema_version));
}

}  // namespace shockgas
