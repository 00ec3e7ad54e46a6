// shockgas-tail: the far tail of the sticky gas's Phi(z) by biased Markov
// chains over the initial velocities of a window around a tagged particle
// (docs/far-tail.md). Argument parsing only; the method is in
// shockgas/tail/tail_sampler.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli/cli.hpp"
#include "shockgas/cli/progress.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/tail/tail_sampler.hpp"

int main(int argc, char** argv) {
    CLI::App app{"Far tail of the sticky gas's mass-weighted velocity distribution Phi(z), z = V t^(1/3), "
                 "by biased Markov chains over a window's initial velocities (docs/far-tail.md)"};
    app.set_version_flag("--version", "shockgas-tail " + shockgas::build_info().version);
    double time = 1000.0;
    std::int64_t half_window = 1000;
    std::int64_t focus = 0;
    double z_reach = 5.5, z_step = 0.25;
    std::vector<double> biases;
    std::string law = "gaussian";
    std::string output;
    shockgas::TailSamplerParameters p;
    p.steps_per_bias = 100000;
    p.burn_in_steps = 10000;
    app.add_option("--time,-t", time, "time t at which the tagged cluster's velocity is taken")->capture_default_str();
    app.add_option("--half-window", half_window, "particles on each side of the tagged one (open line)")
        ->capture_default_str();
    app.add_option("--focus", focus,
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
    bool prior_start = false;
    app.add_flag("--prior-start", prior_start, "start every replica from the prior, not from the instanton");
    app.add_option("--z-reach", z_reach, "deepest z of the default bias ladder")->capture_default_str();
    app.add_option("--z-step", z_step, "spacing in z of the default bias ladder")->capture_default_str();
    app.add_option("--biases", biases,
                   "explicit bias ladder beta_k (first 0), comma separated, instead of --z-reach/--z-step")
        ->delimiter(',');
    app.add_option("--steps-per-bias", p.steps_per_bias, "recorded Metropolis steps per chain and bias")
        ->capture_default_str();
    app.add_option("--burn-in", p.burn_in_steps, "unrecorded steps before each bias")->capture_default_str();
    app.add_option("--chains", p.chains, "independent chains (jackknife error bars)")->capture_default_str();
    app.add_option("--seed", p.seed, "random seed, 0 .. 2^63 - 1")->check(shockgas::cli::seed_in_range)->capture_default_str();
    p.threads = 0;
    app.add_option("-j,--threads", p.threads,
                   "chains run at once, one per thread; 0 means every core (the result does not depend on it)")
        ->capture_default_str();
    double progress_interval = 60.0;
    app.add_option("--progress-interval", progress_interval,
                   "when stderr is not a terminal (a batch job's log), write a progress line every this many "
                   "wall seconds")
        ->check(shockgas::cli::finite_non_negative)
        ->capture_default_str();
    app.add_option("--velocity-law", law, "initial velocities: gaussian or uniform (variance 1/3)")
        ->capture_default_str();
    // Samples outside [z-min, z-max) are counted in no bin, and the unbiased chain fixes the
    // norm, so the range must hold the whole unbiased mass (tail_sampler.hpp).
    app.add_option("--z-min", p.z_min,
                   "lower end of the z range histogrammed and written (must hold the whole unbiased mass)")
        ->capture_default_str();
    app.add_option("--z-max", p.z_max,
                   "upper end of the z range histogrammed and written; samples beyond it are not counted")
        ->capture_default_str();
    double bin_width = 0.02;
    app.add_option("--bin-width", bin_width,
                   "output bin width in z (a multiple of the 0.001 WHAM bins; the bin average differs from the "
                   "density at the centre by ~ (h d ln Phi/dz)^2/24, 3% for 0.02 at z = 5)")
        ->capture_default_str();
    app.add_option("--output,-o", output, "output HDF5 file")->required();
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-tail"); status >= 0) return status;
    return shockgas::cli::run("shockgas-tail", [&] {
        p.law = shockgas::velocity_law_from_string(law);
        p.biases = biases.empty() ? shockgas::tail_bias_ladder(z_reach, z_step) : biases;
        if (focus < 0) throw shockgas::InputError(fmt::format("--focus must be >= 0 (0: the whole window), got {}", focus));
        const double fine_bins = bin_width / p.fine_bin_width;
        if (!(fine_bins >= 0.5) || std::abs(fine_bins - std::round(fine_bins)) > 1e-6)
            throw shockgas::InputError(
                fmt::format("--bin-width must be a positive multiple of the {} WHAM bins, got {}", p.fine_bin_width, bin_width));
        p.sites = 2 * half_window + 1;
        p.fine_bins_per_output_bin = std::llround(fine_bins);
        const std::int64_t reach = focus > 0 ? std::min(focus, half_window) : half_window;
        p.focus_begin = half_window - reach;
        p.focus_end = half_window + reach + 1;
        shockgas::h5::check_writable(output);
        shockgas::TaggedClusterVelocity tagged(half_window, time);
        if (biases.empty() && !prior_start)
            for (double z : shockgas::tail_ladder_targets(z_reach, z_step)) {
                const auto mean = shockgas::tagged_cluster_instanton(z, time, half_window);
                p.start_mean.insert(p.start_mean.end(), mean.begin(), mean.end());
            }
        // Each thread its own copy: the observable keeps scratch clusters.
        const shockgas::ObservableFactory make_observable = [&tagged] {
            return shockgas::WindowObservable(
                [copy = tagged](std::span<const double> velocity) mutable { return copy(velocity); });
        };
        // On a terminal one line, rewritten; in a log a line when shockgas-sim's
        // ProgressLog says one is due (every interval, and at each tenth done).
        const bool terminal = isatty(fileno(stderr)) != 0;
        shockgas::ProgressLog log(progress_interval);
        const auto progress = [&](double done, double elapsed) {
            shockgas::Progress status;
            status.fraction_done = done;
            status.elapsed_seconds = elapsed;
            if (!terminal && !log.due(status)) return;
            const std::string eta = done > 0.0 ? fmt::format("{:.0f} s", elapsed * (1.0 - done) / done) : "--";
            const std::string line =
                fmt::format("shockgas-tail: progress: {:.1f}% of the steps  elapsed {:.0f} s  ETA {}", 100.0 * done,
                            elapsed, eta);
            if (terminal)
                fmt::print(stderr, "\r{:<80}", line);
            else
                fmt::print(stderr, "{}\n", line);
            std::fflush(stderr);
        };
        const auto estimate = shockgas::sample_far_tail(p, make_observable, progress);
        if (terminal) fmt::print(stderr, "\n");
        shockgas::write_tail_estimate(output, "shockgas-tail", p, estimate, time, half_window, "tagged_cluster_velocity");
        double deepest = 1.0, deepest_z = 0.0;
        for (std::size_t i = 0; i < estimate.z.size(); ++i)
            if (estimate.density[i] > 0.0 && estimate.density[i] < deepest) {
                deepest = estimate.density[i];
                deepest_z = estimate.z[i];
            }
        fmt::print("{}: t = {}, {} biases x {} chains, {} evaluations; deepest Phi = {:.3g} at z = {:.3f}; "
                   "{:.1f} s CPU, {:.1f} s wall\n",
                   output, time, p.biases.size(), p.chains, estimate.evaluations, deepest, deepest_z,
                   estimate.cpu_seconds, estimate.wall_seconds);
        return 0;
    });
}
