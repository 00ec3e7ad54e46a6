// SPDX-License-Identifier: GPL-3.0-or-later
// One shockgas-spheres job: the ensemble spread over the ranks of an MPI job
// (shockgas/ranks/ranks.hpp; one process without a launcher), each rank's
// block run by run_spheres, the blocks joined at rank 0 into the file one
// process writes, bit for bit (realization k always draws from seed stream
// first_realization + k). And shockgas-merge's work on shockgas-spheres parts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/run/progress.hpp"
#include "shockgas/spheres/ensemble.hpp"

namespace shockgas::ranks {
class Session;
}

namespace shockgas::spheres {

struct SphereJob {
    SphereParameters parameters;  // the whole ensemble
    std::string output;
    // checkpoint: the job's path; each rank of a job of several ranks keeps
    // its block's as CHECKPOINT.rank<k>, so --resume wants the same number of
    // ranks as the interrupted job (refused before the run otherwise).
    SphereRunOptions run;
};

struct SphereJobOutcome {
    bool interrupted = false;    // some rank was stopped: every block's checkpoint is kept
    bool wrote_output = false;   // rank 0, the whole ensemble written
    SphereResult result;         // rank 0: the whole ensemble's; other ranks: their block's
};

// Runs the job on this rank (collective: every rank of the session calls it
// once, after parsing and checking its arguments). Progress is reported by
// rank 0 only, for its own block.
SphereJobOutcome run_spheres_job(SphereJob& job, ranks::Session& session, const ProgressCallback& progress);

// shockgas-merge on shockgas-spheres parts (--first-realization k), in
// realization order, into output (written atomically): join_spheres_parts,
// recorded with merged_by (program), merged_date and merged_from. Refuses an
// output that names a part, and parts made by another build of the engine
// than this program's (the merged file records this build's provenance).
// Returns the number of realizations merged.
std::int64_t merge_spheres_files(const std::vector<std::string>& inputs, const std::string& output,
                                 const std::string& program);

}  // namespace shockgas::spheres
