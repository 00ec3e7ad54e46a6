// SPDX-License-Identifier: GPL-3.0-or-later
// A stand-in for shockgas-sim whose rank 1 fails during its run, as an engine
// exception or std::bad_alloc would: main catches it, prints its line and
// returns. Rank 0 meanwhile "runs" far longer than the test's time limit, so
// the job ends in time only if the failing rank stops every rank (the
// DistributedSession destructor's MPI_Abort) instead of leaving rank 0 to
// wait at reduce() forever.
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "shockgas/run/distributed.hpp"

int main(int argc, char** argv) {
    constexpr auto rank0_run_time = std::chrono::minutes(10);
    shockgas::DistributedSession session(argc, argv);
    try {
        shockgas::SimulationParameters whole;
        whole.realizations = session.ranks();
        const auto mine = *session.share(whole);
        if (session.rank() == 1) throw std::runtime_error("simulated failure during the run of rank 1");
        std::this_thread::sleep_for(rank0_run_time);
        session.reduce(mine, shockgas::EnsembleResult{});
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "failing_run: error: %s\n", error.what());
        return 1;
    }
}
