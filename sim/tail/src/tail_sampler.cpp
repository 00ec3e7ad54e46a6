// SPDX-License-Identifier: GPL-3.0-or-later
// The far-tail sampler: biased Metropolis chains over a window's initial
// velocities, combined by WHAM (see shockgas/tail/tail_sampler.hpp, docs/far-tail.md).
#include "shockgas/tail/tail_sampler.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <limits>
#include <optional>
#include <random>
#include <thread>

#include <fmt/format.h>

#include "shockgas/model/exact_constants.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas {

namespace {

constexpr double velocity_variance = exact::uniform_initial_temperature;  // <v^2> of the uniform law on [-1, 1], kept for the Gaussian
// Exact sticky-gas constants (python/exact_ballistic.py): kappa = Var Phi (EB7)
// and the linear tail coefficient |a_1|/(2D)^(1/3) of EB9 at D = 1/3.
constexpr double exact_phi_variance = exact::sticky_gas_temperature_prefactor;
constexpr double exact_tail_linear_coefficient = 2.676;
// The autoregressive Gaussian move v' = rho v + sqrt(1 - rho^2) xi keeps the
// prior (it is reversible for it) and changes v by ~ 0.45 sigma: a small step
// for chains at large bias, where redrawing from the prior is mostly rejected.
constexpr double autoregressive_rho = 0.9;
// Below this z the bias is weak and the prior is a good start.
constexpr double instanton_z_min = 1.5;

// Platform-independent variates: top 53 bits (as generate_initial_condition),
// Gaussians by Box-Muller.
double unit_uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
double standard_normal(std::mt19937_64& engine) {
    const double u = 1.0 - unit_uniform(engine);  // (0, 1]
    const double angle = 2.0 * M_PI * unit_uniform(engine);
    return std::sqrt(-2.0 * std::log(u)) * std::cos(angle);
}

// The chains move latent variables g, i.i.d. N(0, 1/3) under the prior,
// whatever the initial law; the observable sees the velocities v = F^-1(G(g)),
// F the law's distribution function and G the latent one's. For the Gaussian
// v = g. For the uniform law on [-1, 1], F^-1(G(g)) = erf(g sqrt(3/2)): every
// latent state is a valid window, so the collective (block) moves the tail
// needs are never refused at the law's edge, as they would be if the chains
// moved the velocities themselves and rejected any move leaving [-1, 1]
// (docs/far-tail.md, "The uniform start"). The map is monotone, so the
// law of any observable is unchanged: only the chain's coordinates are.
constexpr double uniform_latent_scale = 1.2247448713915890;  // sqrt(3/2) = 1/(sqrt(2) sigma), sigma^2 = 1/3
double velocity_of_latent(VelocityLaw law, double latent) {
    return law == VelocityLaw::gaussian ? latent : std::erf(uniform_latent_scale * latent);
}
// The inverse map, for the instanton start (which is a mean in velocities).
// Velocities at or beyond the uniform law's edge (a cluster asked to move at
// |V| >= 1, which no window of this law can give) are held just inside it.
double latent_of_velocity(VelocityLaw law, double velocity) {
    if (law == VelocityLaw::gaussian) return velocity;
    constexpr double edge = 1.0 - 1e-12;
    const double target = std::clamp(velocity, -edge, edge);
    // Bisection on erf(y) = |target| in [0, 6] (erf(6) rounds to 1): 64
    // halvings reach the double next to the root, and this runs only at the start.
    const double magnitude = std::abs(target);
    double below = 0.0, above = 6.0;
    for (int i = 0; i < 64; ++i) {
        const double middle = 0.5 * (below + above);
        (std::erf(middle) < magnitude ? below : above) = middle;
    }
    const double y = 0.5 * (below + above);
    return std::copysign(y, target) / uniform_latent_scale;
}

double draw_latent(std::mt19937_64& engine) { return std::sqrt(velocity_variance) * standard_normal(engine); }
// A proposal reversible with respect to the latent prior, so Metropolis
// accepts with min(1, exp(beta (z' - z))) alone: a redraw from the prior, or
// the autoregressive step g' = rho g + sqrt(1 - rho^2) sigma xi.
double propose_latent(double current, std::mt19937_64& engine) {
    const bool redraw = unit_uniform(engine) < 0.5;
    if (redraw) return draw_latent(engine);
    return autoregressive_rho * current +
           std::sqrt((1.0 - autoregressive_rho * autoregressive_rho) * velocity_variance) * standard_normal(engine);
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
    std::vector<double> swaps_tried;     // per neighbour pair (k, k + 1)
    std::vector<double> swaps_accepted;
};

// One replica: the window's latent variables at one bias, the velocities
// they map to (velocity_of_latent), and its z.
struct Replica {
    std::vector<double> latent;
    std::vector<double> velocity;
    double z = 0.0;
};

// One Metropolis step for the weight prior(v) exp(beta z(v)). Two moves:
// Both act on the latent variables, whose prior is Gaussian for every law.
//  - one site: a proposal reversible for the prior (propose_latent()), accepted
//    with min(1, exp(beta dz));
//  - a block shift: velocities of a run of up to block_max consecutive sites
//    move together, by one delta (flat) or by delta falling linearly to 0
//    across the run (ramp), with sd ~ sigma / sqrt(length) so the prior
//    changes by O(1). The tail's optimal windows are collective (a fast
//    cluster needs the particles ahead of it to clear the way: a ramp of
//    velocities, see tagged_cluster_instanton), which single sites build
//    only slowly. Accepted with min(1, prior ratio exp(beta dz)).
bool metropolis_step(const TailSamplerParameters& p, const WindowObservable& observable, double beta,
                     Replica& replica, std::vector<double>& saved, std::mt19937_64& engine, std::int64_t& evaluations) {
    const auto focus_width = static_cast<double>(p.focus_end - p.focus_begin);
    auto pick_site = [&] {
        const bool in_focus = unit_uniform(engine) < p.focus_probability;
        return static_cast<std::size_t>(
            in_focus ? p.focus_begin + static_cast<std::int64_t>(unit_uniform(engine) * focus_width)
                     : static_cast<std::int64_t>(unit_uniform(engine) * static_cast<double>(p.sites)));
    };
    std::vector<double>& latent = replica.latent;
    double log_prior_ratio = 0.0;
    std::size_t first = 0, length = 1;
    if (p.block_probability > 0.0 && unit_uniform(engine) < p.block_probability) {
        length = 1 + static_cast<std::size_t>(unit_uniform(engine) * static_cast<double>(p.block_max));
        first = pick_site();
        length = std::min(length, latent.size() - first);
        const bool ramp = unit_uniform(engine) < 0.5;  // else flat
        const double delta =
            std::sqrt(velocity_variance / static_cast<double>(length)) * (ramp ? 1.0 : 0.5) * standard_normal(engine);
        saved.assign(latent.begin() + static_cast<std::ptrdiff_t>(first),
                     latent.begin() + static_cast<std::ptrdiff_t>(first + length));
        for (std::size_t i = first; i < first + length; ++i) {
            const double shape =
                ramp ? 1.0 - static_cast<double>(i - first) / static_cast<double>(length) : 1.0;
            const double moved = latent[i] + delta * shape;
            // Gaussian prior: ln prior(g') - ln prior(g) = -(g'^2 - g^2) / (2 sigma^2).
            log_prior_ratio -= (moved * moved - latent[i] * latent[i]) / (2.0 * velocity_variance);
            latent[i] = moved;
        }
    } else {
        first = pick_site();
        saved.assign(1, latent[first]);
        latent[first] = propose_latent(latent[first], engine);
    }
    const auto remap = [&] {
        for (std::size_t i = first; i < first + length; ++i) replica.velocity[i] = velocity_of_latent(p.law, latent[i]);
    };
    remap();
    const double proposed_z = observable(replica.velocity);
    ++evaluations;
    const double log_ratio = log_prior_ratio + beta * (proposed_z - replica.z);
    const bool accept = log_ratio >= 0.0 || unit_uniform(engine) < std::exp(log_ratio);
    if (accept) {
        replica.z = proposed_z;
    } else {
        std::copy(saved.begin(), saved.end(), latent.begin() + static_cast<std::ptrdiff_t>(first));
        remap();
    }
    return accept;
}

// One independent chain: a replica per bias, all stepped in turn, with
// replica exchange between neighbouring biases every exchange_interval steps
// (Swendsen & Wang, PRL 57, 2607 (1986); Hukushima & Nemoto, JPSJ 65, 1604
// (1996)): swapping the states of biases k and k + 1 is accepted with
// min(1, exp((beta_{k+1} - beta_k)(z_k - z_{k+1}))), which keeps every
// replica's law, and lets a state found at one bias serve the others.
ChainRecord run_chain(const TailSamplerParameters& p, const WindowObservable& observable, std::int64_t chain,
                      std::size_t fine_bins, std::int64_t& evaluations, std::atomic<std::int64_t>& steps_done) {
    std::mt19937_64 engine(realization_seed(p.seed, chain));
    const std::size_t biases = p.biases.size();
    std::vector<Replica> replicas(biases);
    const auto sites = static_cast<std::size_t>(p.sites);
    for (std::size_t k = 0; k < biases; ++k) {
        Replica& replica = replicas[k];
        replica.latent.resize(sites);
        for (double& g : replica.latent) g = draw_latent(engine);
        // Start near the bias's typical set: prior noise about the given mean,
        // taken to latent variables (the burn-in removes what the start gets wrong).
        if (!p.start_mean.empty())
            for (std::size_t i = 0; i < sites; ++i)
                replica.latent[i] += latent_of_velocity(p.law, p.start_mean[k * sites + i]);
        replica.velocity.resize(sites);
        for (std::size_t i = 0; i < sites; ++i) replica.velocity[i] = velocity_of_latent(p.law, replica.latent[i]);
        replica.z = observable(replica.velocity);
        ++evaluations;
    }
    ChainRecord record{std::vector<double>(biases * fine_bins, 0.0), std::vector<double>(biases, 0.0),
                       std::vector<double>(biases, 0.0), std::vector<double>(biases, 0.0),
                       std::vector<double>(biases, 0.0), std::vector<double>(biases, 0.0)};
    std::vector<double> saved;
    const std::int64_t interval = p.exchange_interval;
    const std::int64_t total = p.burn_in_steps + p.steps_per_bias;
    for (std::int64_t done = 0, round = 0; done < total; done += interval, ++round) {
        const std::int64_t steps = std::min(interval, total - done);
        for (std::size_t k = 0; k < biases; ++k) {
            for (std::int64_t step = 0; step < steps; ++step) {
                const bool accept =
                    metropolis_step(p, observable, p.biases[k], replicas[k], saved, engine, evaluations);
                if (done + step < p.burn_in_steps) continue;
                const double z = replicas[k].z;
                record.samples[k] += 1.0;
                record.accepted[k] += accept ? 1.0 : 0.0;
                record.sum_z[k] += z;
                const double position = (z - p.z_min) / p.fine_bin_width;
                if (position >= 0.0 && position < static_cast<double>(fine_bins))
                    record.histogram[k * fine_bins + static_cast<std::size_t>(position)] += 1.0;
            }
        }
        steps_done.fetch_add(steps * static_cast<std::int64_t>(biases), std::memory_order_relaxed);
        // Even pairs on even rounds, odd pairs on odd rounds.
        for (auto k = static_cast<std::size_t>(round % 2); k + 1 < biases; k += 2) {
            const double log_ratio = (p.biases[k + 1] - p.biases[k]) * (replicas[k].z - replicas[k + 1].z);
            record.swaps_tried[k] += 1.0;
            if (log_ratio >= 0.0 || unit_uniform(engine) < std::exp(log_ratio)) {
                std::swap(replicas[k], replicas[k + 1]);
                record.swaps_accepted[k] += 1.0;
            }
        }
    }
    return record;
}

}  // namespace


TaggedClusterVelocity::TaggedClusterVelocity(std::int64_t half_window, double time)
    : time_(time), scale_(std::cbrt(time)) {
    if (half_window < 1) throw InputError("tagged cluster: the half window must hold at least one particle");
    // The instanton starts hold one window per bias (8 bytes a site): 23
    // biases of 2·10^6 + 1 sites are 370 MB. A cluster at time t spans
    // ~ t^(2/3) particles, so 10^6 on each side would serve t ~ 10^9, far
    // beyond what the chains reach, while 10^8 would take 7.5 GB within 20 s.
    constexpr std::int64_t most_half_window = 1'000'000;
    if (half_window > most_half_window)
        throw InputError(fmt::format("tagged cluster: the half window must hold at most {} particles, got {}",
                                     most_half_window, half_window));
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

std::vector<double> tail_ladder_targets(double z_reach, double z_step) {
    std::vector<double> targets{0.0};
    for (double z = z_step; z <= z_reach + 1e-9; z += z_step) targets.push_back(z);
    return targets;
}

std::vector<double> tagged_cluster_instanton(double z, double time, std::int64_t half_window) {
    std::vector<double> mean(static_cast<std::size_t>(2 * half_window + 1), 0.0);
    if (z < instanton_z_min) return mean;
    const double velocity = z / std::cbrt(time);                      // EB8: V = z t^(-1/3)
    const double mass_unit = std::cbrt(velocity_variance * time * time);  // EB2: M* = (D t^2)^(1/3)
    // EB9's saddle: scaled mass m = 6/w^2, w = z D^(-1/3).
    const double w = z / std::cbrt(velocity_variance);
    const auto cluster = static_cast<std::int64_t>(std::max(1.0, std::round(6.0 / (w * w) * mass_unit)));
    const double ramp = velocity * time;  // the particles ahead within V t must clear the way
    for (std::int64_t offset = -half_window; offset <= half_window; ++offset) {
        double v = 0.0;
        if (offset <= 0 && offset > -cluster) v = velocity;
        if (offset > 0 && static_cast<double>(offset) < ramp) v = velocity * (1.0 - static_cast<double>(offset) / ramp);
        mean[static_cast<std::size_t>(offset + half_window)] = v;
    }
    return mean;
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
    TailSamplerParameters one_thread = p;
    one_thread.threads = 1;
    return sample_far_tail(one_thread, ObservableFactory([&observable] { return observable; }));
}

TailEstimate sample_far_tail(const TailSamplerParameters& p, const ObservableFactory& make_observable,
                             const TailProgress& progress) {
    if (p.biases.empty() || p.biases.front() != 0.0)
        throw InputError("tail sampler: the bias ladder must start at 0 (plain sampling fixes the normalization)");
    if (!std::is_sorted(p.biases.begin(), p.biases.end())) throw InputError("tail sampler: biases must ascend");
    if (!std::all_of(p.biases.begin(), p.biases.end(), [](double beta) { return std::isfinite(beta); }))
        throw InputError("tail sampler: biases must be finite");
    for (const auto& [name, probability] :
         {std::pair<const char*, double>{"focus", p.focus_probability}, {"block", p.block_probability}})
        if (!(probability >= 0.0 && probability <= 1.0))
            throw InputError(fmt::format("tail sampler: the {} probability must lie in [0, 1], got {}", name, probability));
    if (p.exchange_interval < 1)
        throw InputError(fmt::format("tail sampler: the exchange interval must be >= 1 step, got {}", p.exchange_interval));
    if (p.chains < 2) throw InputError("tail sampler: need >= 2 chains for error bars");
    if (p.threads < 0) throw InputError(fmt::format("tail sampler: threads must be >= 0, got {}", p.threads));
    if (p.sites < 1 || p.focus_begin < 0 || p.focus_end > p.sites || p.focus_end <= p.focus_begin)
        throw InputError("tail sampler: the focus range must lie inside the window");
    if (p.steps_per_bias < 1) throw InputError("tail sampler: need >= 1 step per bias (--steps-per-bias)");
    if (p.burn_in_steps < 0) throw InputError("tail sampler: --burn-in must be >= 0");
    if (!p.start_mean.empty() && p.start_mean.size() != p.biases.size() * static_cast<std::size_t>(p.sites))
        throw InputError("tail sampler: start_mean must hold one window per bias");
    if (p.block_probability > 0.0 && p.block_max < 1) throw InputError("tail sampler: block shifts need block_max >= 1");
    if (!(p.z_max > p.z_min) || !(p.fine_bin_width > 0.0) || p.fine_bins_per_output_bin < 1)
        throw InputError("tail sampler: bad histogram range or bin width");
    const auto group = static_cast<std::size_t>(p.fine_bins_per_output_bin);
    const auto output_bins = static_cast<std::size_t>(
        std::ceil((p.z_max - p.z_min) / (p.fine_bin_width * static_cast<double>(group)) - 1e-9));
    const std::size_t fine_bins = output_bins * group;
    const std::size_t biases = p.biases.size();
    const auto chains = static_cast<std::size_t>(p.chains);

    TailEstimate estimate;
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(); };
    // The chains, each by whichever thread takes it next; each record lands in
    // its chain's slot, so the combination below sees them in chain order.
    std::vector<ChainRecord> records(chains);
    std::vector<std::int64_t> evaluations(chains, 0);
    std::atomic<std::size_t> next_chain{0};
    std::atomic<std::int64_t> steps_done{0};
    std::atomic<std::size_t> threads_done{0};
    const auto hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const auto threads = static_cast<std::size_t>(std::clamp(p.threads > 0 ? p.threads : hardware, 1,
                                                             static_cast<int>(chains)));
    std::vector<std::exception_ptr> failures(threads);
    {
        std::vector<std::jthread> workers;
        for (std::size_t w = 0; w < threads; ++w)
            workers.emplace_back([&, w] {
                try {
                    const WindowObservable observable = make_observable();
                    for (std::size_t c; (c = next_chain.fetch_add(1)) < chains;)
                        records[c] = run_chain(p, observable, static_cast<std::int64_t>(c), fine_bins,
                                               evaluations[c], steps_done);
                } catch (...) {
                    failures[w] = std::current_exception();
                    next_chain.store(chains);  // the others stop after their current chain
                }
                threads_done.fetch_add(1);
            });
        const double total_steps = static_cast<double>(chains) * static_cast<double>(biases) *
                                   static_cast<double>(p.burn_in_steps + p.steps_per_bias);
        double last_report = 0.0;
        while (threads_done.load() < threads) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            if (progress && threads_done.load() < threads && elapsed() >= last_report + 0.5) {
                last_report = elapsed();
                progress(static_cast<double>(steps_done.load(std::memory_order_relaxed)) / total_steps, last_report);
            }
        }
    }
    for (const auto& failure : failures)
        if (failure) std::rethrow_exception(failure);
    for (const std::int64_t e : evaluations) estimate.evaluations += e;

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
    estimate.swap_acceptance.assign(biases, 0.0);
    for (std::size_t k = 0; k + 1 < biases; ++k) {
        double tried = 0.0, accepted = 0.0;
        for (std::size_t c = 0; c < chains; ++c) {
            tried += records[c].swaps_tried[k];
            accepted += records[c].swaps_accepted[k];
        }
        estimate.swap_acceptance[k] = tried > 0.0 ? accepted / tried : 0.0;
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
    estimate.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    estimate.wall_seconds = elapsed();
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
    root.set_attribute("block_probability", p.block_probability);
    root.set_attribute("block_max", p.block_max);
    root.set_attribute("exchange_interval", p.exchange_interval);
    root.set_attribute("instanton_start", static_cast<std::int64_t>(!p.start_mean.empty()));
    root.set_attribute("z_min", p.z_min);
    root.set_attribute("z_max", p.z_max);
    root.set_attribute("fine_bin_width", p.fine_bin_width);
    root.set_attribute("fine_bins_per_output_bin", p.fine_bins_per_output_bin);
    root.set_attribute("evaluations", e.evaluations);
    root.set_attribute("wham_iterations", e.wham_iterations);
    root.set_attribute("cpu_seconds", e.cpu_seconds);
    root.set_attribute("wall_seconds", e.wall_seconds);
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
    pieces.write("swap_acceptance", e.swap_acceptance);
    file.commit();
}

}  // namespace shockgas
