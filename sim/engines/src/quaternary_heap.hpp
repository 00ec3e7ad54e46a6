// SPDX-License-Identifier: GPL-3.0-or-later
// The event queue of EventEngine (and of the pass-through engine's kinetic
// lists): an indexed 4-ary min-heap of (time, slot) entries stored
// contiguously.
//
// Same ordering rule as EventQueue (time, then slot), so the two return
// events in exactly the same order (tested). Differences are only in layout:
// the key travels with the slot in one 16-byte entry, so a comparison during a
// sift reads the entry itself instead of a separate time array, and four
// children share one or two cache lines, halving the depth of a binary heap.
// Within one exact time window a block's heap holds only the pairs due in that
// window, so it is small and stays in cache.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace shockgas {

class QuaternaryHeap {
public:
    static constexpr double never = std::numeric_limits<double>::infinity();

    struct Entry {
        double time;
        std::int32_t slot;
    };

    explicit QuaternaryHeap(std::int32_t slots = 0) { reset(slots); }

    void reset(std::int32_t slots) {
        position_.assign(static_cast<std::size_t>(slots), absent);
        heap_.clear();
        heap_.reserve(static_cast<std::size_t>(slots));
    }

    bool empty() const { return heap_.empty(); }
    std::size_t size() const { return heap_.size(); }
    std::int32_t top_slot() const { return heap_.front().slot; }
    double top_time() const { return heap_.empty() ? never : heap_.front().time; }
    bool contains(std::int32_t slot) const { return position_[static_cast<std::size_t>(slot)] != absent; }

    // Schedule slot at time t; t = never removes it.
    void schedule(std::int32_t slot, double t) {
        if (t == never) {
            remove(slot);
            return;
        }
        const std::int32_t position = position_[static_cast<std::size_t>(slot)];
        if (position == absent) {
            heap_.push_back({t, slot});
            sift_up(static_cast<std::int32_t>(heap_.size()) - 1);
            return;
        }
        Entry& entry = heap_[static_cast<std::size_t>(position)];
        const bool earlier = t < entry.time;  // same slot: time alone decides
        entry.time = t;
        if (earlier)
            sift_up(position);
        else
            sift_down(position);
    }

    // The top entry moved to time t, not earlier than its current time.
    void replace_top(double t) {
        heap_.front().time = t;
        sift_down(0);
    }
    // The top entry leaves, and slots a and b (-1: none; a != b) are
    // scheduled at ta and tb if these are not after `due` and removed if they
    // are, as pop_top and two schedules would leave the heap. An event's two
    // neighbour pairs after it: where one of them was not queued, it takes
    // the top's place, one sift instead of a pop and a push (docs/engines.md).
    [[gnu::always_inline]] inline void pop_top_and_schedule(std::int32_t a, double ta, std::int32_t b, double tb,
                                                            double due) {
        const bool a_enters = a >= 0 && ta <= due && ta != never && !contains(a);
        const bool b_enters = !a_enters && b >= 0 && tb <= due && tb != never && !contains(b);
        if (a_enters || b_enters) {
            position_[static_cast<std::size_t>(heap_.front().slot)] = absent;
            place(0, a_enters ? Entry{ta, a} : Entry{tb, b});
            sift_down(0);
        } else {
            pop_top();
        }
        if (a >= 0 && !a_enters) {
            if (ta <= due)
                schedule(a, ta);  // never: removed
            else
                remove(a);
        }
        if (b >= 0 && !b_enters) {
            if (tb <= due)
                schedule(b, tb);
            else
                remove(b);
        }
    }
    // Empties the heap: every queued slot is absent again.
    void clear() {
        for (const Entry& entry : heap_) position_[static_cast<std::size_t>(entry.slot)] = absent;
        heap_.clear();
    }
    // Removes the top entry.
    void pop_top() {
        position_[static_cast<std::size_t>(heap_.front().slot)] = absent;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (heap_.empty()) return;
        heap_.front() = last;
        sift_down(0);
    }

    void remove(std::int32_t slot) {
        const std::int32_t position = position_[static_cast<std::size_t>(slot)];
        if (position == absent) return;
        position_[static_cast<std::size_t>(slot)] = absent;
        const Entry last = heap_.back();
        heap_.pop_back();
        if (last.slot == slot) return;
        const Entry removed = heap_[static_cast<std::size_t>(position)];
        heap_[static_cast<std::size_t>(position)] = last;
        position_[static_cast<std::size_t>(last.slot)] = position;
        if (before(last, removed))
            sift_up(position);
        else
            sift_down(position);
    }

    // Bulk load: append entries in any order, then heapify() once (Floyd's
    // bottom-up construction, linear time). The heap must be empty before.
    void append_unordered(std::int32_t slot, double t) {
        position_[static_cast<std::size_t>(slot)] = static_cast<std::int32_t>(heap_.size());
        heap_.push_back({t, slot});
    }
    void heapify() {
        const auto count = static_cast<std::int32_t>(heap_.size());
        for (std::int32_t position = (count - 2) / 4; position >= 0 && count > 1; --position) sift_down(position);
    }

private:
    static constexpr std::int32_t absent = -1;

    // (time, slot) order. Bitwise, not short-circuit, operators: the result is
    // computed without branches, which matters because heap comparisons are
    // unpredictable and a mispredicted branch costs more than the comparison.
    static bool before(const Entry& a, const Entry& b) {
        return (a.time < b.time) | ((a.time == b.time) & (a.slot < b.slot));
    }
    void place(std::int32_t position, const Entry& entry) {
        heap_[static_cast<std::size_t>(position)] = entry;
        position_[static_cast<std::size_t>(entry.slot)] = position;
    }
    void sift_up(std::int32_t position) {
        const Entry entry = heap_[static_cast<std::size_t>(position)];
        while (position > 0) {
            const std::int32_t parent = (position - 1) / 4;
            const Entry& above = heap_[static_cast<std::size_t>(parent)];
            if (!before(entry, above)) break;
            place(position, above);
            position = parent;
        }
        place(position, entry);
    }
    void sift_down(std::int32_t position) {
        const auto count = static_cast<std::int32_t>(heap_.size());
        const Entry entry = heap_[static_cast<std::size_t>(position)];
        for (;;) {
            const std::int32_t first = 4 * position + 1;
            if (first >= count) break;
            std::int32_t best = first;
            if (first + 4 <= count) {
                // All four children: a tournament of selects (cmov), no branches.
                const Entry* child = &heap_[static_cast<std::size_t>(first)];
                const std::int32_t low = before(child[1], child[0]) ? 1 : 0;
                const std::int32_t high = before(child[3], child[2]) ? 3 : 2;
                best = first + (before(child[high], child[low]) ? high : low);
            } else {
                for (std::int32_t c = first + 1; c < count; ++c)
                    if (before(heap_[static_cast<std::size_t>(c)], heap_[static_cast<std::size_t>(best)])) best = c;
            }
            const Entry& below = heap_[static_cast<std::size_t>(best)];
            if (!before(below, entry)) break;
            place(position, below);
            position = best;
        }
        place(position, entry);
    }

    std::vector<std::int32_t> position_;
    std::vector<Entry> heap_;
};

}  // namespace shockgas
