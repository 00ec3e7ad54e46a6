// SPDX-License-Identifier: GPL-3.0-or-later
// The event queue returns events in exactly the order of a reference ordered
// set, on randomized workloads of schedule / reschedule / remove / pop.
#include <cstdint>

#include <gtest/gtest.h>

#include "../queue_workload.hpp"
#include "event_queue.hpp"

namespace {

TEST(EventQueue, MatchesReferenceOrderOnRandomWorkloads) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        shockgas::testing::QueueWorkload workload(seed, 500);
        shockgas::EventQueue queue(workload.slots());
        workload.run(20000, queue);
        ASSERT_FALSE(HasFatalFailure()) << "seed " << seed;
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
