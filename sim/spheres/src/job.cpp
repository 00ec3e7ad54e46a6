// SPDX-License-Identifier: GPL-3.0-or-later
// One shockgas-spheres job over MPI ranks or one process (job.hpp).
//
// A rank's block travels to rank 0 as the bytes of an ordinary output file
// (write_spheres_output into a private temporary directory), and rank 0 joins
// the blocks with join_spheres_parts, as shockgas-merge joins parts: the file
// schema is the wire format, so every dataset is carried with no second
// serializer to keep in step, and the join checks that all ranks ran the same
// parameters and the same build of the engine.
#include "shockgas/spheres/job.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/ranks/ranks.hpp"
#include "shockgas/run/checkpoint.hpp"
#include "shockgas/run/distributed.hpp"  // realization_block: the ring's split of an ensemble over ranks

namespace shockgas::spheres {

namespace {

bool exists(const std::string& path) { return h5::probe(path).kind != h5::Probe::Kind::absent; }

// Checkpoints a job of another number of ranks left (BASE for one process,
// BASE.rank<k> for ranks): refused before the run, since a block's checkpoint
// holds that block's realizations only and this job would split the ensemble
// otherwise.
void check_checkpoints_of_this_layout(const std::string& base, int ranks) {
    const auto found = [](const std::string& path) {
        const auto generations = checkpoint_generations(path);
        return exists(generations[0]) || exists(generations[1]);
    };
    int rank_files = 0;  // BASE.rank0, BASE.rank1, ... as far as they go
    while (found(rank_checkpoint_path(base, rank_files))) ++rank_files;
    std::string other_job;
    if (ranks > 1 && found(base))
        other_job = fmt::format("{} is its checkpoint from one process: resume it without mpirun", base);
    else if (rank_files > 0 && rank_files != ranks)
        other_job = fmt::format("{} ... {} are its checkpoints from a job of {} ranks: resume it with mpirun -np {}",
                                rank_checkpoint_path(base, 0), rank_checkpoint_path(base, rank_files - 1), rank_files,
                                rank_files);
    if (!other_job.empty())
        throw InputError(fmt::format("this run was interrupted in a job of another number of ranks: {} (or remove "
                                     "the checkpoints to start anew)",
                                     other_job));
}

std::vector<char> encode_block(const SphereParameters& mine, const SphereResult& result) {
    ranks::TemporaryDirectory directory;
    const std::string path = directory.file("block.h5");
    write_spheres_output(path, mine, result);
    return ranks::read_bytes(path);
}

// Rank 0: the whole ensemble from every rank's block, in rank order (idle
// ranks send nothing); throws, naming the rank, when one could not be sent.
JoinedParts join_blocks(std::vector<ranks::Block>& blocks, int ranks) {
    ranks::TemporaryDirectory directory;
    std::vector<SphereOutput> parts;
    std::vector<std::string> names;
    double slowest_rank_seconds = 0.0;
    for (std::size_t source = 0; source < blocks.size(); ++source) {
        if (blocks[source].failed)
            throw InputError(fmt::format("rank {} of {} could not send its realizations: {}", source, ranks,
                                         std::string(blocks[source].bytes.begin(), blocks[source].bytes.end())));
        if (blocks[source].bytes.empty()) continue;  // idle: more ranks than realizations
        const std::string path = directory.file(fmt::format("rank-{}.h5", source));
        ranks::write_bytes(path, blocks[source].bytes);
        blocks[source].bytes = {};  // hold each block once, decoded
        parts.push_back(read_spheres_output(path));
        names.push_back(fmt::format("rank {}", source));
        slowest_rank_seconds = std::max(slowest_rank_seconds, parts.back().result.wall_seconds);
    }
    JoinedParts joined = join_spheres_parts(parts, names);
    // Ranks run side by side: the ensemble took as long as the slowest one.
    joined.result.wall_seconds = slowest_rank_seconds;
    return joined;
}

}  // namespace

SphereJobOutcome run_spheres_job(SphereJob& job, ranks::Session& session, const ProgressCallback& progress) {
    const std::string base_checkpoint = job.run.checkpoint;
    if (!base_checkpoint.empty()) check_checkpoints_of_this_layout(base_checkpoint, session.ranks());
    session.agree_ready();

    SphereParameters mine = job.parameters;
    SphereRunOptions run = job.run;
    if (session.ranks() > 1) {
        const RealizationBlock block = realization_block(job.parameters.realizations, session.rank(), session.ranks());
        mine.first_realization = job.parameters.first_realization + block.first;
        mine.realizations = static_cast<int>(block.count);
        if (mine.threads == 0) mine.threads = ranks::Session::cores_available();
        if (!run.checkpoint.empty()) run.checkpoint = rank_checkpoint_path(base_checkpoint, session.rank());
        run.checkpoint_when_done = true;  // kept until rank 0 says the whole ensemble is written
    }

    SphereJobOutcome outcome;
    if (mine.realizations > 0)
        outcome.result = run_spheres(mine, session.is_root() ? progress : ProgressCallback{}, run);
    outcome.interrupted = session.any(outcome.result.interrupted);
    if (outcome.interrupted) {
        session.finish();
        return outcome;  // every block's checkpoint stays for --resume
    }
    if (session.ranks() == 1) {
        write_spheres_output(job.output, mine, outcome.result);
        outcome.wrote_output = true;
        session.finish();
        remove_spheres_checkpoint(run.checkpoint);
        return outcome;
    }

    // Encoding failures travel as messages, so that rank 0 still receives
    // from every rank and no one is left waiting.
    ranks::Block block;
    if (mine.realizations > 0) {
        try {
            block.bytes = encode_block(mine, outcome.result);
        } catch (const std::exception& error) {
            const std::string message = error.what();
            block = {true, {message.begin(), message.end()}};
        }
    }
    auto blocks = session.gather_at_root(std::move(block));
    bool written = false;
    if (blocks) {
        try {
            JoinedParts joined = join_blocks(*blocks, session.ranks());
            write_spheres_output(job.output, joined.parameters, joined.result, {session.ranks(), {}, {}});
            outcome.result = std::move(joined.result);
            written = true;
        } catch (...) {
            session.root_says(false);  // no rank removes its checkpoint for a job that wrote no output
            session.finish();
            throw;
        }
    }
    const bool job_written = session.root_says(written);
    session.finish();
    outcome.wrote_output = job_written && session.is_root();
    if (job_written) remove_spheres_checkpoint(run.checkpoint);
    return outcome;
}

std::int64_t merge_spheres_files(const std::vector<std::string>& inputs, const std::string& output,
                                 const std::string& program) {
    h5::check_writable(output);
    // The merged file is renamed over the output: a part named as the output would be replaced.
    h5::check_not_an_input(output, inputs);
    std::vector<SphereOutput> parts;
    for (const auto& input : inputs) {
        parts.push_back(read_spheres_output(input));
        if (parts.back().spheres_sha256 != spheres_sha256())
            throw InputError(fmt::format("'{}' was made by another build of the engine (spheres_sha256 {}, this is "
                                         "{}): merge with the build that ran the parts",
                                         input, parts.back().spheres_sha256.substr(0, 12),
                                         spheres_sha256().substr(0, 12)));
    }
    JoinedParts joined = join_spheres_parts(parts, inputs);
    write_spheres_output(output, joined.parameters, joined.result,
                         {1, program + " " + build_info().version, joined.merged_from});
    return joined.result.realizations;
}

}  // namespace shockgas::spheres
