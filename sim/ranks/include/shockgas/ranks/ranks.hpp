// SPDX-License-Identifier: GPL-3.0-or-later
// The processes of one job under an MPI launcher (`mpirun -np K PROGRAM`, build
// option SHOCKGAS_MPI), as the few collective steps a program that spreads
// independent realizations over ranks needs: agree that every rank is ready,
// gather each rank's bytes at rank 0, and pass rank 0's word back. What the
// bytes are (an output file's, so that merging blocks is merging parts) is the
// program's business; this room only moves them.
//
// Two implementations of this one interface: ranks_mpi.cpp (MPI) and
// ranks_serial.cpp (one rank, no MPI), so a program compiles the same calls in
// both builds. Without a launcher an MPI build is one rank and never touches
// MPI (Open MPI's singleton start-up costs about 0.5 s a run).
//
// Failure rule: no rank is left waiting for another. A rank that leaves main
// before agree_ready() makes every rank's agree_ready() throw; one that leaves
// between agree_ready() and finish() (an exception during its run) aborts the
// job; a rank whose block failed to encode sends its message instead, and rank
// 0 receives from every rank before it decodes anything.
//
// shockgas-spheres uses this room. shockgas-sim's DistributedSession
// (sim/run/src/distributed_mpi.cpp) does the same steps with the ring's types
// and is not built on this room: sim/run is part of the ring's stamp, so any
// edit there reruns every ring result; the two are joined when that stamp
// changes for a reason of its own.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace shockgas::ranks {

// One rank's contribution at gather_at_root: its bytes, or the message of
// what went wrong while making them.
struct Block {
    bool failed = false;
    std::vector<char> bytes;  // the payload, or the failure's message
};

class Session {
public:
    // Initializes MPI when started by an MPI launcher (MPI build); must be the
    // first thing main does, since MPI_Init may consume arguments from argv.
    Session(int& argc, char**& argv);
    // Finalizes MPI; see the failure rule above.
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    int rank() const { return rank_; }
    int ranks() const { return ranks_; }
    bool is_root() const { return rank_ == 0; }

    // Collective, once: every rank has parsed and checked its arguments.
    // Throws InputError naming the lowest rank that left main before.
    void agree_ready();
    // Collective: whether `flag` is true on any rank.
    bool any(bool flag);
    // Collective: rank 0's `word` on every rank (others' argument unread).
    bool root_says(bool word);
    // Collective: every rank's block at rank 0, in rank order; nullopt on the
    // other ranks.
    std::optional<std::vector<Block>> gather_at_root(Block mine);
    // After the last collective step: leaving main is no longer a failure.
    void finish() { phase_ = Phase::finished; }

    // The cores this process may run on (mpirun binds each rank to one core
    // for -np <= 2 by default), 0 when unknown.
    static int cores_available();

private:
    enum class Phase { setup, running, finished };
    int rank_ = 0;
    int ranks_ = 1;
    Phase phase_ = Phase::setup;
    bool launched_ = false;  // MPI initialized (started by an MPI launcher)
};

// The bytes of a file, and a file from bytes, in a private temporary
// directory: how a block becomes bytes and bytes a block again.
class TemporaryDirectory {
public:
    TemporaryDirectory();
    ~TemporaryDirectory();
    TemporaryDirectory(const TemporaryDirectory&) = delete;
    TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
    std::string file(const std::string& name) const;

private:
    std::string path_;
};
std::vector<char> read_bytes(const std::string& path);
void write_bytes(const std::string& path, const std::vector<char>& bytes);

}  // namespace shockgas::ranks
