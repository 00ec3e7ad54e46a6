// SPDX-License-Identifier: GPL-3.0-or-later
// One randomized workload for the event queues' property tests (tests only):
// schedule / reschedule / remove / take-the-top over a few hundred slots, with
// times on a 1/8 grid so that exact ties, which the (time, slot) rule must
// break, are common. A std::set of (time, slot) is the reference order.
#pragma once

#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace shockgas::testing {

class QueueWorkload {
public:
    static constexpr double never = std::numeric_limits<double>::infinity();

    QueueWorkload(std::uint64_t seed, std::int32_t max_slots)
        : rng_(seed),
          slots_(1 + static_cast<std::int32_t>(rng_() % static_cast<std::uint64_t>(max_slots))),
          scheduled_(static_cast<std::size_t>(slots_), never) {}

    std::int32_t slots() const { return slots_; }

    // Every other slot at a random time, for queues that bulk-load a block's
    // pending pairs before the first event.
    std::vector<std::pair<std::int32_t, double>> bulk_load() {
        std::vector<std::pair<std::int32_t, double>> loaded;
        for (std::int32_t slot = 0; slot < slots_; slot += 2) {
            const double t = grid_time();
            set(slot, t);
            loaded.emplace_back(slot, t);
        }
        return loaded;
    }

    // Runs `operations` random operations on every queue and checks each
    // against the reference after every one. A queue needs schedule(slot, t),
    // remove(slot), top_slot(), top_time() and size().
    template <class... Queue>
    void run(int operations, Queue&... queues) {
        for (int op = 0; op < operations; ++op) {
            const auto slot = static_cast<std::int32_t>(rng_() % static_cast<std::uint64_t>(slots_));
            const auto action = rng_() % 4;
            if (action <= 1) {
                const double t = grid_time();
                set(slot, t);
                (queues.schedule(slot, t), ...);
            } else if (action == 2) {
                set(slot, never);
                (queues.remove(slot), ...);
            } else if (!reference_.empty()) {
                const auto [time, top] = *reference_.begin();
                (check_top(queues, time, top), ...);
                if (::testing::Test::HasFatalFailure()) return;
                set(top, never);
                (queues.remove(top), ...);
            }
            (check_size(queues), ...);
            if (::testing::Test::HasFatalFailure()) return;
        }
    }

private:
    double grid_time() { return std::uniform_int_distribution<int>(0, 64)(rng_) / 8.0; }
    void set(std::int32_t slot, double t) {
        double& current = scheduled_[static_cast<std::size_t>(slot)];
        if (current != never) reference_.erase({current, slot});
        if (t != never) reference_.insert({t, slot});
        current = t;
    }
    template <class Queue>
    static void check_top(const Queue& queue, double time, std::int32_t slot) {
        ASSERT_EQ(queue.top_slot(), slot);
        ASSERT_EQ(queue.top_time(), time);
    }
    template <class Queue>
    void check_size(const Queue& queue) const {
        ASSERT_EQ(queue.size(), reference_.size());
    }

    std::mt19937_64 rng_;
    std::int32_t slots_;
    std::vector<double> scheduled_;
    std::set<std::pair<double, std::int32_t>> reference_;  // (time, slot): the tie-break rule
};

}  // namespace shockgas::testing
