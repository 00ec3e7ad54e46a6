// SPDX-License-Identifier: GPL-3.0-or-later
// Pool-adjacent-violators (PAV): the one implementation of the stack
// algorithm that turns a sequence of blocks into the blocks of its isotonic
// regression (Ayer et al., Ann. Math. Stat. 26, 641 (1955); Best &
// Chakravarti, Math. Prog. 47, 425 (1990)). In the sticky gas (r = 0) these
// blocks are the clusters at time t: the generalized variational principle
// (E, Rykov & Sinai, Commun. Math. Phys. 177, 349 (1996)) makes a cluster a
// level set of the mass-weighted isotonic regression of y = x + t v.
//
// Two callers: the exact engine (sim/engines/src/exact_engine.cpp), which supplies a
// double-double violation test and runs on the ring, and the open-line solver
// below, used by the far-tail sampler (sim/tail/include/shockgas/tail/tail_sampler.hpp).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace shockgas {

// Stack PAV, in place: blocks[0, top) is the stack of pooled blocks, each not
// violating the one below it. must_pool(left, right) says whether adjacent
// blocks violate; pooled(left, right) merges them. By the pooling lemma (a
// violating pair of blocks, each inside a level set, lies inside one level
// set) the order of pooling does not matter, so the result is the isotonic
// regression's level sets. O(size) calls of must_pool.
template <class Block, class MustPool, class Pool>
void pool_adjacent_violators(std::vector<Block>& blocks, MustPool&& must_pool, Pool&& pooled) {
    std::size_t top = 0;
    for (std::size_t next = 0; next < blocks.size(); ++next) {
        Block incoming = blocks[next];
        while (top > 0 && must_pool(blocks[top - 1], incoming)) {
            incoming = pooled(blocks[top - 1], incoming);
            --top;
        }
        blocks[top++] = incoming;
    }
    blocks.resize(top);
}

// A sticky cluster on an open line: particles [first, first + count) of the
// input, with total mass, first moment sum m x and momentum sum m v.
struct LineCluster {
    std::size_t first = 0;
    std::size_t count = 0;
    double mass = 0.0;
    double first_moment = 0.0;
    double momentum = 0.0;

    double velocity() const { return momentum / mass; }
    // Centre of mass at t: (sum m x + t sum m v) / M (momentum conservation).
    double position(double t) const { return (first_moment + t * momentum) / mass; }
};

// The sticky-gas clusters at time t of unit-mass particles on an OPEN line
// (no ring, no particles beyond the ends), given in the order of their
// positions x (increasing): PAV on y = x + t v with the exact engine's
// conventions (a pair touching at t while approaching is merged). Plain
// double arithmetic: meant for windows of <= 10^5 particles at t <= 10^5,
// where a pooling decision can be wrong only for clusters within ~10^-10 of
// contact (probability zero for continuous velocities). `clusters` is
// overwritten; its capacity is reused, so repeated calls do not allocate.
void sticky_clusters_on_line(std::span<const double> position, std::span<const double> velocity, double t,
                             std::vector<LineCluster>& clusters);

// The cluster holding particle `tagged` (index into the input).
const LineCluster& cluster_holding(const std::vector<LineCluster>& clusters, std::size_t tagged);

}  // namespace shockgas
