// The far-tail sampler: biased Metropolis chains over a window's initial
// velocities, combined by WHAM (see shockgas/tail_sampler.hpp, docs/far-tail.md).
#include "shockgas/tail_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include <fmt/format.h>

#include "shockgas/h5.hpp"
#include "shockgas/parameters.hpp"
#include "shockgas/provenance.hpp"
#include "shockgas/state.hpp"

namespace shockgas {

namespace {

constexpr double velocity_variance = 1.0 / 3.0;  // <v^2> of the uniform law on [-1, 1], kept for the Gaussian
// Exact sticky-gas constants (python/exact_ballistic.py): kappa = Var Phi (EB7)
// and the linear tail coefficient |a_1|/(2D)^(1/3) of EB9 at D = 1/3.
constexpr double exact_phi_variance = 0.2128532;
constexpr double exact_tail_linear_coefficient = 2.676;
// The autoregressive Gaussian move v' = rho v + sqrt(1 - rho^2) xi keeps the
// prior (it is reversible for it) and changes v by ~ 0.45 sigma: a small step
// for chains at large bias, where redrawing from the prior is mostly rejected.
constexpr double autoregressive_rho = 0.9;
constexpr double uniform_step = 0.2;  // reflected uniform step on [-1, 1] (symmetric: keeps the uniform law)

// Platform-independent variates: top 53 bits (as generate_initial_condition),
// Gaussians by Box-Muller.
double unit_uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
double standard_normal(std::mt19937_64& engine) {
    const double u = 1.0 - unit_uniform(engine);  // (0, 1]
    const double angle = 2.0 * M_PI * unit_uniform(engine);
    return std::sqrt(-2.0 * std::log(u)) * std::cos(angle);
}
double draw_from_prior(VelocityLaw law, std::mt19937_64& engine) {
    if (law == VelocityLaw::gaussian) return std::sqrt(velocity_variance) * standard_normal(engine);
    return 2.0 * unit_uniform(engine) - 1.0;
}
// A proposal reversible with respect to the prior, so Metropolis accepts with
// min(1, exp(beta (z' - z))) alone.
double propose(VelocityLaw law, double current, std::mt19937_64& engine) {
    const bool redraw = unit_uniform(engine) < 0.5;
    if (redraw) return draw_from_prior(law, engine);
    if (law == VelocityLaw::gaussian)
        return autoregressive_rho * current +
               std::sqrt((1.0 - autoregressive_rho * autoregressive_rho) * velocity_variance) * standard_normal(engine);
    double moved = current + uniform_step * (unit_uniform(engine) - 0.5);
    if (moved > 1.0) moved = 2.0 - moved;
    if (moved < -1.0) moved = -2.0 - moved;
    return moved;
}

double log_sum_exp(std::span<const double> values) {
    double largest = -std::numeric_limits<double>::infinity();
    for (double v : values) largest = std::max(largest, v);
    if (!std::isfinite(largest)) return largest;
    double sum = 0.0;
    for (double v : values) sum += std::exp(v - largest);
    return largest + std::log(sum);
}

struct ChainRecord {
    std::vector<double> histogram;  // biases x fine bins
    std::vector<double> samples;    // per bias (in range or not)
    std::vector<double> accepted;
    std::vector<double> sum_z;
};

ChainRecord run_chain(const TailSamplerParameters& p, const WindowObservable& observable, std::int64_t chain,
                      std::size_t fine_bins, std::int64_t& evaluations) {
    std::mt19937_64 engine(realization_seed(p.seed, chain));
    std::vector<double> velocity(static_cast<std::size_t>(p.sites));
    for (double& v : velocity) v = draw_from_prior(p.law, engine);
    double z = observable(velocity);
    ++evaluations;
    const std::size_t biases = p.biases.size();
    ChainRecord record{std::vector<double>(biases * fine_bins, 0.0), std::vector<double>(biases, 0.0),
                       std::vector<double>(biases, 0.0), std::vector<double>(biases, 0.0)};
    const auto focus_width = static_cast<double>(p.focus_end - p.focus_begin);
    for (std::size_t k = 0; k < biases; ++k) {
        const double beta = p.biases[k];
        for (std::int64_t step = 0; step < p.burn_in_steps + p.steps_per_bias; ++step) {
            const bool in_focus = unit_uniform(engine) < p.focus_probability;
            const auto site = static_cast<std::size_t>(
                in_focus ? p.focus_begin + static_cast<std::int64_t>(unit_uniform(engine) * focus_width)
                         : static_cast<std::int64_t>(unit_uniform(engine) * static_cast<double>(p.sites)));
            const double old_velocity = velocity[site];
            velocity[site] = propose(p.law, old_velocity, engine);
            const double proposed_z = observable(velocity);
            ++evaluations;
            // Metropolis for the weight prior(v) exp(beta z(v)); the proposal keeps the prior.
            const double log_ratio = beta * (proposed_z - z);
            const bool accept = log_ratio >= 0.0 || unit_uniform(engine) < std::exp(log_ratio);
            if (accept)
                z = proposed_z;
            else
                velocity[site] = old_velocity;
            if (step < p.burn_in_steps) continue;
            record.samples[k] += 1.0;
            record.accepted[k] += accept ? 1.0 : 0.0;
            record.sum_z[k] += z;
            const double position = (z - p.z_min) / p.fine_bin_width;
            if (position >= 0.0 && position < static_cast<double>(fine_bins))
                record.histogram[k * fine_bins + static_cast<std::size_t>(position)] += 1.0;
        }
    }
    return record;
}

}  // namespace


TaggedClusterVelocity::TaggedClusterVelocity(std::int64_t half_window, double time)
    : time_(time), scale_(std::cbrt(time)) {
    if (half_window < 1) throw InputError("tagged cluster: the half window must hold at least one particle");
    if (!(time > 0.0) || !std::isfinite(time)) throw InputError("tagged cluster: time must be positive and finite");
    position_.resize(static_cast<std::size_t>(2 * half_window + 1));
    for (std::size_t i = 0; i < position_.size(); ++i)
        position_[i] = static_cast<double>(static_cast<std::int64_t>(i) - half_window);
}

double TaggedClusterVelocity::operator()(std::span<const double> velocity) {
    sticky_clusters_on_line(position_, velocity, time_, clusters_);
    const LineCluster& holder = cluster_holding(clusters_, tagged());
    last_mass_ = holder.mass;
    return holder.velocity() * scale_;  // EB8: z = V t^(1/3)
}

std::vector<double> tail_bias_ladder(double z_reach, double z_step) {
    if (!(z_step > 0.0) || !(z_reach >= z_step)) throw InputError("bias ladder: need 0 < step <= reach");
    std::vector<double> biases{0.0};
    for (double z = z_step; z <= z_reach + 1e-9; z += z_step)
        biases.push_back(std::max(z / exact_phi_variance, 1.5 * z * z + exact_tail_linear_coefficient));
    return biases;
}

std::vector<double> wham_log_probability(std::span<const double> histograms, std::span<const double> samples,
                                         std::span<const double> biases, std::span<const double> bin_centres,
                                         std::vector<double>* log_partition, std::int64_t* iterations) {
    const std::size_t chains = biases.size(), bins = bin_centres.size();
    constexpr double minus_infinity = -std::numeric_limits<double>::infinity();
    std::vector<double> log_counts(bins, minus_infinity);
    for (std::size_t b = 0; b < bins; ++b) {
        double total = 0.0;
        for (std::size_t k = 0; k < chains; ++k) total += histograms[k * bins + b];
        if (total > 0.0) log_counts[b] = std::log(total);
    }
    std::vector<double> log_samples(chains);
    for (std::size_t k = 0; k < chains; ++k) log_samples[k] = std::log(std::max(samples[k], 1.0));
    std::vector<double> free_energy(chains, 0.0), log_p(bins, minus_infinity), terms(std::max(chains, bins));
    // Start from the stitched ladder, so that the iteration (whose slow mode
    // is a tilt across many pieces) starts near its fixed point: chain k's
    // own reweighting gives ln P_b = ln h_kb - beta_k z_b + F_k - ln N_k; F_0
    // is set by chain 0 alone, F_k by matching chain k - 1 on the bins both
    // visit (weighted by the smaller count, the noisier of the two).
    for (std::size_t k = 0; k < chains; ++k) {
        if (k == 0) {
            std::size_t used = 0;
            for (std::size_t b = 0; b < bins; ++b)
                if (histograms[b] > 0.0) terms[used++] = std::log(histograms[b]);
            free_energy[0] = used > 0 ? log_samples[0] - log_sum_exp(std::span(terms.data(), used)) : 0.0;
            continue;
        }
        double weighted_shift = 0.0, weight = 0.0;
        for (std::size_t b = 0; b < bins; ++b) {
            const double below = histograms[(k - 1) * bins + b], here = histograms[k * bins + b];
            if (below <= 0.0 || here <= 0.0) continue;
            const double log_p_below =
                std::log(below) - biases[k - 1] * bin_centres[b] + free_energy[k - 1] - log_samples[k - 1];
            const double log_p_here_without_f = std::log(here) - biases[k] * bin_centres[b] - log_samples[k];
            const double w = std::min(below, here);
            weighted_shift += w * (log_p_below - log_p_here_without_f);
            weight += w;
        }
        free_energy[k] = weight > 0.0 ? weighted_shift / weight : free_energy[k - 1];
    }
    std::int64_t iteration = 0;
    for (; iteration < 100000; ++iteration) {
        for (std::size_t b = 0; b < bins; ++b) {
            if (log_counts[b] == minus_infinity) continue;
            for (std::size_t k = 0; k < chains; ++k)
                terms[k] = log_samples[k] + biases[k] * bin_centres[b] - free_energy[k];
            log_p[b] = log_counts[b] - log_sum_exp(std::span(terms.data(), chains));
        }
        const double norm = log_sum_exp(log_p);
        for (double& v : log_p) v -= norm;
        double change = 0.0;
        for (std::size_t k = 0; k < chains; ++k) {
            for (std::size_t b = 0; b < bins; ++b) terms[b] = log_p[b] + biases[k] * bin_centres[b];
            const double updated = log_sum_exp(std::span(terms.data(), bins));
            change = std::max(change, std::abs(updated - free_energy[k]));
            free_energy[k] = updated;
        }
        if (change < 1e-10) break;
    }
    if (log_partition != nullptr) *log_partition = free_energy;
    if (iterations != nullptr) *iterations = iteration + 1;
    return log_p;
}

TailEstimate sample_far_tail(const TailSamplerParameters& p, const WindowObservable& observable) {
    if (p.biases.empty() || p.biases.front() != 0.0)
        throw InputError("tail sampler: the bias ladder must start at 0 (plain sampling fixes the normalization)");
    if (!std::is_sorted(p.biases.begin(), p.biases.end())) throw InputError("tail sampler: biases must ascend");
    if (p.chains < 2) throw InputError("tail sampler: need >= 2 chains for error bars");
    if (p.sites < 1 || p.focus_begin < 0 || p.focus_end > p.sites || p.focus_end <= p.focus_begin)
        throw InputError("tail sampler: the focus range must lie inside the window");
    if (p.steps_per_bias < 1 || p.burn_in_steps < 0) throw InputError("tail sampler: need >= 1 step per bias");
    if (!(p.z_max > p.z_min) || !(p.fine_bin_width > 0.0) || p.fine_bins_per_output_bin < 1)
        throw InputError("tail sampler: bad histogram range or bin width");
    const auto group = static_cast<std::size_t>(p.fine_bins_per_output_bin);
    const auto output_bins = static_cast<std::size_t>(
        std::ceil((p.z_max - p.z_min) / (p.fine_bin_width * static_cast<double>(group)) - 1e-9));
    const std::size_t fine_bins = output_bins * group;
    const std::size_t biases = p.biases.size();
    const auto chains = static_cast<std::size_t>(p.chains);

    TailEstimate estimate;
    std::vector<ChainRecord> records;
    for (std::size_t c = 0; c < chains; ++c)
        records.push_back(run_chain(p, observable, static_cast<std::int64_t>(c), fine_bins, estimate.evaluations));

    std::vector<double> centres(fine_bins);
    for (std::size_t b = 0; b < fine_bins; ++b)
        centres[b] = p.z_min + (static_cast<double>(b) + 0.5) * p.fine_bin_width;
    const double output_width = p.fine_bin_width * static_cast<double>(group);
    // ln Phi on the output bins from the chains not left out.
    auto combine = [&](std::optional<std::size_t> left_out, std::vector<double>* log_partition,
                       std::int64_t* iterations) {
        std::vector<double> histogram(biases * fine_bins, 0.0), samples(biases, 0.0);
        for (std::size_t c = 0; c < chains; ++c) {
            if (left_out && *left_out == c) continue;
            for (std::size_t i = 0; i < histogram.size(); ++i) histogram[i] += records[c].histogram[i];
            for (std::size_t k = 0; k < biases; ++k) samples[k] += records[c].samples[k];
        }
        const std::vector<double> log_p =
            wham_log_probability(histogram, samples, p.biases, centres, log_partition, iterations);
        std::vector<double> log_phi(output_bins);
        for (std::size_t o = 0; o < output_bins; ++o)
            log_phi[o] = log_sum_exp(std::span(log_p).subspan(o * group, group)) - std::log(output_width);
        return log_phi;
    };
    estimate.log_density = combine(std::nullopt, &estimate.log_partition, &estimate.wham_iterations);
    estimate.leave_one_out.resize(chains * output_bins);
    for (std::size_t c = 0; c < chains; ++c) {
        const std::vector<double> partial = combine(c, nullptr, nullptr);
        std::copy(partial.begin(), partial.end(), estimate.leave_one_out.begin() + static_cast<std::ptrdiff_t>(c * output_bins));
    }
    // Delete-one-chain jackknife of ln Phi, bin by bin.
    const double n = static_cast<double>(chains);
    estimate.z.resize(output_bins);
    estimate.density.resize(output_bins);
    estimate.density_sigma.resize(output_bins);
    estimate.log_density_sigma.resize(output_bins);
    estimate.samples.assign(output_bins, 0.0);
    for (std::size_t o = 0; o < output_bins; ++o) {
        estimate.z[o] = p.z_min + (static_cast<double>(o) + 0.5) * output_width;
        double mean = 0.0, square = 0.0;
        bool complete = true;
        for (std::size_t c = 0; c < chains; ++c) {
            const double v = estimate.leave_one_out[c * output_bins + o];
            complete = complete && std::isfinite(v);
            mean += v;
        }
        mean /= n;
        for (std::size_t c = 0; c < chains; ++c) {
            const double d = estimate.leave_one_out[c * output_bins + o] - mean;
            square += d * d;
        }
        const double log_sigma = complete ? std::sqrt((n - 1.0) / n * square) : std::numeric_limits<double>::quiet_NaN();
        estimate.log_density_sigma[o] = log_sigma;
        estimate.density[o] = std::exp(estimate.log_density[o]);
        estimate.density_sigma[o] = estimate.density[o] * log_sigma;  // first order in sigma(ln Phi)
        for (std::size_t c = 0; c < chains; ++c)
            for (std::size_t k = 0; k < biases; ++k)
                for (std::size_t f = o * group; f < (o + 1) * group; ++f)
                    estimate.samples[o] += records[c].histogram[k * fine_bins + f];
    }
    // Per-bias diagnostics, and the overlap of neighbouring pieces.
    estimate.biases = p.biases;
    estimate.chains = p.chains;
    estimate.acceptance.assign(biases, 0.0);
    estimate.mean_z.assign(biases, 0.0);
    std::vector<double> pooled(biases * fine_bins, 0.0), pooled_samples(biases, 0.0);
    for (std::size_t k = 0; k < biases; ++k) {
        double accepted = 0.0, sum_z = 0.0;
        for (std::size_t c = 0; c < chains; ++c) {
            accepted += records[c].accepted[k];
            sum_z += records[c].sum_z[k];
            pooled_samples[k] += records[c].samples[k];
            for (std::size_t b = 0; b < fine_bins; ++b) pooled[k * fine_bins + b] += records[c].histogram[k * fine_bins + b];
        }
        estimate.acceptance[k] = accepted / pooled_samples[k];
        estimate.mean_z[k] = sum_z / pooled_samples[k];
    }
    estimate.overlap_with_next.assign(biases, 0.0);
    for (std::size_t k = 0; k + 1 < biases; ++k) {
        double overlap = 0.0;
        for (std::size_t o = 0; o < output_bins; ++o) {
            double here = 0.0, next = 0.0;
            for (std::size_t f = o * group; f < (o + 1) * group; ++f) {
                here += pooled[k * fine_bins + f];
                next += pooled[(k + 1) * fine_bins + f];
            }
            overlap += std::min(here / pooled_samples[k], next / pooled_samples[k + 1]);
        }
        estimate.overlap_with_next[k] = overlap;
    }
    return estimate;
}

void write_tail_estimate(const std::string& path, const std::string& program, const TailSamplerParameters& p,
                         const TailEstimate& e, double time, std::int64_t half_window,
                         const std::string& observable_name) {
    h5::AtomicFile file(path);
    h5::Group root = file.root();
    write_provenance(root, program);
    root.set_attribute("kind", "far_tail");
    root.set_attribute("observable", observable_name);
    root.set_attribute("time", time);
    root.set_attribute("half_window", half_window);
    root.set_attribute("velocity_law", to_string(p.law));
    root.set_attribute("velocity_variance", velocity_variance);
    root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
    root.set_attribute("chains", p.chains);
    root.set_attribute("steps_per_bias", p.steps_per_bias);
    root.set_attribute("burn_in_steps", p.burn_in_steps);
    root.set_attribute("focus_begin", p.focus_begin);
    root.set_attribute("focus_end", p.focus_end);
    root.set_attribute("focus_probability", p.focus_probability);
    root.set_attribute("z_min", p.z_min);
    root.set_attribute("z_max", p.z_max);
    root.set_attribute("fine_bin_width", p.fine_bin_width);
    root.set_attribute("fine_bins_per_output_bin", p.fine_bins_per_output_bin);
    root.set_attribute("evaluations", e.evaluations);
    root.set_attribute("wham_iterations", e.wham_iterations);
    root.write("z", e.z);
    root.write("phi", e.density);
    root.write("phi_sigma", e.density_sigma);
    root.write("log_phi", e.log_density);
    root.write("log_phi_sigma", e.log_density_sigma);
    root.write("samples", e.samples);
    root.write("log_phi_leave_one_chain_out", e.leave_one_out,
               {static_cast<hsize_t>(e.chains), static_cast<hsize_t>(e.z.size())});
    h5::Group pieces = root.create_group("pieces");
    pieces.write("bias", e.biases);
    pieces.write("acceptance", e.acceptance);
    pieces.write("mean_z", e.mean_z);
    pieces.write("log_partition", e.log_partition);
    pieces.write("overlap_with_next", e.overlap_with_next);
    file.commit();
}

}  // namespace shockgas
