// The event queue returns events in exactly the order of a reference ordered
// set, on randomized workloads of schedule / reschedule / remove / pop.
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/event_queue.hpp"

namespace {

TEST(EventQueue, MatchesReferenceOrderOnRandomWorkloads) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        std::mt19937_64 rng(seed);
        const std::int32_t slots = 1 + static_cast<std::int32_t>(rng() % 500);
        shockgas::EventQueue queue(slots);
        std::set<std::pair<double, std::int32_t>> reference;  // (time, slot): the tie-break rule
        std::vector<double> scheduled(static_cast<std::size_t>(slots), shockgas::EventQueue::never);
        // Coarse times (multiples of 1/8) make exact ties common.
        std::uniform_int_distribution<int> coarse(0, 64);
        for (int op = 0; op < 20000; ++op) {
            const auto slot = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(slots));
            const auto s = static_cast<std::size_t>(slot);
            const auto action = rng() % 4;
            if (action <= 1) {
                const double t = coarse(rng) / 8.0;
                if (scheduled[s] != shockgas::EventQueue::never) reference.erase({scheduled[s], slot});
                reference.insert({t, slot});
                scheduled[s] = t;
                queue.schedule(slot, t);
            } else if (action == 2) {
                if (scheduled[s] != shockgas::EventQueue::never) reference.erase({scheduled[s], slot});
                scheduled[s] = shockgas::EventQueue::never;
                queue.remove(slot);
            } else if (!reference.empty()) {
                const auto expected = *reference.begin();
                ASSERT_EQ(queue.top_slot(), expected.second);
                ASSERT_EQ(queue.top_time(), expected.first);
                reference.erase(reference.begin());
                scheduled[static_cast<std::size_t>(expected.second)] = shockgas::EventQueue::never;
                queue.remove(expected.second);
            }
            ASSERT_EQ(queue.size(), reference.size());
        }
    }
}

TEST(EventQueue, EmptyQueueReportsNever) {
    shockgas::EventQueue queue(3);
    EXPECT_TRUE(queue.empty());
    EXPECT_EQ(queue.top_time(), shockgas::EventQueue::never);
    queue.schedule(1, 2.0);
    queue.schedule(1, shockgas::EventQueue::never);
    EXPECT_TRUE(queue.empty());
}

}  // namespace
