// SPDX-License-Identifier: GPL-3.0-or-later
// Saving and restoring the per-slot ring records that both event engines keep
// (velocity, gap, clock, mass, next, prev), written once for both. Used by
// ReferenceEventEngine and EventEngine's snapshot()/restore() (checkpoints).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "shockgas/engines/engine.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas::snapshot_io {

template <class Record>
void save_ring(const std::vector<Record>& records, EngineSnapshot& out) {
    auto& velocity = out.reals["velocity"];
    auto& gap = out.reals["gap"];
    auto& clock = out.reals["clock"];
    auto& mass = out.reals["mass"];
    auto& next = out.integers["next"];
    auto& prev = out.integers["prev"];
    for (const Record& r : records) {
        velocity.push_back(r.velocity);
        gap.push_back(r.gap);
        clock.push_back(r.clock);
        mass.push_back(r.mass);
        next.push_back(r.next);
        prev.push_back(r.prev);
    }
}

// Refuses a snapshot written by another engine class, naming both.
inline void expect_kind(const EngineSnapshot& snapshot, const char* kind, const std::string& engine) {
    if (snapshot.kind != kind)
        throw InputError("checkpoint: engine state of kind '" + snapshot.kind + "' given to the " + engine + " engine");
}

// The array `name` of exactly `size` values; InputError naming it otherwise.
template <class Map>
const typename Map::mapped_type& array(const Map& arrays, const std::string& name, std::size_t size,
                                       const EngineSnapshot& snapshot) {
    const auto it = arrays.find(name);
    if (it == arrays.end())
        throw InputError(fmt::format("checkpoint: {} engine state has no '{}'", snapshot.kind, name));
    if (it->second.size() != size)
        throw InputError(fmt::format("checkpoint: {} engine state '{}' has {} values, expected {}", snapshot.kind,
                                     name, it->second.size(), size));
    return it->second;
}

// Overwrites records (already sized for the same initial condition) from the
// snapshot; link indices must point inside the ring.
template <class Record>
void restore_ring(const EngineSnapshot& snapshot, std::vector<Record>& records) {
    const std::size_t n = records.size();
    const auto& velocity = array(snapshot.reals, "velocity", n, snapshot);
    const auto& gap = array(snapshot.reals, "gap", n, snapshot);
    const auto& clock = array(snapshot.reals, "clock", n, snapshot);
    const auto& mass = array(snapshot.reals, "mass", n, snapshot);
    const auto& next = array(snapshot.integers, "next", n, snapshot);
    const auto& prev = array(snapshot.integers, "prev", n, snapshot);
    for (std::size_t s = 0; s < n; ++s) {
        if (next[s] < 0 || prev[s] < 0 || next[s] >= static_cast<std::int64_t>(n) ||
            prev[s] >= static_cast<std::int64_t>(n))
            throw InputError(fmt::format("checkpoint: {} engine state links slot {} outside the ring", snapshot.kind, s));
        Record& r = records[s];
        r.velocity = velocity[s];
        r.gap = gap[s];
        r.clock = clock[s];
        r.mass = mass[s];
        r.next = static_cast<std::int32_t>(next[s]);
        r.prev = static_cast<std::int32_t>(prev[s]);
    }
}

}  // namespace shockgas::snapshot_io
