// SPDX-License-Identifier: GPL-3.0-or-later
// The event queue: an indexed binary min-heap of pair collision times.
//
// Slot i holds the next collision time of the pair (i, next(i)). Keys compare
// by (time, slot), so simultaneous events are taken in increasing slot order:
// a deterministic tie-break, independent of insertion history.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace shockgas {

class EventQueue {
public:
    static constexpr double never = std::numeric_limits<double>::infinity();

    explicit EventQueue(std::int32_t slots = 0) { reset(slots); }

    void reset(std::int32_t slots) {
        time_.assign(static_cast<std::size_t>(slots), never);
        heap_position_.assign(static_cast<std::size_t>(slots), absent);
        heap_.clear();
        heap_.reserve(static_cast<std::size_t>(slots));
    }

    bool empty() const { return heap_.empty(); }
    std::size_t size() const { return heap_.size(); }
    std::int32_t top_slot() const { return heap_.front(); }
    double top_time() const { return heap_.empty() ? never : time_[static_cast<std::size_t>(heap_.front())]; }
    double time_of(std::int32_t slot) const { return time_[static_cast<std::size_t>(slot)]; }

    // Schedule slot at time t; t = never removes it.
    void schedule(std::int32_t slot, double t) {
        const auto s = static_cast<std::size_t>(slot);
        if (t == never) {
            remove(slot);
            return;
        }
        const double old = time_[s];
        time_[s] = t;
        if (heap_position_[s] == absent) {
            heap_position_[s] = static_cast<std::int32_t>(heap_.size());
            heap_.push_back(slot);
            sift_up(heap_position_[s]);
        } else if (before(t, slot, old, slot)) {
            sift_up(heap_position_[s]);
        } else {
            sift_down(heap_position_[s]);
        }
    }

    void remove(std::int32_t slot) {
        const auto s = static_cast<std::size_t>(slot);
        const std::int32_t position = heap_position_[s];
        time_[s] = never;
        if (position == absent) return;
        heap_position_[s] = absent;
        const std::int32_t last = heap_.back();
        heap_.pop_back();
        if (last == slot) return;
        heap_[static_cast<std::size_t>(position)] = last;
        heap_position_[static_cast<std::size_t>(last)] = position;
        sift_up(position);
        sift_down(heap_position_[static_cast<std::size_t>(last)]);
    }

private:
    static constexpr std::int32_t absent = -1;

    static bool before(double ta, std::int32_t a, double tb, std::int32_t b) {
        return ta < tb || (ta == tb && a < b);
    }
    bool less(std::int32_t a, std::int32_t b) const {
        return before(time_[static_cast<std::size_t>(a)], a, time_[static_cast<std::size_t>(b)], b);
    }
    void place(std::int32_t position, std::int32_t slot) {
        heap_[static_cast<std::size_t>(position)] = slot;
        heap_position_[static_cast<std::size_t>(slot)] = position;
    }
    void sift_up(std::int32_t position) {
        const std::int32_t slot = heap_[static_cast<std::size_t>(position)];
        while (position > 0) {
            const std::int32_t parent = (position - 1) / 2;
            const std::int32_t parent_slot = heap_[static_cast<std::size_t>(parent)];
            if (!less(slot, parent_slot)) break;
            place(position, parent_slot);
            position = parent;
        }
        place(position, slot);
    }
    void sift_down(std::int32_t position) {
        const auto count = static_cast<std::int32_t>(heap_.size());
        const std::int32_t slot = heap_[static_cast<std::size_t>(position)];
        for (;;) {
            std::int32_t child = 2 * position + 1;
            if (child >= count) break;
            if (child + 1 < count && less(heap_[static_cast<std::size_t>(child + 1)], heap_[static_cast<std::size_t>(child)]))
                ++child;
            const std::int32_t child_slot = heap_[static_cast<std::size_t>(child)];
            if (!less(child_slot, slot)) break;
            place(position, child_slot);
            position = child;
        }
        place(position, slot);
    }

    std::vector<double> time_;
    std::vector<std::int32_t> heap_position_;
    std::vector<std::int32_t> heap_;
};

}  // namespace shockgas
