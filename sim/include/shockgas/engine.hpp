// The engine interface: advance one realization to a time, then report its
// clusters. The event-driven engine and the exact sticky-gas engine both
// implement it, so the ensemble driver, the output and the analysis cannot
// tell which engine made a file.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "shockgas/parameters.hpp"
#include "shockgas/state.hpp"

namespace shockgas {

// Recorded when inelastic collapse stops a run (delta = 0).
struct CollapseReport {
    double time = 0.0;
    std::int64_t left_slot = 0;        // the pair whose collision triggered detection
    std::int64_t cluster_mass = 0;     // particles in the collapsing cluster (see engine docs)
    double relative_speed = 0.0;       // of the triggering collision
    std::string criterion;             // "relative_speed" or "stall"
};

// Lets a long run be watched and stopped: the engine publishes its time and
// collision count every few thousand events and stops when asked.
struct LiveStatus {
    std::atomic<double> time{0.0};
    std::atomic<std::uint64_t> collisions{0};
    const std::atomic<bool>* stop = nullptr;
};

class Engine {
public:
    virtual ~Engine() = default;
    // Advances to time t (t >= current time). Returns false if the run stopped
    // earlier, because of collapse or because LiveStatus::stop was raised.
    virtual bool advance_to(double t) = 0;
    virtual double time() const = 0;
    virtual void clusters(ClusterState& out) const = 0;
    virtual std::uint64_t collisions() const = 0;
    virtual std::int64_t cluster_count() const = 0;
    virtual const std::optional<CollapseReport>& collapse() const = 0;
    virtual std::string name() const = 0;
};

// The engine selected by parameters.engine ("auto" resolved here).
std::unique_ptr<Engine> make_engine(const SimulationParameters& parameters, const InitialCondition& initial,
                                    LiveStatus* live);
std::string resolve_engine_name(const SimulationParameters& parameters);

}  // namespace shockgas
