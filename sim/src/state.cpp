#include "shockgas/state.hpp"

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "shockgas/h5.hpp"
#include "shockgas/parameters.hpp"

namespace shockgas {

namespace {
// SplitMix64 finaliser (Steele, Lea & Flood 2014): decorrelates nearby seeds.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}
}  // namespace

std::uint64_t realization_seed(std::uint64_t seed, std::int64_t realization) {
    return splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(realization));
}

InitialCondition generate_initial_condition(std::int64_t particles, double ring_length, std::uint64_t seed,
                                            std::int64_t realization) {
    InitialCondition initial;
    initial.ring_length = ring_length;
    const auto n = static_cast<std::size_t>(particles);
    initial.position.resize(n);
    initial.velocity.resize(n);
    initial.mass.assign(n, 1.0);
    std::mt19937_64 engine(realization_seed(seed, realization));
    const double spacing = ring_length / static_cast<double>(particles);
    for (std::size_t i = 0; i < n; ++i) {
        initial.position[i] = static_cast<double>(i) * spacing;
        // u in [0, 1) from the top 53 bits; v = 2u - 1 uniform on [-1, 1).
        const double u = static_cast<double>(engine() >> 11) * 0x1.0p-53;
        initial.velocity[i] = 2.0 * u - 1.0;
    }
    return initial;
}

void validate(const InitialCondition& initial) {
    const auto n = initial.position.size();
    if (!(initial.ring_length > 0.0) || !std::isfinite(initial.ring_length))
        throw InputError(fmt::format("init: ring_length must be positive and finite, got {}", initial.ring_length));
    if (n < 2) throw InputError(fmt::format("init: need at least 2 particles, got {}", n));
    if (initial.velocity.size() != n)
        throw InputError(fmt::format("init: velocity has {} values but position has {}", initial.velocity.size(), n));
    if (initial.mass.size() != n)
        throw InputError(fmt::format("init: mass has {} values but position has {}", initial.mass.size(), n));
    for (std::size_t i = 0; i < n; ++i) {
        const double x = initial.position[i];
        if (!std::isfinite(x)) throw InputError(fmt::format("init: position[{}] is not finite", i));
        if (!std::isfinite(initial.velocity[i])) throw InputError(fmt::format("init: velocity[{}] is not finite", i));
        if (!std::isfinite(initial.mass[i]) || initial.mass[i] <= 0.0)
            throw InputError(fmt::format("init: mass[{}] must be positive and finite, got {}", i, initial.mass[i]));
        if (x < 0.0 || x >= initial.ring_length)
            throw InputError(fmt::format("init: position[{}] = {} lies outside [0, ring_length = {})", i, x,
                                         initial.ring_length));
        if (i > 0 && x < initial.position[i - 1])
            throw InputError(fmt::format("init: positions are not sorted: position[{}] = {} < position[{}] = {}", i, x,
                                         i - 1, initial.position[i - 1]));
    }
}

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

double wrap_position(double x, double ring_length) {
    double wrapped = x - ring_length * std::floor(x / ring_length);
    if (wrapped >= ring_length) wrapped -= ring_length;  // floor rounding at the top edge
    if (wrapped < 0.0) wrapped = 0.0;
    return wrapped;
}

}  // namespace shockgas
