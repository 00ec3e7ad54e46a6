// SPDX-License-Identifier: GPL-3.0-or-later
// The event-driven engine for hard disks (d = 2) and spheres (d = 3) in a
// periodic box (docs/spheres.md, "The engine"). Exact to round-off: particles
// move freely between events, and the only events are pair collisions and
// crossings of the cells (side >= 1) that limit which pairs are examined.
//
// - One event per particle in the queue (Marin, Risso & Cordero, J. Comput.
//   Phys. 109, 306 (1993)): the earlier of its next collision and its next cell
//   crossing, in an event calendar (calendar_queue.hpp) keyed by (time,
//   particle), so equal times are taken in particle order and every run is
//   deterministic.
// - Delayed states: a particle's position is kept at its own clock and brought
//   up to date only when it takes part in an event.
// - A collision invalidates the events of other particles predicted with its
//   two particles; each particle counts its collisions, an event records its
//   partner's count, and a stale event, when its time comes, predicts again.
// - Overlap policy: a pair closer than one diameter by round-off that is
//   approaching collides at once; one that is receding is left to separate.
//   So particles never pass through each other, and no pair collides twice at
//   one contact. Events that stop advancing time are caught (see Status).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "shockgas/model/parameters.hpp"

namespace shockgas::spheres {

// Positions in [0, L)^d and velocities, flattened (particle i's coordinates
// are [i d, i d + d)), at one time.
struct SphereState {
    int dimension = 3;
    double box_length = 0.0;
    double time = 0.0;
    std::vector<double> positions;
    std::vector<double> velocities;
    std::int64_t particles() const { return static_cast<std::int64_t>(velocities.size()) / dimension; }
};

struct CollisionCounts {
    std::uint64_t inelastic = 0;   // g_n >= delta: restitution r
    std::uint64_t elastic = 0;     // g_n < delta: restitution 1
    std::uint64_t cell_crossings = 0;
    std::uint64_t stale_events = 0;  // events whose partner had collided since: predicted again
    std::uint64_t collisions() const { return inelastic + elastic; }
};

enum class EngineStatus {
    running,
    // delta = 0 and r < 1: an inelastic collision slower than the collapse
    // speed (inelastic collapse; McNamara & Young 1992). The state is that at it.
    collapsed,
};

// The whole state of an engine, for checkpoints: every particle's position at
// its own clock, velocity, cell and collision count, every prediction, the cell
// lists and the counters. An engine made from it continues exactly as the one
// it was taken from, bit for bit (the calendar is rebuilt from the
// predictions; it pops in (time, particle) order whatever its layout).
struct EngineRecord {
    int dimension = 3;
    double box_length = 0.0;
    double time = 0.0;
    std::vector<double> reals;          // per particle: x (d), v (d), clock, collision time, crossing time
    std::vector<std::int64_t> integers; // per particle: partner, partner's count, crossing axis, step, count,
                                        // cell (d), next, previous; then the cell heads; then the counters
};

class HardSphereEngine {
public:
    // Continues the engine `record` was taken from (save()). Throws InputError
    // if the record is not one (sizes that do not fit).
    HardSphereEngine(const EngineRecord& record, const CollisionModel& collision, double collapse_speed = 1e-12);
    EngineRecord save() const;

    // Throws InputError if two particles of the start overlap by more than
    // round-off (10^-9 of a diameter) or the state does not fit the box.
    HardSphereEngine(const SphereState& start, const CollisionModel& collision, double collapse_speed = 1e-12);
    ~HardSphereEngine();
    HardSphereEngine(HardSphereEngine&&) noexcept;
    HardSphereEngine& operator=(HardSphereEngine&&) noexcept;

    // Runs every event up to time t, then brings every particle to t. Stops
    // early, at the event, when the gas collapses (status()). Throws
    // NumericalFailure when 10^6 + 10 N consecutive events advance time by less
    // than 10^-12 of max(t, 1) where collapse is impossible (delta > 0 or r = 1).
    // With stop: returns false, between two events and with no particle moved
    // (so that a save() then continues exactly), soon after *stop is raised.
    bool advance_to(double t, const std::atomic<bool>* stop = nullptr);
    // Runs events until `collisions` more collisions have happened (for
    // benchmarks and the melting of starts); the particles are left unsynchronized
    // except through state().
    void run_collisions(std::uint64_t collisions);

    double time() const;
    EngineStatus status() const;
    const CollisionCounts& counts() const;
    // The state at time(): positions brought to it, wrapped into [0, L).
    SphereState state() const;
    // Bytes the engine holds: particles, predictions, cells, the queue.
    std::size_t memory_bytes() const;
    // Velocities at time() (they change only at events; no positions are moved).
    std::vector<double> velocities() const;

    struct Core;  // the engine of each dimension, in engine.cpp

private:
    std::unique_ptr<Core> core_;
};

}  // namespace shockgas::spheres
