// SPDX-License-Identifier: GPL-3.0-or-later
// An independent pass-through engine, for tests only: the same physics as
// PassThroughEngine (world lines; a crossing closing at >= delta bends both
// lines by the one collision rule, a slower one passes), but with the elastic
// crossings neither processed nor sorted, and the inelastic ones found by
// another route. It checks the engine's exact collision count at sizes far
// beyond the reference event loop's (docs/measurements.md, "Velocity classes
// built: the count solved, the search not").
//
// Counting without sorting. Within a window (T0, T1] the ring is cut at gaps
// no line can cross (wider than the whole spread times the window), and in a
// block between two cuts no pair can meet twice. Order the pair (i, j) by
// (velocity, id); let A_ij(t) = 1 if the faster of the two is behind the
// slower at t (the pair is closing), 0 otherwise. While the velocity order of
// the pair holds, its relative motion keeps one sign, so it crosses at most
// once, and a crossing takes A from 1 to 0. A bend of one of the two that
// reverses their velocity order changes A without a crossing. Hence, summed
// over the block's pairs (Eq. O1),
//     crossings(T0, T1] = Inv(T0) - Inv(T1) + sum over bends of sum over the
//                         lines j the bent line's velocity passes of
//                         (A_after - A_before),
// where Inv(t) = sum_ij A_ij(t) is the number of inversions of the velocity
// sequence in position order (a Fenwick tree, O(m log m)), and the bent line's
// velocity passes exactly the lines between its old and new place in the
// block's velocity order (kept sorted, so the sum costs one step per line
// passed). Nothing else about the elastic crossings is ever computed.
//
// Finding the inelastic crossings. Each block keeps its lines in velocity
// classes (width max(delta, spread / 16)), each class sorted by position at
// the class's reference time; a line that bends moves to its new class's
// unsorted list, and a class is re-sorted when that list grows. Within a class
// every line is within the class width of every other, so the order at t
// differs from the stored one only within a band of (v_max - v_min)(t - t_ref)
// of positions. Each line keeps its earliest inelastic meeting (both
// directions, every class), found by a binary search per class, a scan of the
// band and a scan onwards while a meeting could still come earlier. Meetings
// run from one heap in (time, behind, ahead) order; one whose other line bent
// since is looked for again by its owner from its time, as the pass-through
// engine does.
//
// Particles: the physical ring is the lines sorted by position; particle n is
// the line at extended rank n + c + W, where W is the lines' total winding
// (the sum of floor(X / L) of their unwrapped positions X) and c is fixed at
// the start (clusters()).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>

#include "shockgas/model/collision.hpp"
#include "shockgas/engines/engine.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::testing {

class InversionOracle final : public Engine {
public:
    // A window lasts this fraction of the current time (at least of 1), or
    // less where the ring would have no cut.
    static constexpr double window_fraction = 0.02;
    // Velocity classes per block, at most.
    static constexpr double most_classes = 16.0;
    // A class's unsorted list is merged in beyond this many lines.
    static constexpr std::size_t most_unsorted = 12;

    InversionOracle(const InitialCondition& initial, const CollisionModel& model)
        : model_(model), ring_(initial.ring_length) {
        start(initial.position, initial.velocity, 0.0);
    }
    InversionOracle(const MidRunState& state, const CollisionModel& model) : model_(model), ring_(state.ring_length) {
        start(state.position, state.velocity, state.time);
        collisions_ = state.collisions;
        inelastic_ = state.inelastic_collisions;
    }

    bool advance_to(double t) override {
        if (!started_) {
            started_ = true;
            run_window(now_);  // lines that start at one point and close meet at the start time
        }
        while (now_ < t) run_window(std::min(t, now_ + window_fraction * std::max(now_, 1.0)));
        return true;
    }
    double time() const override { return now_; }
    std::uint64_t collisions() const override { return collisions_; }
    std::uint64_t inelastic_collisions() const { return inelastic_; }
    std::int64_t cluster_count() const override { return static_cast<std::int64_t>(x_.size()); }
    const std::optional<CollapseReport>& collapse() const override { return no_collapse_; }
    std::string name() const override { return "inversion-oracle"; }

    // Particle n (ring order from particle 0): wrapped position and velocity.
    void clusters(ClusterState& out) const override {
        const auto n = static_cast<std::int64_t>(x_.size());
        std::vector<std::pair<double, std::int32_t>> wrapped;
        const std::int64_t winding = wrapped_order(wrapped);
        out.clear();
        out.time = now_;
        for (std::int64_t k = 0; k < n; ++k) {
            const std::int64_t rank = floor_mod(k + offset_ + winding, n);
            const auto& [y, j] = wrapped[static_cast<std::size_t>(rank)];
            out.position.push_back(y);
            out.velocity.push_back(v_[static_cast<std::size_t>(j)]);
            out.mass.push_back(1.0);
            out.first_particle.push_back(k);
        }
    }

private:
    static constexpr double never = std::numeric_limits<double>::infinity();
    static std::int64_t floor_mod(std::int64_t a, std::int64_t n) { return ((a % n) + n) % n; }

    // Sorts (position, line) pairs by position; a level pair with the faster
    // ahead, as a crossing at exactly that time counts as done.
    void sort_crossed_ahead(std::vector<std::pair<double, std::int32_t>>& keys) const {
        std::sort(keys.begin(), keys.end(), [this](const auto& a, const auto& b) {
            if (a.first != b.first) return a.first < b.first;
            const double va = v_[static_cast<std::size_t>(a.second)];
            const double vb = v_[static_cast<std::size_t>(b.second)];
            return va != vb ? va < vb : a.second < b.second;
        });
    }

    // The lines by wrapped position at now_ (sort_crossed_ahead), and their
    // total winding W: winding_ plus the turns in the stored positions.
    std::int64_t wrapped_order(std::vector<std::pair<double, std::int32_t>>& wrapped) const {
        const auto n = static_cast<std::int64_t>(x_.size());
        wrapped.resize(static_cast<std::size_t>(n));
        std::int64_t winding = winding_;
        for (std::int64_t j = 0; j < n; ++j) {
            const double X = position(j, now_);
            const double turns = std::floor(X / ring_);
            winding += static_cast<std::int64_t>(turns);
            wrapped[static_cast<std::size_t>(j)] = {X - turns * ring_, static_cast<std::int32_t>(j)};
        }
        sort_crossed_ahead(wrapped);
        return winding;
    }

    double position(std::int64_t j, double t) const {
        const auto s = static_cast<std::size_t>(j);
        return x_[s] + v_[s] * (t - clock_[s]);
    }

    void start(const std::vector<double>& position, const std::vector<double>& velocity, double time) {
        const std::size_t n = position.size();
        if (n < 2 || velocity.size() != n) throw std::invalid_argument("InversionOracle: at least two lines");
        x_ = position;
        v_ = velocity;
        clock_.assign(n, time);
        now_ = time;
        order_.resize(n);
        for (std::size_t k = 0; k < n; ++k) order_[k] = static_cast<std::int32_t>(k);
        // offset_: particle 0 (line 0) at extended rank 0 + offset_ + W now.
        std::vector<std::pair<double, std::int32_t>> wrapped;
        const std::int64_t winding = wrapped_order(wrapped);
        std::int64_t rank0 = 0;
        while (wrapped[static_cast<std::size_t>(rank0)].second != 0) ++rank0;
        offset_ = rank0 + static_cast<std::int64_t>(n) * static_cast<std::int64_t>(std::floor(x_[0] / ring_)) - winding;
    }

    // --- windows ---

    void run_window(double end) {
        const double begin = now_;
        const auto n = static_cast<std::int64_t>(order_.size());
        // Every line's position at `begin` into [0, L) (its turns go to
        // winding_), and the ring order from the seam.
        key_.resize(static_cast<std::size_t>(n));
        for (std::int64_t k = 0; k < n; ++k) {
            const auto j = static_cast<std::size_t>(order_[static_cast<std::size_t>(k)]);
            double X = position(static_cast<std::int64_t>(j), begin);
            const double turns = std::floor(X / ring_);
            if (turns != 0.0) {
                x_[j] -= turns * ring_;
                winding_ += static_cast<std::int64_t>(turns);
                X = position(static_cast<std::int64_t>(j), begin);
            }
            key_[static_cast<std::size_t>(k)] = {X, order_[static_cast<std::size_t>(k)]};
        }
        // Stable by position alone: a level pair keeps the order it has, which
        // is the particles' at the start and the last window's end sort after.
        std::stable_sort(key_.begin(), key_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (std::int64_t k = 0; k < n; ++k) order_[static_cast<std::size_t>(k)] = key_[static_cast<std::size_t>(k)].second;
        const auto [lo_v, hi_v] = std::minmax_element(v_.begin(), v_.end());
        const double spread = *hi_v - *lo_v;
        // Cuts: gaps wider than the spread's travel in the window.
        const auto gap = [&](std::int64_t k) {
            const double next = k + 1 < n ? key_[static_cast<std::size_t>(k + 1)].first : key_[0].first + ring_;
            return next - key_[static_cast<std::size_t>(k)].first;
        };
        double widest = -never;
        for (std::int64_t k = 0; k < n; ++k) widest = std::max(widest, gap(k));
        if (spread > 0.0 && spread * (end - begin) * (1.0 + 1e-9) + 1e-9 >= widest) end = begin + 0.5 * widest / spread;
        const double travel = spread * (end - begin) * (1.0 + 1e-9) + 1e-9;
        cuts_.clear();
        for (std::int64_t k = 0; k < n; ++k)
            if (gap(k) > travel) cuts_.push_back(k);
        for (std::size_t c = 0; c < cuts_.size(); ++c) {
            const std::int64_t lo = cuts_[c] + 1;
            const std::int64_t hi = c + 1 < cuts_.size() ? cuts_[c + 1] : cuts_[0] + n;
            run_block(lo, hi, begin, end);
        }
        now_ = end;
    }

    // --- one block (cyclic indices lo..hi of the order, possibly past n) ---

    struct Local {
        double x, v, clock;  // on the block's axis (lines past the seam shifted by L)
        std::int32_t id;
        std::int32_t turn;
        std::uint32_t version;
        std::int32_t last_partner;
        std::int32_t cls, slot;  // slot >= 0: index in the class's sorted list; < 0: -(unsorted index) - 1
        std::int32_t vrank;      // place in the block's velocity order
    };
    struct Entry {
        double key;
        std::int32_t i;  // -1: left the class
    };
    struct Class {
        double reference = 0.0;
        double v_min = never, v_max = -never;
        std::vector<Entry> sorted;
        std::vector<std::int32_t> unsorted;
        std::size_t gone = 0;
    };
    struct Meeting {
        double time;
        std::int32_t behind, ahead;
        std::uint32_t behind_version, ahead_version;
        std::int32_t owner;
        bool operator>(const Meeting& o) const {
            if (time != o.time) return time > o.time;
            if (behind != o.behind) return behind > o.behind;
            return ahead > o.ahead;
        }
    };

    double local_position(std::int32_t i, double t) const {
        const Local& l = loc_[static_cast<std::size_t>(i)];
        return l.x + l.v * (t - l.clock);
    }
    bool slower(std::int32_t i, std::int32_t j) const {  // the (velocity, id) order
        const Local& a = loc_[static_cast<std::size_t>(i)];
        const Local& b = loc_[static_cast<std::size_t>(j)];
        return a.v < b.v || (a.v == b.v && a.id < b.id);
    }
    int class_of(double v) const {
        return std::clamp(static_cast<int>(std::floor((v - block_v_min_) / class_width_)), 0,
                          static_cast<int>(classes_.size()) - 1);
    }

    // Inversions of a rank sequence (pairs in order whose ranks decrease).
    std::int64_t inversions(const std::vector<std::int32_t>& rank) {
        const std::size_t m = rank.size();
        fenwick_.assign(m + 1, 0);
        std::int64_t count = 0;
        for (std::size_t k = 0; k < m; ++k) {
            std::int64_t not_above = 0;
            for (auto i = static_cast<std::int64_t>(rank[k]) + 1; i > 0; i -= i & -i)
                not_above += fenwick_[static_cast<std::size_t>(i)];
            count += static_cast<std::int64_t>(k) - not_above;
            for (auto i = static_cast<std::size_t>(rank[k]) + 1; i <= m; i += i & (~i + 1)) ++fenwick_[i];
        }
        return count;
    }

    void run_block(std::int64_t lo, std::int64_t hi, double begin, double end) {
        const auto n = static_cast<std::int64_t>(order_.size());
        const auto m = static_cast<std::int32_t>(hi - lo + 1);
        if (m < 2) return;
        end_ = end;
        loc_.resize(static_cast<std::size_t>(m));
        block_v_min_ = never;
        double block_v_max = -never;
        for (std::int32_t i = 0; i < m; ++i) {
            const std::int64_t k = lo + i;
            const auto id = order_[static_cast<std::size_t>(k % n)];
            const std::int32_t turn = k >= n ? 1 : 0;
            const auto s = static_cast<std::size_t>(id);
            loc_[static_cast<std::size_t>(i)] = {x_[s] + turn * ring_, v_[s], clock_[s], id, turn, 0, -1, 0, 0, 0};
            block_v_min_ = std::min(block_v_min_, v_[s]);
            block_v_max = std::max(block_v_max, v_[s]);
        }
        by_velocity_.resize(static_cast<std::size_t>(m));
        for (std::int32_t i = 0; i < m; ++i) by_velocity_[static_cast<std::size_t>(i)] = i;
        std::sort(by_velocity_.begin(), by_velocity_.end(), [this](std::int32_t a, std::int32_t b) { return slower(a, b); });
        for (std::int32_t r = 0; r < m; ++r) loc_[static_cast<std::size_t>(by_velocity_[static_cast<std::size_t>(r)])].vrank = r;
        rank_.resize(static_cast<std::size_t>(m));
        for (std::int32_t i = 0; i < m; ++i) rank_[static_cast<std::size_t>(i)] = loc_[static_cast<std::size_t>(i)].vrank;
        const std::int64_t inversions_begin = inversions(rank_);  // the block is in position order at begin
        flip_sum_ = 0;
        if (classify(model_, block_v_max - block_v_min_) == CollisionKind::inelastic) {
            class_width_ = std::max(model_.velocity_threshold, (block_v_max - block_v_min_) / most_classes);
            classes_.assign(static_cast<std::size_t>(std::floor((block_v_max - block_v_min_) / class_width_)) + 1,
                            Class{});
            for (std::int32_t i = 0; i < m; ++i) {
                Local& l = loc_[static_cast<std::size_t>(i)];
                l.cls = class_of(l.v);
                Class& c = classes_[static_cast<std::size_t>(l.cls)];
                c.reference = begin;
                l.slot = static_cast<std::int32_t>(c.sorted.size());
                c.sorted.push_back({local_position(i, begin), i});
                c.v_min = std::min(c.v_min, l.v);
                c.v_max = std::max(c.v_max, l.v);
            }
            for (std::int32_t i = 0; i < m; ++i) look(i, begin);
            run_meetings();
        }
        // The order at the window's end, and Eq. O1.
        key_.resize(static_cast<std::size_t>(m));
        for (std::int32_t i = 0; i < m; ++i) key_[static_cast<std::size_t>(i)] = {local_position(i, end), i};
        std::sort(key_.begin(), key_.end(), [this](const auto& a, const auto& b) {
            if (a.first != b.first) return a.first < b.first;
            return slower(a.second, b.second);
        });
        for (std::int32_t k = 0; k < m; ++k)
            rank_[static_cast<std::size_t>(k)] = loc_[static_cast<std::size_t>(key_[static_cast<std::size_t>(k)].second)].vrank;
        const std::int64_t crossings = inversions_begin - inversions(rank_) + flip_sum_;
        if (crossings < 0) throw std::logic_error("InversionOracle: a negative crossing count");
        collisions_ += static_cast<std::uint64_t>(crossings);
        for (std::int32_t k = 0; k < m; ++k) {
            const Local& l = loc_[static_cast<std::size_t>(key_[static_cast<std::size_t>(k)].second)];
            order_[static_cast<std::size_t>((lo + k) % n)] = l.id;
            if (l.version != 0) {
                const auto s = static_cast<std::size_t>(l.id);
                x_[s] = l.x - l.turn * ring_;
                v_[s] = l.v;
                clock_[s] = l.clock;
            }
        }
    }

    // Line i's earliest inelastic meeting after t (by the window's end), onto the heap.
    void look(std::int32_t i, double t) {
        const double xa = local_position(i, t);
        const double va = loc_[static_cast<std::size_t>(i)].v;
        const double delta = model_.velocity_threshold;
        double best = end_;  // a meeting at the window's end itself runs in it: the state at t includes it
        std::int32_t behind = -1, ahead = -1;
        const auto keep = [&](double time, std::int32_t b, std::int32_t a) {
            if (time < best || (time == best && (behind < 0 || b < behind || (b == behind && a < ahead)))) {
                best = time;
                behind = b;
                ahead = a;
            }
        };
        // j ahead of i (catching it: j slower by delta) or behind (j faster by delta).
        const auto meet = [&](std::int32_t j) {
            const Local& o = loc_[static_cast<std::size_t>(j)];
            const bool partners = loc_[static_cast<std::size_t>(i)].last_partner == j || o.last_partner == i;
            if (classify(model_, va - o.v) == CollisionKind::inelastic) {
                const double gap = local_position(j, t) - xa;
                if (gap > 0.0 || (gap == 0.0 && !partners)) keep(t + gap / (va - o.v), i, j);
            } else if (classify(model_, o.v - va) == CollisionKind::inelastic) {
                const double gap = xa - local_position(j, t);
                if (gap > 0.0 || (gap == 0.0 && !partners)) keep(t + gap / (o.v - va), j, i);
            }
        };
        const double slack = 1e-12 * (std::abs(xa) + 1.0);
        for (Class& c : classes_) {
            if (c.v_max < c.v_min) continue;  // empty
            const bool forward = c.v_min <= va - delta;
            const bool backward = c.v_max >= va + delta;
            if (!forward && !backward) continue;
            const double dt = t - c.reference;
            const auto first_not_below = [&](double key) {
                return std::lower_bound(c.sorted.begin(), c.sorted.end(), key,
                                        [](const Entry& e, double k) { return e.key < k; });
            };
            if (forward) {  // from the first line not certainly behind i, while a meeting could beat best
                for (auto e = first_not_below(xa - c.v_max * dt - slack); e != c.sorted.end(); ++e) {
                    if (e->key + c.v_min * dt - xa > (best - t) * (va - c.v_min) + slack) break;
                    if (e->i >= 0) meet(e->i);
                }
            }
            if (backward) {
                for (auto e = first_not_below(xa - c.v_min * dt + slack); e != c.sorted.begin();) {
                    --e;
                    if (xa - (e->key + c.v_max * dt) > (best - t) * (c.v_max - va) + slack) break;
                    if (e->i >= 0) meet(e->i);
                }
            }
            for (const std::int32_t j : c.unsorted) meet(j);
        }
        if (behind >= 0)
            heap_.push({best, behind, ahead, loc_[static_cast<std::size_t>(behind)].version,
                        loc_[static_cast<std::size_t>(ahead)].version, i});
    }

    void run_meetings() {
        while (!heap_.empty()) {
            const Meeting c = heap_.top();
            heap_.pop();
            const bool behind_current = loc_[static_cast<std::size_t>(c.behind)].version == c.behind_version;
            const bool ahead_current = loc_[static_cast<std::size_t>(c.ahead)].version == c.ahead_version;
            if (behind_current && ahead_current) {
                bend(c.behind, c.ahead, c.time);
            } else if (c.owner == c.behind ? behind_current : ahead_current) {
                look(c.owner, c.time);  // its other line bent since: look again from then
            }
        }
    }

    // Line a's velocity to v_new at t_e (position x_e), keeping the block's
    // velocity order, with Eq. O1's term for every line it passes.
    void change_velocity(std::int32_t a, double v_new, double x_e, double t_e) {
        Local& l = loc_[static_cast<std::size_t>(a)];
        std::int32_t r = l.vrank;
        const bool down = v_new < l.v;
        l.v = v_new;
        const auto m = static_cast<std::int32_t>(by_velocity_.size());
        while (down ? r > 0 && slower(a, by_velocity_[static_cast<std::size_t>(r - 1)])
                    : r + 1 < m && slower(by_velocity_[static_cast<std::size_t>(r + 1)], a)) {
            const std::int32_t j = by_velocity_[static_cast<std::size_t>(down ? r - 1 : r + 1)];
            const double x_j = local_position(j, t_e);
            // Passing j downwards: A goes from [a behind j] to [j behind a];
            // upwards the other way round.
            const int sign = (x_e > x_j) - (x_e < x_j);
            flip_sum_ += down ? sign : -sign;
            by_velocity_[static_cast<std::size_t>(r)] = j;
            loc_[static_cast<std::size_t>(j)].vrank = r;
            r += down ? -1 : 1;
        }
        by_velocity_[static_cast<std::size_t>(r)] = a;
        l.vrank = r;
    }

    void leave_class(std::int32_t i) {
        Local& l = loc_[static_cast<std::size_t>(i)];
        Class& c = classes_[static_cast<std::size_t>(l.cls)];
        if (l.slot >= 0) {
            c.sorted[static_cast<std::size_t>(l.slot)].i = -1;
            ++c.gone;
        } else {
            const auto u = static_cast<std::size_t>(-l.slot - 1);
            const std::int32_t last = c.unsorted.back();
            c.unsorted[u] = last;
            loc_[static_cast<std::size_t>(last)].slot = -static_cast<std::int32_t>(u) - 1;
            c.unsorted.pop_back();
        }
    }
    void join_class(std::int32_t i, double t) {
        Local& l = loc_[static_cast<std::size_t>(i)];
        l.cls = class_of(l.v);
        Class& c = classes_[static_cast<std::size_t>(l.cls)];
        c.unsorted.push_back(i);
        l.slot = -static_cast<std::int32_t>(c.unsorted.size());
        c.v_min = std::min(c.v_min, l.v);
        c.v_max = std::max(c.v_max, l.v);
        if (c.unsorted.size() > most_unsorted || 2 * c.gone > c.sorted.size() + 8) resort(c, t);
    }
    // The class's lines sorted by position at t, which becomes its reference time.
    void resort(Class& c, double t) {
        std::vector<Entry>& e = c.sorted;
        e.erase(std::remove_if(e.begin(), e.end(), [](const Entry& x) { return x.i < 0; }), e.end());
        for (const std::int32_t j : c.unsorted) e.push_back({0.0, j});
        c.unsorted.clear();
        c.v_min = never;
        c.v_max = -never;
        for (Entry& x : e) {
            x.key = local_position(x.i, t);
            c.v_min = std::min(c.v_min, loc_[static_cast<std::size_t>(x.i)].v);
            c.v_max = std::max(c.v_max, loc_[static_cast<std::size_t>(x.i)].v);
        }
        std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) { return a.key < b.key; });
        for (std::size_t k = 0; k < e.size(); ++k) loc_[static_cast<std::size_t>(e[k].i)].slot = static_cast<std::int32_t>(k);
        c.reference = t;
        c.gone = 0;
    }

    // The inelastic crossing of `behind` (catching) and `ahead` at t_e (Eq. (1)
    // through collide()): both leave from the catching line's position, the
    // catching line with the physical right particle's velocity.
    void bend(std::int32_t behind, std::int32_t ahead, double t_e) {
        ++inelastic_;
        const double x_e = local_position(behind, t_e);
        const PostCollision after = collide(1.0, loc_[static_cast<std::size_t>(behind)].v, 1.0,
                                            loc_[static_cast<std::size_t>(ahead)].v, model_.restitution);
        for (const std::int32_t i : {behind, ahead}) {
            Local& l = loc_[static_cast<std::size_t>(i)];
            l.x = x_e;
            l.clock = t_e;
            leave_class(i);
        }
        change_velocity(behind, after.right_velocity, x_e, t_e);
        change_velocity(ahead, after.left_velocity, x_e, t_e);
        for (const std::int32_t i : {behind, ahead}) {
            Local& l = loc_[static_cast<std::size_t>(i)];
            ++l.version;
            l.last_partner = i == behind ? ahead : behind;
            join_class(i, t_e);
        }
        look(behind, t_e);
        look(ahead, t_e);
    }

    CollisionModel model_;
    double ring_;
    double now_ = 0.0;
    bool started_ = false;
    std::vector<double> x_, v_, clock_;  // by line id: position at clock (unwrapped), velocity, time of last bend
    std::vector<std::int32_t> order_;    // line ids in ring order at now_
    std::int64_t winding_ = 0;           // turns taken out of the stored positions
    std::int64_t offset_ = 0;            // c of the particle labelling (clusters)
    std::uint64_t collisions_ = 0;
    std::uint64_t inelastic_ = 0;
    std::vector<std::int64_t> cuts_;
    std::vector<std::pair<double, std::int32_t>> key_;
    // The block being run.
    std::vector<Local> loc_;
    std::vector<std::int32_t> by_velocity_;
    std::vector<std::int32_t> rank_;
    std::vector<std::int64_t> fenwick_;
    std::vector<Class> classes_;
    double block_v_min_ = 0.0;
    double class_width_ = 1.0;
    double end_ = 0.0;
    std::int64_t flip_sum_ = 0;
    std::priority_queue<Meeting, std::vector<Meeting>, std::greater<>> heap_;
    std::optional<CollapseReport> no_collapse_;
};

}  // namespace shockgas::testing
