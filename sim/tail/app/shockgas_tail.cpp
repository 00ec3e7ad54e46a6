// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-tail: the far tail of the sticky gas's Phi(z) by biased Markov
// chains over the initial velocities of a window around a tagged particle
// (docs/far-tail.md). Binds the command line to a shockgas::TailRequest, runs
// it (shockgas::run_tail, shockgas/tail/tail_command.hpp) and prints the
// summary; the method is in shockgas/tail/tail_sampler.hpp.
#include <cstdio>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/cli/progress.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/tail/tail_command.hpp"

namespace {

// Every option, bound to the request's fields (their defaults are the request's).
void add_options(CLI::App& app, shockgas::TailRequest& request, double& progress_interval) {
    shockgas::TailSamplerParameters& p = request.sampler;
    app.set_version_flag("--version", "shockgas-tail " + shockgas::build_info().version);
    app.add_option("--time,-t", request.time, "time t at which the tagged cluster's velocity is taken")
        ->capture_default_str();
    app.add_option("--half-window", request.half_window, "particles on each side of the tagged one (open line)")
        ->capture_default_str();
    app.add_option("--focus", request.focus,
                   "proposals pick a site within +-focus of the tag with probability --focus-probability "
                   "(0: the whole window)")
        ->capture_default_str();
    app.add_option("--focus-probability", p.focus_probability,
                   "share of proposals whose site (a block shift's first site) is picked within +-focus of the "
                   "tag; the rest pick any site of the window")
        ->capture_default_str();
    app.add_option("--block-probability", p.block_probability, "share of block-shift moves")->capture_default_str();
    app.add_option("--block-max", p.block_max, "longest run of sites a block shift moves")->capture_default_str();
    app.add_option("--exchange-interval", p.exchange_interval, "steps per bias between replica exchanges")
        ->capture_default_str();
    app.add_flag("--prior-start", request.prior_start, "start every replica from the prior, not from the instanton");
    app.add_option("--z-reach", request.z_reach, "deepest z of the default bias ladder")->capture_default_str();
    app.add_option("--z-step", request.z_step, "spacing in z of the default bias ladder")->capture_default_str();
    app.add_option("--biases", request.biases,
                   "explicit bias ladder beta_k (first 0), comma separated, instead of --z-reach/--z-step")
        ->delimiter(',');
    app.add_option("--steps-per-bias", p.steps_per_bias, "recorded Metropolis steps per chain and bias")
        ->capture_default_str();
    app.add_option("--burn-in", p.burn_in_steps, "unrecorded steps before each bias")->capture_default_str();
    app.add_option("--chains", p.chains, "independent chains (jackknife error bars)")->capture_default_str();
    app.add_option("--seed", p.seed, "random seed, 0 .. 2^63 - 1")
        ->check(shockgas::cli::seed_in_range)
        ->capture_default_str();
    app.add_option("-j,--threads", p.threads,
                   "chains run at once, one per thread; 0 means every core (the result does not depend on it)")
        ->capture_default_str();
    app.add_option("--progress-interval", progress_interval,
                   "when stderr is not a terminal (a batch job's log), write a progress line every this many "
                   "wall seconds")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--velocity-law", request.law, "initial velocities: gaussian or uniform (variance 1/3)")
        ->capture_default_str();
    // Samples outside [z-min, z-max) are counted in no bin, and the unbiased chain fixes the
    // norm, so the range must hold the whole unbiased mass (tail_sampler.hpp).
    app.add_option("--z-min", p.z_min,
                   "lower end of the z range histogrammed and written (must hold the whole unbiased mass)")
        ->capture_default_str();
    app.add_option("--z-max", p.z_max,
                   "upper end of the z range histogrammed and written; samples beyond it are not counted")
        ->capture_default_str();
    app.add_option("--bin-width", request.bin_width,
                   "output bin width in z (a multiple of the 0.001 WHAM bins; the bin average differs from the "
                   "density at the centre by ~ (h d ln Phi/dz)^2/24, 3% for 0.02 at z = 5)")
        ->capture_default_str();
    app.add_option("--output,-o", request.output, "output HDF5 file")->required();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Far tail of the sticky gas's mass-weighted velocity distribution Phi(z), z = V t^(1/3), "
        "by biased Markov chains over a window's initial velocities (docs/far-tail.md)"};
    shockgas::TailRequest request;
    double progress_interval = 60.0;
    add_options(app, request, progress_interval);
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-tail"); status >= 0) return status;
    return shockgas::cli::run("shockgas-tail", [&] {
        // On a terminal one line, rewritten; in a log a line every interval and at
        // each tenth done (steps_progress_printer).
        const bool terminal = isatty(fileno(stderr)) != 0;
        shockgas::TailHooks hooks;
        hooks.progress = shockgas::cli::steps_progress_printer("shockgas-tail", progress_interval);
        hooks.sampled = [terminal] {
            if (terminal) fmt::print(stderr, "\n");  // past the progress line
        };
        const shockgas::TailOutcome outcome = shockgas::run_tail(request, "shockgas-tail", hooks);
        fmt::print("{}\n", shockgas::tail_summary(request, outcome));
        return 0;
    });
}
