// SPDX-License-Identifier: GPL-3.0-or-later
// The exact sticky-gas engine.
//
// THE LINE. For r = 0 every collision merges, so the particles found in one
// cluster at time t have only ever interacted with each other: the cluster
// moves at V = sum m v / M (the merge rule of collision.hpp applied to the
// whole cluster at once) and sits at Y(t) = (sum m x + t sum m v) / M, the
// mass-weighted mean of y_j = x_j + t v_j. Which particles share a cluster is
// given by the generalized variational principle (E, Rykov & Sinai, Commun.
// Math. Phys. 177, 349 (1996); Brenier & Grenier, SIAM J. Numer. Anal. 35,
// 2317 (1998)): the cluster positions are the slopes of the convex minorant
// of F(mu) = integral_0^mu y dmu' (mu the cumulative mass), i.e. the blocks
// of the mass-weighted isotonic regression of (y_j), which pool-adjacent-
// violators (PAV) computes in O(N). Two facts make the construction exact,
// not just a recipe:
//  (a) Pooling lemma. A level set S of the solution is a straight piece of
//      the minorant of F, which equals F at both ends of S and lies below
//      it in between: every prefix of S has mean y >= the piece's slope
//      (S's value) and every suffix mean <= it. So if adjacent
//      blocks A | B, each inside a level set, violate (mean_A >= mean_B),
//      a level-set boundary between them would give mean_A <= value(S_A) <
//      value(S_B) <= mean_B: impossible. Pooling violators in ANY order
//      therefore never pools across a true boundary, and a partition with no
//      violator left is the solution (Best & Chakravarti, Math. Prog. 47,
//      425 (1990)).
//  (b) Semigroup. The sticky dynamics is autonomous: the clusters at an
//      earlier time t0, taken as particles of mass M and velocity V at
//      positions Y(t0), evolve into the state at t > t0. Their y at time t is
//      Y(t0) + (t - t0) V = (sum m x + t sum m v) / M, the block mean of the
//      particle problem. So advance_to(t) starts PAV from the current
//      clusters (clusters never split), costing O(K), K <= N.
//
// THE RING. Unroll the ring into the periodic line: particle j + kN sits at
// x_j + kL with velocity v_j, so y_{j+N} = y_j + L (in any frame). Periodic
// data give the periodic solution, whose level sets are the ring's clusters.
// That this periodic problem is well posed, with every cluster a finite run
// of at most N particles, is where the centre-of-mass frame enters. Let
// Ybar(t) = Xcm + t Vcm and l(mu) = Ybar + L (mu - M/2) / M the uniform
// lattice co-moving with the centre of mass (M the total mass). Then y - l is
// periodic in mu with zero mass-weighted mean over a period, so
// H(mu) = F(mu) - integral_0^mu l is periodic and bounded, and F = R + H with
// R a parabola of curvature L / M. Hence F >= R + min H: the convex minorant
// of F exists, and touches F at mu* = argmin H and its copies mu* + kM, so
// every period holds a cluster boundary and no cluster is longer than N (the
// particles j and j + N are always L apart). In the final state these copies
// are the only boundaries: mu* is the gap that never closes, and the lone
// cluster's first particle is the one after it (the event engine's last merge
// keeps its left member).
// The algorithm needs neither Vcm nor mu* explicitly. It runs PAV along one
// period of the current clusters, from wherever the list starts, then checks
// the pair across the seam (last block, first block one ring length on) and,
// while the last block violates either neighbour, pools and goes on around
// the ring. Every pooled pair was a violator of the periodic problem and none
// is left, so by (a) the blocks are its level sets: clusters straddling the
// seam come out whole, and since no pooling ever crosses a boundary mu* + kM,
// the lone final cluster starts at mu* (the block that absorbs the others
// across the seam is the one beginning there). A drifting centre of mass
// changes nothing: velocities enter every comparison only through the
// separation of two clusters (Galilean invariance).
//
// CONVENTIONS shared with the event engine: a pair that touches exactly at t
// (equal positions, approaching) is already merged; touching clusters with
// equal velocities are not merged (the event engine never schedules them).
// A merged cluster keeps the left member's first particle.
//
// PRECISION. Naive running sums of m y reach ~ N (L + t) ~ 10^15 at N = 10^7,
// t = 10^8, so a block mean from their difference carries ~ 0.1 of absolute
// error, while clusters whose contact is decided at t are often much closer.
// Here (1) no running sum is formed: each block carries coordinates local to
// its first particle (anchor in [0, L), first moment about it, momentum); the
// separation of two neighbours is (anchor_B - anchor_A + wrap L) + (offset_B
// - offset_A), each part of size <= L + t |V|; (2) those parts are kept in
// double-double arithmetic (products exact by fma, sums by two-sum, ~106
// bits), so a pooling decision is wrong only if the clusters are within
// ~10^-30 (L + t) ~ 10^-22 of contact. A plain-double estimate of the
// separation, with a bound on its rounding error, settles every pair that is
// not that close to contact (almost all) before the double-double test runs.
// The only double roundings are the cluster mass (exact for integer masses
// < 2^53, as in the paper), and the reported position and velocity (one
// rounding each). Tested at N = 10^7, t ~ 10^8 on an initial condition that
// focuses groups of particles onto points with contact decided at 2^-30
// (tests/unit/test_exact_engine.cpp).
#include "exact_engine.hpp"
#include "shockgas/model/pav.hpp"

#include <algorithm>
#include <cmath>

namespace shockgas {

namespace {

using Extended = ExactEngine::Extended;

// Rounding-error bound of the plain-double separation estimate, in units of
// u = 2^-53 times its scale (see must_pool; 6 is derived, 16 is used).
constexpr double filter_unit_roundoffs = 16.0;

// Error-free transformations (Knuth TAOCP vol. 2, 4.2.2; Dekker 1971):
// a + b = s + e and a * b = p + e exactly.
Extended two_sum(double a, double b) {
    const double s = a + b;
    const double b_virtual = s - a;
    return {s, (a - (s - b_virtual)) + (b - b_virtual)};
}
Extended fast_two_sum(double a, double b) {  // requires |a| >= |b| or a == 0
    const double s = a + b;
    return {s, b - (s - a)};
}
Extended two_product(double a, double b) {
    const double p = a * b;
    return {p, std::fma(a, b, -p)};
}

// Double-double arithmetic (Hida, Li & Bailey, QD library algorithms; the
// "accurate" sum): relative error ~ 2^-104 per operation.
Extended add(Extended a, Extended b) {
    Extended s = two_sum(a.hi, b.hi);
    const Extended t = two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return fast_two_sum(s.hi, s.lo);
}
Extended add(Extended a, double b) {
    Extended s = two_sum(a.hi, b);
    s.lo += a.lo;
    return fast_two_sum(s.hi, s.lo);
}
Extended negate(Extended a) { return {-a.hi, -a.lo}; }
Extended subtract(Extended a, Extended b) { return add(a, negate(b)); }
Extended multiply(Extended a, double b) {
    Extended p = two_product(a.hi, b);
    p.lo += a.lo * b;
    return fast_two_sum(p.hi, p.lo);
}
Extended divide(Extended a, double b) {
    const double q1 = a.hi / b;
    const Extended back = two_product(q1, b);
    const double remainder = ((a.hi - back.hi) - back.lo) + a.lo;
    return fast_two_sum(q1, remainder / b);
}
Extended extended(double a) { return {a, 0.0}; }
// Sign of a normalized double-double is the sign of hi (hi = 0 implies lo = 0).
bool is_negative(Extended a) { return a.hi < 0.0; }
bool is_zero(Extended a) { return a.hi == 0.0; }
bool less(Extended a, Extended b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }

}  // namespace

ExactEngine::ExactEngine(const InitialCondition& initial, LiveStatus* live)
    : live_(live),
      ring_length_(initial.ring_length),
      frame_velocity_(frame_velocity(initial.velocity, initial.mass)),
      particles_(initial.size()) {
    validate(initial);
    const auto n = static_cast<std::size_t>(particles_);
    block_.resize(n);
    // In the frame (state.hpp): the clusters are the same in any frame
    // (Galilean invariance, the top of this file), and y = x + t v stays of
    // size L + t |v - V| instead of L + t |v|.
    for (std::size_t i = 0; i < n; ++i)
        block_[i] = {initial.mass[i], two_product(initial.mass[i], initial.velocity[i] - frame_velocity_),
                     extended(0.0), initial.position[i], static_cast<std::int64_t>(i)};
}

// Y - anchor = (first moment + t momentum) / M: the cluster's centre of mass
// moves ballistically from its initial value (momentum conservation).
Extended ExactEngine::offset_at(const Block& block, double t) const {
    return divide(add(block.first_moment, multiply(block.momentum, t)), block.mass);
}

// Y_right - Y_left at time t for neighbours in ring order: right lies one ring
// length further on when the walk from left to right passes particle 0, i.e.
// when its first particle does not come after left's (always for a lone
// cluster facing its own copy).
Extended ExactEngine::separation(const Block& left, const Block& right, double t) const {
    Extended anchors = two_sum(right.anchor, -left.anchor);
    if (right.first_particle <= left.first_particle) anchors = add(anchors, ring_length_);
    return add(anchors, subtract(offset_at(right, t), offset_at(left, t)));
}

// Adjacent violators at t: the left cluster's mean y is beyond the right
// one's, or they touch at t while approaching (the event engine has merged a
// pair whose contact time is <= t).
bool ExactEngine::must_pool(const Block& left, const Block& right, double t) const {
    // Filter: the separation in plain double, from the leading parts. Each
    // offset (first moment + t momentum) / M is off by <= 4 u of
    // (|first moment| + t |momentum|) / M (u = 2^-53: three roundings plus the
    // dropped low parts), the anchors and their sum by <= 3 u of their
    // magnitudes: <= 6 u of `scale` in all. 16 u leaves a margin.
    const double wrap = right.first_particle <= left.first_particle ? ring_length_ : 0.0;
    const double right_offset = (right.first_moment.hi + t * right.momentum.hi) / right.mass;
    const double left_offset = (left.first_moment.hi + t * left.momentum.hi) / left.mass;
    const double estimate = ((right.anchor - left.anchor) + wrap) + (right_offset - left_offset);
    const double scale = right.anchor + left.anchor + wrap +
                         (std::abs(right.first_moment.hi) + t * std::abs(right.momentum.hi)) / right.mass +
                         (std::abs(left.first_moment.hi) + t * std::abs(left.momentum.hi)) / left.mass;
    const double rounding_bound = filter_unit_roundoffs * 0x1p-53 * scale;
    if (estimate > rounding_bound) return false;
    if (estimate < -rounding_bound) return true;

    const Extended gap = separation(left, right, t);
    if (is_negative(gap)) return true;
    if (!is_zero(gap)) return false;
    // V_left > V_right  <=>  P_left M_right > P_right M_left (masses > 0).
    return less(multiply(right.momentum, left.mass), multiply(left.momentum, right.mass));
}

// Perfectly inelastic merger of left and right (collision.hpp merge(): mass
// and momentum add); the first moment is carried to left's anchor.
ExactEngine::Block ExactEngine::pooled(const Block& left, const Block& right) const {
    Extended shift = two_sum(right.anchor, -left.anchor);
    if (right.first_particle <= left.first_particle) shift = add(shift, ring_length_);
    Block merged = left;
    merged.mass = left.mass + right.mass;
    merged.momentum = add(left.momentum, right.momentum);
    merged.first_moment = add(add(left.first_moment, right.first_moment), multiply(shift, right.mass));
    return merged;
}

// PAV along the period, in place, with this engine's exact violation test
// (the one stack algorithm, shockgas/model/pav.hpp).
void ExactEngine::pool_along_line(double t) {
    pool_adjacent_violators(
        block_, [this, t](const Block& left, const Block& right) { return must_pool(left, right, t); },
        [this](const Block& left, const Block& right) { return pooled(left, right); });
}

// The seam pair (last block, first block one ring length on), then PAV
// continued around the ring while the grown last block violates either of its
// neighbours (see the top of this file).
void ExactEngine::pool_across_seam(double t) {
    std::size_t head = 0;  // block_[head, end) are live
    while (block_.size() - head >= 2) {
        Block& last = block_.back();
        if (must_pool(block_[block_.size() - 2], last, t)) {
            block_[block_.size() - 2] = pooled(block_[block_.size() - 2], last);
            block_.pop_back();
        } else if (must_pool(last, block_[head], t)) {
            last = pooled(last, block_[head]);
            ++head;
        } else {
            break;
        }
    }
    if (head > 0) block_.erase(block_.begin(), block_.begin() + static_cast<std::ptrdiff_t>(head));
}

bool ExactEngine::advance_to(double t) {
    if (live_ != nullptr && live_->halt_requested()) return false;
    t = std::max(t, now_);
    if (block_.size() > 1) {
        pool_along_line(t);
        pool_across_seam(t);
    }
    now_ = t;
    if (live_ != nullptr) {
        live_->time.store(now_, std::memory_order_relaxed);
        live_->collisions.store(collisions(), std::memory_order_relaxed);
    }
    return true;
}

void ExactEngine::clusters(ClusterState& out) const {
    out.clear();
    out.time = now_;
    out.frame_velocity = frame_velocity_;
    const std::size_t count = block_.size();
    std::size_t start = 0;
    for (std::size_t k = 1; k < count; ++k)
        if (block_[k].first_particle < block_[start].first_particle) start = k;
    out.position.reserve(count);
    out.velocity.reserve(count);
    out.mass.reserve(count);
    out.first_particle.reserve(count);
    const double inverse_ring = 1.0 / ring_length_;
    for (std::size_t k = 0, index = start; k < count; ++k, index = index + 1 == count ? 0 : index + 1) {
        const Block& b = block_[index];
        // Y = anchor + offset, reduced mod L in double-double before the one
        // rounding to double. The period count may be off by one near a
        // multiple of L (inverse_ring rounds); the exact corrections fix it.
        Extended position = add(offset_at(b, now_), b.anchor);
        const double periods = std::floor(position.hi * inverse_ring);
        position = subtract(position, two_product(periods, ring_length_));
        if (is_negative(position)) position = add(position, ring_length_);
        if (!less(position, extended(ring_length_))) position = add(position, -ring_length_);
        // A position within half an ulp below L rounds to L, which is 0
        // (and + 0.0 turns a -0 into +0).
        out.position.push_back(position.hi < ring_length_ ? position.hi + 0.0 : 0.0);
        out.velocity.push_back(divide(b.momentum, b.mass).hi);
        out.mass.push_back(b.mass);
        out.first_particle.push_back(b.first_particle);
    }
    frame_to_lab_positions(out, ring_length_);
}

}  // namespace shockgas
