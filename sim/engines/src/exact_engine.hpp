// SPDX-License-Identifier: GPL-3.0-or-later
// The exact sticky-gas engine (r = 0, ballistic aggregation): the clusters at
// any time follow from the state at an earlier time without an event loop,
// by the generalized variational principle (E, Rykov & Sinai, Commun. Math.
// Phys. 177, 349 (1996); Brenier & Grenier, SIAM J. Numer. Anal. 35, 2317
// (1998)). Clusters at time t are the blocks of the mass-weighted isotonic
// (pool-adjacent-violators) regression of y_i = x_i + t v_i on the ring.
//
// Why this is exact on a ring, and how it stays exact at N = 10^7, t = 10^8,
// is argued at the top of src/exact_engine.cpp and in ARCHITECTURE.md.
// Cost per advance_to(t): O(K) for the K clusters present before the call
// (at most N), memory 56 bytes per particle.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shockgas/engines/engine.hpp"

namespace shockgas {

class ExactEngine final : public Engine {
public:
    explicit ExactEngine(const InitialCondition& initial, LiveStatus* live = nullptr);

    bool advance_to(double t) override;
    double time() const override { return now_; }
    void clusters(ClusterState& out) const override;
    // Every merge in the sticky gas is one binary collision: N - K of them.
    std::uint64_t collisions() const override { return static_cast<std::uint64_t>(particles_) - block_.size(); }
    std::int64_t cluster_count() const override { return static_cast<std::int64_t>(block_.size()); }
    const std::optional<CollapseReport>& collapse() const override { return no_collapse_; }
    std::string name() const override { return "exact"; }

    static constexpr std::size_t bytes_per_particle();

    // Double-double number hi + lo (|lo| <= ulp(hi)/2): ~106 significant bits.
    struct Extended {
        double hi = 0.0;
        double lo = 0.0;
    };

private:
    // One cluster = one pooled block of consecutive particles in ring order.
    // Coordinates are local to the block: anchor is the initial position of
    // its first (leftmost) particle, in [0, L); first_moment is
    // sum_j m_j (x_j - anchor) over its particles with positions unrolled
    // continuously from the anchor (so >= 0 and <= M L). No coordinate of
    // size N t is ever formed.
    struct Block {
        double mass;
        Extended momentum;      // sum_j m_j (v_j - V), V the frame velocity
        Extended first_moment;  // sum_j m_j (x_j - anchor), unrolled
        double anchor;
        std::int64_t first_particle;
    };

    Extended offset_at(const Block& block, double t) const;
    Extended separation(const Block& left, const Block& right, double t) const;
    bool must_pool(const Block& left, const Block& right, double t) const;
    Block pooled(const Block& left, const Block& right) const;
    void pool_along_line(double t);
    void pool_across_seam(double t);

    std::vector<Block> block_;  // in ring order (a rotation of it)
    LiveStatus* live_;
    double ring_length_;
    double frame_velocity_;  // momenta are relative to it (frame_velocity, state.hpp)
    std::int64_t particles_;
    double now_ = 0.0;
    std::optional<CollapseReport> no_collapse_;  // r = 0 never collapses
};

constexpr std::size_t ExactEngine::bytes_per_particle() { return sizeof(Block); }

}  // namespace shockgas
