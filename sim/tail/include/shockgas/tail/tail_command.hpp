// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-tail as a library call: what the program's options ask for
// (TailRequest, whose defaults are the program's), and the run that carries it
// out (run_tail): check the options, build the sampler's parameters and the
// chains' instanton starts, run the chains and write the file. The program
// (sim/tail/app/shockgas_tail.cpp) binds its options to these fields, shows
// progress and prints tail_summary.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shockgas/tail/tail_sampler.hpp"

namespace shockgas {

struct TailRequest {
    double time = 1000.0;                 // t at which the tagged cluster's velocity is taken
    std::int64_t half_window = 1000;      // particles on each side of the tagged one
    std::int64_t focus = 0;               // proposals within +-focus of the tag (0: the whole window)
    double z_reach = 5.5, z_step = 0.25;  // the default bias ladder (tail_bias_ladder)
    std::vector<double> biases;           // an explicit ladder instead (empty: the default one)
    bool prior_start = false;             // every replica from the prior, not from the instanton
    std::string law = "gaussian";         // initial velocities: gaussian or uniform
    double bin_width = 0.02;              // output bin width in z, a multiple of sampler.fine_bin_width
    std::string output;                   // HDF5 file
    // The sampler's own settings. Its biases, sites, focus range, starts, law
    // and bins per output bin are set from the fields above
    // (tail_sampler_parameters, tail_start_means).
    TailSamplerParameters sampler = [] {
        TailSamplerParameters p;
        p.steps_per_bias = 100000;
        p.burn_in_steps = 10000;
        p.threads = 0;
        return p;
    }();
};

// The sampler's parameters for the request, without the starts: InputError for
// an unknown law, a negative focus, or a bin width that is no positive
// multiple of the WHAM bins.
TailSamplerParameters tail_sampler_parameters(const TailRequest& request);

// The chains' start means (biases x sites): the instanton of each target of
// the default ladder (tail_ladder_targets); empty, the prior, for an explicit
// ladder or prior_start.
std::vector<double> tail_start_means(const TailRequest& request);

// What the program hears while run_tail works: the chains' progress, and
// "sampled" once the chains are done, before the file is written.
struct TailHooks {
    TailProgress progress;
    std::function<void()> sampled;
};

struct TailOutcome {
    TailSamplerParameters parameters;  // as run
    TailEstimate estimate;
};

// Runs the request: checks the options and that the output can be written,
// runs the chains on the tagged cluster's velocity and writes the estimate
// (write_tail_estimate, observable "tagged_cluster_velocity") to
// request.output with `program`'s provenance.
TailOutcome run_tail(const TailRequest& request, const std::string& program, const TailHooks& hooks = {});

// The smallest positive Phi of the estimate and its z; density 1 and z 0 when
// no bin is below 1.
struct DeepestDensity {
    double density = 1.0;
    double z = 0.0;
};
DeepestDensity deepest_density(const TailEstimate& estimate);

// The program's one line on stdout: the file, t, the ladder and chains, the
// evaluations, the deepest Phi and the time taken (no newline).
std::string tail_summary(const TailRequest& request, const TailOutcome& outcome);

}  // namespace shockgas
