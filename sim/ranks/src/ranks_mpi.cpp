// SPDX-License-Identifier: GPL-3.0-or-later
// The MPI implementation of shockgas/ranks/ranks.hpp (build option SHOCKGAS_MPI).
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <thread>

#include <fmt/format.h>
#include <mpi.h>

#include "shockgas/model/parameters.hpp"  // InputError
#include "shockgas/ranks/ranks.hpp"

namespace shockgas::ranks {

namespace {

constexpr int root_rank = 0;
constexpr int header_tag = 1;
constexpr int payload_tag = 2;
// MPI counts are int: payloads travel in pieces well below 2^31 bytes.
constexpr std::int64_t max_message_bytes = std::int64_t{1} << 30;
// Exit status of a job stopped because one rank failed during its run.
constexpr int failed_run_status = 1;
// Set by MPI launchers for every process they start: Open MPI's mpirun
// (OMPI_*), PMIx launchers (Open MPI 5, srun --mpi=pmix), and PMI-1/2 ones
// (MPICH's and Intel MPI's hydra, srun --mpi=pmi2).
constexpr const char* launcher_variables[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};

// Waits for one nonblocking step while sleeping between polls: a rank that
// finished its block early may wait a long time for the slowest one, and a
// blocking call would spin on a core the other ranks' threads could use.
void wait_without_spinning(MPI_Request& request) {
    constexpr auto poll_interval = std::chrono::milliseconds(10);
    for (int done = 0;;) {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done != 0) return;
        std::this_thread::sleep_for(poll_interval);
    }
}

void send(const void* data, int count, MPI_Datatype type, int destination, int tag) {
    MPI_Request request;
    MPI_Isend(data, count, type, destination, tag, MPI_COMM_WORLD, &request);
    wait_without_spinning(request);
}

void receive(void* data, int count, MPI_Datatype type, int source, int tag) {
    MPI_Request request;
    MPI_Irecv(data, count, type, source, tag, MPI_COMM_WORLD, &request);
    wait_without_spinning(request);
}

int all_min(int value) {
    int result = value;
    MPI_Request request;
    MPI_Iallreduce(&value, &result, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
    wait_without_spinning(request);
    return result;
}

}  // namespace

Session::Session(int& argc, char**& argv) {
    launched_ = std::any_of(std::begin(launcher_variables), std::end(launcher_variables),
                            [](const char* name) { return std::getenv(name) != nullptr; });
    if (!launched_) return;
    // FUNNELED: worker threads never call MPI; only main does.
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
}

Session::~Session() {
    if (!launched_) return;
    switch (phase_) {
    case Phase::setup:
        // Leaving before agree_ready(): take part in its agreement as the
        // failing rank, so that the others stop too.
        all_min(rank_);
        break;
    case Phase::running:
        // Left between agree_ready() and finish(): the others would wait at
        // the next collective step forever. Stop them all.
        if (ranks_ > 1) MPI_Abort(MPI_COMM_WORLD, failed_run_status);
        break;
    case Phase::finished:
        break;
    }
    MPI_Finalize();
}

void Session::agree_ready() {
    // Every rank reports ranks_ (ready) or its own index (failed, from the
    // destructor); the minimum names the first failing rank, if any.
    const int lowest_failing = launched_ ? all_min(ranks_) : ranks_;
    if (lowest_failing < ranks_) {
        phase_ = Phase::finished;  // every rank has agreed to stop: nothing left to wait for
        throw InputError(fmt::format("rank {} of {} failed before the run (see its own error message)",
                                     lowest_failing, ranks_));
    }
    phase_ = Phase::running;
}

bool Session::any(bool flag) {
    if (!launched_) return flag;
    return all_min(flag ? 0 : 1) == 0;
}

bool Session::root_says(bool word) {
    if (!launched_) return word;
    int value = word ? 1 : 0;
    MPI_Request request;
    MPI_Ibcast(&value, 1, MPI_INT, root_rank, MPI_COMM_WORLD, &request);
    wait_without_spinning(request);
    return value != 0;
}

std::optional<std::vector<Block>> Session::gather_at_root(Block mine) {
    if (!launched_ || ranks_ == 1) {
        std::vector<Block> blocks;
        blocks.push_back(std::move(mine));
        return blocks;
    }
    if (rank_ != root_rank) {
        const std::int64_t header[2] = {mine.failed ? 1 : 0, static_cast<std::int64_t>(mine.bytes.size())};
        send(header, 2, MPI_INT64_T, root_rank, header_tag);
        for (std::int64_t offset = 0; offset < header[1]; offset += max_message_bytes)
            send(mine.bytes.data() + offset, static_cast<int>(std::min(max_message_bytes, header[1] - offset)),
                 MPI_BYTE, root_rank, payload_tag);
        return std::nullopt;
    }
    std::vector<Block> blocks;
    blocks.push_back(std::move(mine));
    for (int source = 1; source < ranks_; ++source) {
        std::int64_t header[2] = {0, 0};
        receive(header, 2, MPI_INT64_T, source, header_tag);
        Block block{header[0] != 0, std::vector<char>(static_cast<std::size_t>(header[1]))};
        for (std::int64_t offset = 0; offset < header[1]; offset += max_message_bytes)
            receive(block.bytes.data() + offset, static_cast<int>(std::min(max_message_bytes, header[1] - offset)),
                    MPI_BYTE, source, payload_tag);
        blocks.push_back(std::move(block));
    }
    return blocks;
}

int Session::cores_available() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof(set), &set) != 0) return 0;
    return CPU_COUNT(&set);
}

}  // namespace shockgas::ranks
