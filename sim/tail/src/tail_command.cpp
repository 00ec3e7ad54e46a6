// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-tail's work (shockgas/tail/tail_command.hpp).
#include "shockgas/tail/tail_command.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

TailSamplerParameters tail_sampler_parameters(const TailRequest& request) {
    TailSamplerParameters p = request.sampler;
    p.law = velocity_law_from_string(request.law);
    p.biases = request.biases.empty() ? tail_bias_ladder(request.z_reach, request.z_step) : request.biases;
    if (request.focus < 0)
        throw InputError(fmt::format("--focus must be >= 0 (0: the whole window), got {}", request.focus));
    const double fine_bins = request.bin_width / p.fine_bin_width;
    if (!(fine_bins >= 0.5) || std::abs(fine_bins - std::round(fine_bins)) > 1e-6)
        throw InputError(fmt::format("--bin-width must be a positive multiple of the {} WHAM bins, got {}",
                                     p.fine_bin_width, request.bin_width));
    p.sites = 2 * request.half_window + 1;
    p.fine_bins_per_output_bin = std::llround(fine_bins);
    const std::int64_t reach = request.focus > 0 ? std::min(request.focus, request.half_window) : request.half_window;
    p.focus_begin = request.half_window - reach;
    p.focus_end = request.half_window + reach + 1;
    return p;
}

std::vector<double> tail_start_means(const TailRequest& request) {
    std::vector<double> start_mean;
    if (!request.biases.empty() || request.prior_start) return start_mean;
    for (double z : tail_ladder_targets(request.z_reach, request.z_step)) {
        const auto mean = tagged_cluster_instanton(z, request.time, request.half_window);
        start_mean.insert(start_mean.end(), mean.begin(), mean.end());
    }
    return start_mean;
}

TailOutcome run_tail(const TailRequest& request, const std::string& program, const TailHooks& hooks) {
    TailOutcome outcome;
    TailSamplerParameters& p = outcome.parameters;
    p = tail_sampler_parameters(request);
    h5::check_writable(request.output);
    const TaggedClusterVelocity tagged(request.half_window, request.time);
    p.start_mean = tail_start_means(request);
    // Each thread its own copy: the observable keeps scratch clusters.
    const ObservableFactory make_observable = [&tagged] {
        return WindowObservable([copy = tagged](std::span<const double> velocity) mutable { return copy(velocity); });
    };
    outcome.estimate = sample_far_tail(p, make_observable, hooks.progress);
    if (hooks.sampled) hooks.sampled();
    write_tail_estimate(request.output, program, p, outcome.estimate, request.time, request.half_window,
                        "tagged_cluster_velocity");
    return outcome;
}

DeepestDensity deepest_density(const TailEstimate& estimate) {
    DeepestDensity deepest;
    for (std::size_t i = 0; i < estimate.z.size(); ++i)
        if (estimate.density[i] > 0.0 && estimate.density[i] < deepest.density) {
            deepest.density = estimate.density[i];
            deepest.z = estimate.z[i];
        }
    return deepest;
}

std::string tail_summary(const TailRequest& request, const TailOutcome& outcome) {
    const TailEstimate& estimate = outcome.estimate;
    const DeepestDensity deepest = deepest_density(estimate);
    return fmt::format(
        "{}: t = {}, {} biases x {} chains, {} evaluations; deepest Phi = {:.3g} at z = {:.3f}; "
        "{:.1f} s CPU, {:.1f} s wall",
        request.output, request.time, outcome.parameters.biases.size(), outcome.parameters.chains, estimate.evaluations,
        deepest.density, deepest.z, estimate.cpu_seconds, estimate.wall_seconds);
}

}  // namespace shockgas
