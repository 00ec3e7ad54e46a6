// SPDX-License-Identifier: GPL-3.0-or-later
// The event calendar of the disk and sphere engine: one entry per particle,
// keyed by (time, particle), popped in exactly the order of the ring's
// QuaternaryHeap (tested), in O(1) expected work per operation instead of
// O(log N) (R. Brown, Commun. ACM 31, 1220 (1988); G. Paul, J. Comput. Phys.
// 221, 615 (2007)). docs/spheres.md, "Speed", has the measurement that chose it.
//
// Time is cut into days of width w; day d = floor(t / w) goes to bucket
// d mod B (B a power of two, at least N). A bucket is an unsorted doubly linked
// list of the entries whose day maps to it; entries further than B days ahead
// of the current day wait in a separate list (the far future) and are filed
// when the calendar's year reaches them. The minimum is found by scanning days
// from the current one, each bucket for entries of exactly that day, and is
// cached until an entry earlier than it is scheduled or it is removed. The day
// width follows the events: every B pops it is set to 4 mean gaps between pops
// (a few entries a day) and the calendar refiled if it was off by 2x or more.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace shockgas::spheres {

class CalendarQueue {
public:
    static constexpr double never = std::numeric_limits<double>::infinity();

    explicit CalendarQueue(std::int32_t slots = 0) { reset(slots); }

    void reset(std::int32_t slots) {
        const auto n = static_cast<std::size_t>(slots);
        time_.assign(n, never);
        day_.assign(n, 0);
        next_.assign(n, none);
        previous_.assign(n, none);
        where_.assign(n, absent);
        std::size_t buckets = 16;
        while (buckets < n) buckets *= 2;
        head_.assign(buckets, none);
        mask_ = static_cast<std::int64_t>(buckets) - 1;
        far_head_ = none;
        size_ = 0;
        top_valid_ = false;
        current_day_ = 0;
        day_width_ = 1.0;
        pops_ = 0;
        first_pop_time_ = 0.0;
    }

    // Memory per slot: time, day, links, where; and about two buckets a slot.
    static constexpr std::size_t bytes_per_slot = 2 * sizeof(double) + 2 * sizeof(std::int32_t) + sizeof(std::int64_t) +
                                                  2 * sizeof(std::int32_t);

    bool empty() const { return size_ == 0; }
    std::size_t size() const { return size_; }

    std::int32_t top_slot() {
        find_top();
        return top_slot_;
    }
    double top_time() {
        if (size_ == 0) return never;
        find_top();
        return time_[static_cast<std::size_t>(top_slot_)];
    }

    // Schedules slot at time t (t >= the last popped time); never removes it.
    void schedule(std::int32_t slot, double t) {
        remove(slot);
        if (t == never) return;
        const auto u = static_cast<std::size_t>(slot);
        time_[u] = t;
        file(slot);
        ++size_;
        if (top_valid_ && before(slot, top_slot_)) top_slot_ = slot;
    }

    void remove(std::int32_t slot) {
        const auto u = static_cast<std::size_t>(slot);
        if (where_[u] == absent) return;
        unlink(slot);
        time_[u] = never;
        --size_;
        if (top_valid_ && top_slot_ == slot) top_valid_ = false;
    }

    // The top entry was taken: count it for the day width, which follows
    // the mean gap between pops.
    void popped() {
        const double t = time_[static_cast<std::size_t>(top_slot_)];
        if (pops_ == 0) first_pop_time_ = t;
        if (++pops_ < static_cast<std::uint64_t>(mask_ + 1)) return;
        const double gap = (t - first_pop_time_) / static_cast<double>(pops_);
        pops_ = 0;
        const double width = 4.0 * gap;
        if (width > 0.0 && std::isfinite(width) && (width > 2.0 * day_width_ || width < 0.5 * day_width_))
            refile(width, t);
    }

    // Bulk load, as QuaternaryHeap's (append, then heapify). heapify() sets
    // the first day width from the entries: 4 mean gaps, the gap being the mean
    // time to an entry over the number of entries.
    void append_unordered(std::int32_t slot, double t) { schedule(slot, t); }
    void heapify() {
        if (size_ == 0) return;
        double earliest = never;
        for (std::size_t s = 0; s < time_.size(); ++s)
            if (where_[s] != absent) earliest = std::min(earliest, time_[s]);
        double sum = 0.0;
        for (std::size_t s = 0; s < time_.size(); ++s)
            if (where_[s] != absent) sum += time_[s] - earliest;
        const double width = 4.0 * sum / (static_cast<double>(size_) * static_cast<double>(size_));
        if (width > 0.0 && std::isfinite(width)) refile(width, earliest);
    }

private:
    static constexpr std::int32_t none = -1;
    static constexpr std::int64_t absent = std::numeric_limits<std::int64_t>::min();
    static constexpr std::int64_t far_future = std::numeric_limits<std::int64_t>::max();

    bool before(std::int32_t a, std::int32_t b) const {
        const double ta = time_[static_cast<std::size_t>(a)], tb = time_[static_cast<std::size_t>(b)];
        return ta < tb || (ta == tb && a < b);
    }
    std::int64_t day_of(double t) const {
        const double d = std::floor(t / day_width_);
        return d < 9.0e18 ? static_cast<std::int64_t>(d) : far_future;
    }

    // Puts slot (whose time is set) into its bucket, or the far future.
    void file(std::int32_t slot) {
        const auto u = static_cast<std::size_t>(slot);
        const std::int64_t day = day_of(time_[u]);
        day_[u] = day;
        std::int32_t* head;
        if (day - current_day_ > mask_) {
            where_[u] = far_future;
            head = &far_head_;
        } else {
            where_[u] = day & mask_;
            head = &head_[static_cast<std::size_t>(day & mask_)];
        }
        next_[u] = *head;
        previous_[u] = none;
        if (*head != none) previous_[static_cast<std::size_t>(*head)] = slot;
        *head = slot;
    }
    void unlink(std::int32_t slot) {
        const auto u = static_cast<std::size_t>(slot);
        const std::int32_t before_it = previous_[u], after_it = next_[u];
        if (before_it != none)
            next_[static_cast<std::size_t>(before_it)] = after_it;
        else if (where_[u] == far_future)
            far_head_ = after_it;
        else
            head_[static_cast<std::size_t>(where_[u])] = after_it;
        if (after_it != none) previous_[static_cast<std::size_t>(after_it)] = before_it;
        where_[u] = absent;
    }

    // The earliest entry: the first day from the current one whose bucket
    // holds an entry of that day. At each year's first day the far future's
    // entries within the coming year are filed; after a whole year without
    // entries, when the buckets are empty, the calendar jumps to the far
    // future's earliest day.
    void find_top() {
        if (top_valid_ || size_ == 0) return;
        for (;;) {
            for (std::int64_t scanned = 0; scanned <= mask_; ++scanned, ++current_day_) {
                if ((current_day_ & mask_) == 0 && far_head_ != none) refile_far_future();
                std::int32_t best = none;
                for (std::int32_t s = head_[static_cast<std::size_t>(current_day_ & mask_)]; s != none;
                     s = next_[static_cast<std::size_t>(s)])
                    if (day_[static_cast<std::size_t>(s)] == current_day_ && (best == none || before(s, best))) best = s;
                if (best != none) {
                    top_slot_ = best;
                    top_valid_ = true;
                    return;
                }
            }
            // A year's days scanned in vain. With no far future, the entries
            // were filed into buckets at a year boundary during the scan and
            // lie within a year of here: scan on.
            if (far_head_ == none) continue;
            std::int64_t earliest_day = far_future;
            for (std::int32_t s = far_head_; s != none; s = next_[static_cast<std::size_t>(s)])
                earliest_day = std::min(earliest_day, day_[static_cast<std::size_t>(s)]);
            current_day_ = std::max(current_day_, earliest_day);
            refile_far_future();
        }
    }

    // Files the far future's entries that are now within a year of the current day.
    void refile_far_future() {
        std::int32_t s = far_head_;
        far_head_ = none;
        while (s != none) {
            const std::int32_t following = next_[static_cast<std::size_t>(s)];
            where_[static_cast<std::size_t>(s)] = absent;
            file(s);
            s = following;
        }
    }

    // A new day width: every entry refiled, the current day that of `now`.
    void refile(double width, double now) {
        day_width_ = width;
        std::vector<std::int32_t> entries;
        entries.reserve(size_);
        for (std::size_t b = 0; b < head_.size(); ++b) {
            for (std::int32_t s = head_[b]; s != none; s = next_[static_cast<std::size_t>(s)]) entries.push_back(s);
            head_[b] = none;
        }
        for (std::int32_t s = far_head_; s != none; s = next_[static_cast<std::size_t>(s)]) entries.push_back(s);
        far_head_ = none;
        current_day_ = day_of(now);
        // Filed in slot order, so that the buckets' order (which only the
        // scan's cost, never its result, depends on) is reproducible.
        std::vector<char> queued(time_.size(), 0);
        for (std::int32_t s : entries) queued[static_cast<std::size_t>(s)] = 1;
        for (std::size_t s = 0; s < queued.size(); ++s)
            if (queued[s]) file(static_cast<std::int32_t>(s));
        top_valid_ = false;
    }

    std::vector<double> time_;
    std::vector<std::int64_t> day_;
    std::vector<std::int32_t> next_, previous_;
    std::vector<std::int64_t> where_;  // bucket, far_future, or absent
    std::vector<std::int32_t> head_;
    std::int32_t far_head_ = none;
    std::int64_t mask_ = 15;
    std::size_t size_ = 0;
    bool top_valid_ = false;
    std::int32_t top_slot_ = none;
    std::int64_t current_day_ = 0;
    double day_width_ = 1.0;
    std::uint64_t pops_ = 0;
    double first_pop_time_ = 0.0;
};

}  // namespace shockgas::spheres
