// SPDX-License-Identifier: GPL-3.0-or-later
// The MPI implementation of distributed.hpp (build option SHOCKGAS_MPI).
//
// A rank's block travels to rank 0 as the bytes of an ordinary output file:
// each rank writes its block with write_output into a private temporary
// directory (node-local, so no shared file system is needed), sends the bytes,
// and rank 0 reads every block back with read_output and joins them with
// merge_outputs, exactly as shockgas-merge joins --first-realization parts.
// Using the file schema as the wire format means every dataset the schema
// carries is carried, with no second serializer to keep in step with it, and
// merge_outputs checks on the way that all ranks ran the same parameters and
// the same build (a cluster whose nodes hold different binaries fails here).
#include "shockgas/run/distributed.hpp"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <mpi.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace shockgas {

namespace {

namespace fs = std::filesystem;

constexpr int root_rank = 0;
constexpr int header_tag = 1;
constexpr int payload_tag = 2;
// MPI counts are int: send payloads in pieces well below 2^31 bytes.
constexpr std::int64_t max_message_bytes = std::int64_t{1} << 30;
// Exit status of a job stopped because one rank failed during its run.
constexpr int failed_run_status = 1;
// Set by MPI launchers for every process they start: Open MPI's mpirun
// (OMPI_*), PMIx launchers (Open MPI 5, srun --mpi=pmix), and PMI-1/2 ones
// (MPICH's and Intel MPI's hydra, srun --mpi=pmi2). A launcher that sets none
// of them starts K independent one-rank runs: each would run the whole
// ensemble and write the same file, correct but not faster.
constexpr const char* launcher_variables[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};

// What a rank sends to rank 0 at the reduction, first in a two-integer
// header {kind, payload bytes}, then the payload.
enum class BlockKind : std::int64_t { part = 0, idle = 1, failed = 2 };

// A directory of our own under $TMPDIR (or /tmp), removed with its contents.
class TemporaryDirectory {
public:
    TemporaryDirectory() {
        std::string pattern = (fs::temp_directory_path() / "shockgas-rank-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw InputError(fmt::format("cannot create a temporary directory under '{}'",
                                         fs::temp_directory_path().string()));
        path_ = pattern;
    }
    ~TemporaryDirectory() {
        std::error_code ignored;  // best effort: a leftover temp dir is not worth failing a finished run
        fs::remove_all(path_, ignored);
    }
    TemporaryDirectory(const TemporaryDirectory&) = delete;
    TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
    fs::path file(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
};

std::vector<char> read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) throw InputError(fmt::format("cannot read back '{}'", path.string()));
    return bytes;
}

void write_bytes(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw InputError(fmt::format("cannot write '{}' (disk full?)", path.string()));
}

// This rank's block as the bytes of an output file.
std::vector<char> encode_block(const SimulationParameters& mine, const EnsembleResult& result) {
    TemporaryDirectory directory;
    const fs::path path = directory.file("block.h5");
    write_output(path.string(), mine, result);
    return read_bytes(path);
}

// Waits for one transfer while sleeping between polls. A rank that finished
// early (or is idle) may wait a long time for the slowest one; a blocking
// MPI_Send/MPI_Recv would spin on a core that the ensemble's threads could use.
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

void send_bytes(const std::vector<char>& bytes, int destination) {
    for (std::int64_t offset = 0; offset < static_cast<std::int64_t>(bytes.size()); offset += max_message_bytes) {
        const auto count = static_cast<int>(std::min<std::int64_t>(max_message_bytes,
                                                                   static_cast<std::int64_t>(bytes.size()) - offset));
        send(bytes.data() + offset, count, MPI_BYTE, destination, payload_tag);
    }
}

std::vector<char> receive_bytes(std::int64_t size, int source) {
    std::vector<char> bytes(static_cast<std::size_t>(size));
    for (std::int64_t offset = 0; offset < size; offset += max_message_bytes) {
        const auto count = static_cast<int>(std::min<std::int64_t>(max_message_bytes, size - offset));
        receive(bytes.data() + offset, count, MPI_BYTE, source, payload_tag);
    }
    return bytes;
}

// Cores this process may run on: mpirun binds ranks (to one core for -np <= 2
// by default), and "every hardware thread" would then pile all threads on it.
int cores_available() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof(set), &set) != 0) return 0;  // 0: let the ensemble decide
    return CPU_COUNT(&set);
}

}  // namespace

DistributedSession::DistributedSession(int& argc, char**& argv) {
    // A plain `shockgas-sim` (the figure pipeline's many short runs) would pay
    // Open MPI's singleton start-up, about 0.5 s, for nothing: initialize MPI
    // only when a launcher announced ranks in the environment.
    launched_ = std::any_of(std::begin(launcher_variables), std::end(launcher_variables),
                            [](const char* name) { return std::getenv(name) != nullptr; });
    if (!launched_) return;
    // FUNNELED: the ensemble's worker threads never call MPI; only main does.
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
}

DistributedSession::~DistributedSession() {
    if (!launched_) return;
    switch (phase_) {
    case Phase::setup: {
        // This rank leaves before share(): take part in share()'s agreement
        // with our own rank as the failing one, so the others stop too.
        int failing = rank_, lowest_failing = 0;
        MPI_Allreduce(&failing, &lowest_failing, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
        break;
    }
    case Phase::running:
        // Left main between share() and reduce(): its error is printed, and
        // the other ranks would wait at reduce() forever. Stop them all.
        if (ranks_ > 1) MPI_Abort(MPI_COMM_WORLD, failed_run_status);
        break;
    case Phase::reduced:
        break;
    }
    MPI_Finalize();
}

std::optional<SimulationParameters> DistributedSession::share(const SimulationParameters& whole, bool nothing_to_do) {
    // Every rank reports ranks_ (ready) or its own index (failed, from the
    // destructor); the minimum names the first failing rank, if any.
    int ready = ranks_, lowest_failing = ranks_;
    if (launched_) MPI_Allreduce(&ready, &lowest_failing, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (lowest_failing < ranks_) {
        phase_ = Phase::reduced;  // all ranks have agreed to stop: nothing left to wait for
        throw InputError(fmt::format("rank {} of {} failed before the run (see its own error message)",
                                     lowest_failing, ranks_));
    }
    // Every rank is here: rank 0's decision that there is nothing to run
    // reaches them all, and all leave together.
    int root_done = nothing_to_do ? 1 : 0;
    if (launched_) MPI_Bcast(&root_done, 1, MPI_INT, root_rank, MPI_COMM_WORLD);
    if (root_done != 0) {
        phase_ = Phase::reduced;
        return std::nullopt;
    }
    phase_ = Phase::running;
    SimulationParameters mine = whole;
    if (ranks_ == 1) return mine;  // a one-rank run is exactly the serial program
    const RealizationBlock block = realization_block(whole.realizations, rank_, ranks_);
    mine.first_realization = whole.first_realization + block.first;
    mine.realizations = static_cast<int>(block.count);
    if (mine.threads == 0) mine.threads = cores_available();
    return mine;
}

namespace {

// Rank 0: the whole ensemble from every rank's block (kinds and payloads
// indexed by rank); throws, naming the rank, when one could not be sent.
EnsembleResult join_blocks(int ranks, const std::vector<BlockKind>& kinds, std::vector<std::vector<char>>& payloads) {
    for (int source = 0; source < ranks; ++source)
        if (kinds[static_cast<std::size_t>(source)] == BlockKind::failed) {
            const auto& message = payloads[static_cast<std::size_t>(source)];
            throw InputError(fmt::format("rank {} of {} could not send its realizations: {}", source, ranks,
                                         std::string(message.begin(), message.end())));
        }

    TemporaryDirectory directory;
    std::vector<OutputFile> parts;
    std::vector<std::string> names;
    double slowest_rank_seconds = 0.0;
    for (int source = 0; source < ranks; ++source) {
        if (kinds[static_cast<std::size_t>(source)] != BlockKind::part) continue;  // idle: more ranks than realizations
        const fs::path path = directory.file(fmt::format("rank-{}.h5", source));
        write_bytes(path, payloads[static_cast<std::size_t>(source)]);
        payloads[static_cast<std::size_t>(source)] = {};  // hold each block once, as a decoded part
        parts.push_back(read_output(path.string()));
        names.push_back(fmt::format("rank {}", source));
        slowest_rank_seconds = std::max(slowest_rank_seconds, parts.back().result.wall_seconds);
    }
    EnsembleResult joined = merge_outputs(parts, names).result;
    // merge_outputs adds the parts' wall times (parts run one after another);
    // ranks run side by side, so the ensemble took as long as the slowest one.
    joined.wall_seconds = slowest_rank_seconds;
    return joined;
}

}  // namespace

std::optional<EnsembleResult> DistributedSession::reduce(const SimulationParameters& mine, EnsembleResult result) {
    phase_ = Phase::reduced;  // from here on every rank reaches the exchange below
    if (ranks_ == 1) {
        job_complete_ = result.status != "interrupted";
        return result;
    }

    // Encode this rank's block; a failure becomes a message for rank 0, so
    // that rank 0 still receives from every rank and no one is left waiting.
    BlockKind kind = BlockKind::idle;
    std::vector<char> payload;
    if (mine.realizations > 0) {
        try {
            payload = encode_block(mine, result);
            kind = BlockKind::part;
        } catch (const std::exception& error) {
            const std::string message = error.what();
            payload.assign(message.begin(), message.end());
            kind = BlockKind::failed;
        }
    }

    if (rank_ != root_rank) {
        const std::int64_t header[2] = {static_cast<std::int64_t>(kind), static_cast<std::int64_t>(payload.size())};
        send(header, 2, MPI_INT64_T, root_rank, header_tag);
        send_bytes(payload, root_rank);
        int complete = 0;  // rank 0's word on the joined ensemble (below)
        MPI_Bcast(&complete, 1, MPI_INT, root_rank, MPI_COMM_WORLD);
        job_complete_ = complete != 0;
        return std::nullopt;
    }

    // Rank 0: receive everything first, then decode, so an error while
    // decoding never leaves a sender blocked.
    std::vector<BlockKind> kinds{kind};
    std::vector<std::vector<char>> payloads;
    payloads.push_back(std::move(payload));
    for (int source = 1; source < ranks_; ++source) {
        std::int64_t header[2] = {0, 0};
        receive(header, 2, MPI_INT64_T, source, header_tag);
        kinds.push_back(static_cast<BlockKind>(header[0]));
        payloads.push_back(receive_bytes(header[1], source));
    }
    // Every rank waits for rank 0's word on the joined ensemble (job_complete):
    // sent once it is joined, or as "not complete" when joining fails, so that
    // no rank is left waiting and none removes its checkpoint for a job that
    // wrote no output.
    const auto tell_ranks = [](bool complete) {
        int word = complete ? 1 : 0;
        MPI_Bcast(&word, 1, MPI_INT, root_rank, MPI_COMM_WORLD);
    };
    try {
        EnsembleResult joined = join_blocks(ranks_, kinds, payloads);
        job_complete_ = joined.status != "interrupted";
        tell_ranks(job_complete_);
        return joined;
    } catch (...) {
        tell_ranks(false);
        throw;
    }
}

void DistributedSession::record_provenance(const std::string& output_path) const {
    if (ranks_ == 1) return;
    h5::Handle file(H5Fopen(output_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
    if (!file.valid()) throw h5::Error(fmt::format("cannot reopen '{}' to record mpi_ranks", output_path));
    h5::Group root(h5::Handle(H5Gopen2(file.id(), "/", H5P_DEFAULT), H5Gclose), "/");
    root.set_attribute("mpi_ranks", static_cast<std::int64_t>(ranks_));
}

}  // namespace shockgas
