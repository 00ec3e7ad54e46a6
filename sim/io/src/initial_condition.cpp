// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/initial_condition.hpp"

#include <vector>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

InitialCondition read_initial_condition(const std::string& path) {
    InitialCondition initial;
    try {
        const auto file = h5::File::open_read(path);
        const auto root = file.root();
        if (!root.has_attribute("ring_length"))
            throw InputError(fmt::format("init '{}': missing root attribute ring_length", path));
        initial.ring_length = root.attribute_double("ring_length");
        for (const char* name : {"position", "velocity"})
            if (!root.has(name)) throw InputError(fmt::format("init '{}': missing dataset '{}'", path, name));
        std::vector<hsize_t> dims;
        initial.position = root.read_doubles("position", &dims);
        if (dims.size() != 1) throw InputError(fmt::format("init '{}': position must be one-dimensional", path));
        initial.velocity = root.read_doubles("velocity");
        initial.mass = root.has("mass") ? root.read_doubles("mass") : std::vector<double>(initial.position.size(), 1.0);
    } catch (const h5::Error& error) {
        throw InputError(fmt::format("init '{}': {}", path, error.what()));
    }
    try {
        validate(initial);
    } catch (const InputError& error) {
        throw InputError(fmt::format("{} (file '{}')", error.what(), path));
    }
    return initial;
}

void write_initial_condition(const std::string& path, const InitialCondition& initial) {
    h5::AtomicFile file(path);
    auto root = file.root();
    root.set_attribute("ring_length", initial.ring_length);
    root.write("position", initial.position);
    root.write("velocity", initial.velocity);
    root.write("mass", initial.mass);
    file.commit();
}

}  // namespace shockgas
