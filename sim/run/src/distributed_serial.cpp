// SPDX-License-Identifier: GPL-3.0-or-later
// The one-rank implementation of distributed.hpp, compiled when SHOCKGAS_MPI
// is off: the whole ensemble is this process's share, and there is nothing to
// join, so shockgas-sim runs the ensemble in this one process, as without MPI.
#include "shockgas/run/distributed.hpp"

namespace shockgas {

DistributedSession::DistributedSession(int& /*argc*/, char**& /*argv*/) {}

DistributedSession::~DistributedSession() = default;

std::optional<SimulationParameters> DistributedSession::share(const SimulationParameters& whole, bool nothing_to_do) {
    if (nothing_to_do) {
        phase_ = Phase::reduced;
        return std::nullopt;
    }
    phase_ = Phase::running;
    return whole;
}

std::optional<EnsembleResult> DistributedSession::reduce(const SimulationParameters& /*mine*/, EnsembleResult result) {
    phase_ = Phase::reduced;
    job_complete_ = result.status != "interrupted";
    return result;
}

void DistributedSession::record_provenance(const std::string& /*output_path*/) const {}

}  // namespace shockgas
