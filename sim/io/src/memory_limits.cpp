// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/memory_limits.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace {

// A number from a one-line file ("max" reads as none).
double read_number(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    if (!(in >> word) || word == "max") return -1.0;
    try {
        return std::stod(word);
    } catch (const std::exception&) {
        return -1.0;
    }
}

}  // namespace

double available_memory_bytes(std::string* source) {
    double best = -1.0;
    std::string which;
    const auto consider = [&](double bytes, const std::string& name) {
        if (bytes >= 0.0 && (best < 0.0 || bytes < best)) {
            best = bytes;
            which = name;
        }
    };
    {
        std::ifstream meminfo("/proc/meminfo");
        std::string line;
        while (std::getline(meminfo, line))
            if (line.rfind("MemAvailable:", 0) == 0) {
                std::istringstream fields(line.substr(13));
                double kib = -1.0;
                if (fields >> kib) consider(kib * 1024.0, "MemAvailable");
            }
    }
    // cgroup v2, then v1 (a v1 "no limit" is a huge number, which never wins).
    const double limit_v2 = read_number("/sys/fs/cgroup/memory.max");
    if (limit_v2 >= 0.0)
        consider(limit_v2 - std::max(0.0, read_number("/sys/fs/cgroup/memory.current")), "cgroup memory.max");
    const double limit_v1 = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    if (limit_v1 >= 0.0)
        consider(limit_v1 - std::max(0.0, read_number("/sys/fs/cgroup/memory/memory.usage_in_bytes")),
                 "cgroup memory.limit_in_bytes");
    if (source) *source = which;
    return best;
}

double parse_memory_size(const std::string& text) {
    std::size_t used = 0;
    double value = -1.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    std::string unit = text.substr(used);
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    double scale = 0.0;
    for (const auto& [name, factor] : {std::pair<const char*, double>{"", 1.0}, {"B", 1.0}, {"K", 0x1p10},
                                       {"KB", 0x1p10}, {"KIB", 0x1p10}, {"M", 0x1p20}, {"MB", 0x1p20},
                                       {"MIB", 0x1p20}, {"G", 0x1p30}, {"GB", 0x1p30}, {"GIB", 0x1p30},
                                       {"T", 0x1p40}, {"TB", 0x1p40}, {"TIB", 0x1p40}})
        if (unit == name) scale = factor;
    if (used == 0 || scale == 0.0 || !std::isfinite(value) || value <= 0.0)
        throw InputError(fmt::format("--max-memory '{}' is not a size such as 8G, 500M or 123456 (bytes)", text));
    return value * scale;
}

std::string format_bytes(double bytes) {
    if (bytes >= 0x1p30) return fmt::format("{:.1f} GiB", bytes / 0x1p30);
    if (bytes >= 0x1p20) return fmt::format("{:.0f} MiB", bytes / 0x1p20);
    return fmt::format("{:.0f} KiB", bytes / 0x1p10);
}

}  // namespace shockgas
