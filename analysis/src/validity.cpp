// SPDX-License-Identifier: GPL-3.0-or-later
// The validity map of the threshold delta (shockgas/analysis/validity.hpp).
#include "shockgas/analysis/validity.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <tuple>

#include <fmt/format.h>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/model/exact_constants.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas::analysis {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// (t/a)^(2/3), t in units of the initial spacing a = L/N over the velocity
// unit: x -> lambda x, t -> lambda t is an exact symmetry of the model, so
// lengths scale with a, the sticky gas's cluster spacing is a (t/a)^(2/3) / nu
// and its T is kappa (t/a)^(-2/3).
double two_thirds_power_of_scaled_time(double time, double ring_length, std::int64_t particles) {
    const double scaled = time / (ring_length / static_cast<double>(particles));
    return std::cbrt(scaled * scaled);
}

// The gap from entry i to the next in ring order (positions in [0, L) from the
// smallest first_particle, so the last entry's gap wraps). A gap that rounding
// made slightly negative (two particles in contact) is 0, not nearly L.
double gap_after(const ClusterState& state, std::size_t i, double ring_length) {
    const std::size_t next = (i + 1) % state.size();
    double gap = state.position[next] - state.position[i];
    if (gap < -0.5 * ring_length) gap += ring_length;
    if (next == 0 && gap <= 0.0 && state.size() > 1) gap += ring_length;
    return std::max(gap, 0.0);
}

double cluster_gap_cut(double time, double ring_length, std::int64_t particles, const ValidityRule& rule) {
    const double spacing = ring_length / static_cast<double>(particles);
    return rule.cluster_gap_fraction * spacing * two_thirds_power_of_scaled_time(time, ring_length, particles) /
           sticky_gas_cluster_prefactor;
}

// The history table of one observable: R rows of the given times, NaN where a
// realization has no value. Filled directly, not through TemperatureHistory::from,
// which keeps only the times where every value is a positive T: an observable
// may be 0 (the sticky gas's fragmentation rate).
TemperatureHistory table(const std::vector<double>& times, std::int64_t realizations) {
    TemperatureHistory history;
    history.time = times;
    history.realizations = static_cast<std::size_t>(realizations);
    history.temperature.assign(history.realizations * times.size(), not_a_number);
    return history;
}

TemperatureHistory without_realization(const TemperatureHistory& history, std::size_t left_out) {
    TemperatureHistory out = table(history.time, static_cast<std::int64_t>(history.realizations - 1));
    std::size_t row = 0;
    for (std::size_t r = 0; r < history.realizations; ++r) {
        if (r == left_out) continue;
        for (std::size_t k = 0; k < history.time.size(); ++k)
            out.temperature[row * history.time.size() + k] = history.at(r, k);
        ++row;
    }
    return out;
}

struct Band {
    Deviation mode;
    double k_sigma, floor;
};

Band band_of(const std::string& observable, const std::string& criterion, const ValidityRule& rule) {
    // Relative deviations, X / X_ref - 1, except for the fragmentation rate,
    // which is 0 in the sticky gas: its bands are absolute rates (a fraction of
    // the clusters splitting per unit ln t).
    const Deviation mode = observable == "fragmentation_rate" ? Deviation::absolute : Deviation::relative;
    if (criterion == "3sigma") return {mode, rule.k_sigma, 0.0};
    if (criterion == "1percent") return {mode, 2.0, 0.01};
    if (criterion == "5percent") return {mode, 2.0, 0.05};
    throw InputError(fmt::format("no criterion '{}' for {} (3sigma, 1percent or 5percent)", criterion, observable));
}

const std::vector<std::string>& criteria() {
    static const std::vector<std::string> names = {"3sigma", "1percent", "5percent"};
    return names;
}

// The start of the final stretch outside the band (+inf: inside at the last
// time), provided the observable had joined the sticky gas before it: inside the
// band at two consecutive sample times, so that one noisy sample that happens
// to fall inside does not count as joining. NaN: it never joined. Outside
// means |deviation| > floor + k_sigma sigma: beyond 3 sigma (floor 0), or
// beyond the 1 % or 5 % band by 2 sigma, so that noise alone (the kurtosis of
// a few realizations scatters by 5 % at late times) is not a departure.
double departure_time(const TemperatureHistory& run, const TemperatureHistory& reference, const Band& band) {
    const TemperatureComparison c =
        compare_histories(run, reference, Realizations::paired, band.mode, band.k_sigma, band.floor);
    auto outside = [&](std::size_t k) {
        const double sigma = std::isnan(c.relative_sigma[k]) ? 0.0 : c.relative_sigma[k];
        return std::abs(c.relative_deviation[k]) > band.floor + band.k_sigma * sigma;
    };
    double departure = infinity;
    for (std::size_t k = c.time.size(); k-- > 0;) {
        if (!outside(k)) break;
        departure = c.time[k];
    }
    bool joined = false;
    for (std::size_t k = 0; k + 1 < c.time.size() && !joined; ++k)
        joined = !outside(k) && !outside(k + 1) && c.time[k + 1] < departure;
    if (std::isinf(departure)) return departure;
    return joined ? departure : not_a_number;
}

}  // namespace

const std::vector<std::string>& validity_observables() {
    static const std::vector<std::string> names = {"temperature",        "kurtosis",           "cluster_density",
                                                   "small_gap_fraction", "structure_function", "fragmentation_rate"};
    return names;
}

std::vector<std::size_t> cluster_starts(const ClusterState& state, double ring_length, std::int64_t particles,
                                        const ValidityRule& rule) {
    const std::size_t n = state.size();
    const double cut = cluster_gap_cut(state.time, ring_length, particles, rule);
    std::vector<std::size_t> starts;
    if (n == 0) return starts;
    if (gap_after(state, n - 1, ring_length) >= cut) starts.push_back(0);
    for (std::size_t i = 0; i + 1 < n; ++i)
        if (gap_after(state, i, ring_length) >= cut) starts.push_back(i + 1);
    if (starts.empty()) starts.push_back(0);
    return starts;
}

SnapshotObservables snapshot_observables(const ClusterState& state, double ring_length, std::int64_t particles,
                                         const ValidityRule& rule) {
    SnapshotObservables out;
    const std::size_t n = state.size();
    const double t23 = two_thirds_power_of_scaled_time(state.time, ring_length, particles);
    // Kurtosis of the mass-weighted velocity distribution about its mean (Eq. 4's Phi).
    double mass = 0.0, momentum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        mass += state.mass[i];
        momentum += state.mass[i] * state.lab_velocity(i);
    }
    const double mean = momentum / mass;
    double second = 0.0, fourth = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double u2 = std::pow(state.lab_velocity(i) - mean, 2.0);
        second += state.mass[i] * u2;
        fourth += state.mass[i] * u2 * u2;
    }
    second /= mass;
    fourth /= mass;
    out.kurtosis = fourth / (second * second);
    // Clusters and the empty gaps between them.
    const std::vector<std::size_t> starts = cluster_starts(state, ring_length, particles, rule);
    const std::size_t clusters = starts.size();
    out.cluster_density =
        static_cast<double>(clusters) / static_cast<double>(particles) * t23 / sticky_gas_cluster_prefactor;
    std::vector<double> gaps;
    for (std::size_t c = 0; c < clusters; ++c) {
        const std::size_t next_start = starts[(c + 1) % clusters];
        const std::size_t last = (next_start + n - 1) % n;  // the cluster's last entry
        gaps.push_back(clusters == 1 ? ring_length : gap_after(state, last, ring_length));
    }
    double gap_sum = 0.0;
    for (const double g : gaps) gap_sum += g;
    const double short_gap = rule.small_gap_fraction * gap_sum / static_cast<double>(clusters);
    out.small_gap_fraction =
        static_cast<double>(std::count_if(gaps.begin(), gaps.end(), [&](double g) { return g < short_gap; })) /
        static_cast<double>(clusters);
    // S(k) = |sum_j m_j exp(i k x_j)|^2 / N at the ring's wavenumber k = 2 pi m / L
    // nearest to structure_wavenumber / (a (t/a)^(2/3)).
    const double spacing = ring_length / static_cast<double>(particles);
    const double wanted = rule.structure_wavenumber / (spacing * t23);
    const double mode = std::max(1.0, std::round(wanted * ring_length / (2.0 * std::numbers::pi)));
    const double k = 2.0 * std::numbers::pi * mode / ring_length;
    std::complex<double> sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += state.mass[i] * std::polar(1.0, k * state.position[i]);
    out.structure_function = std::norm(sum) / static_cast<double>(particles) / t23;
    return out;
}

double fragmentation_rate(const ClusterState& earlier, const ClusterState& later, double ring_length,
                          std::int64_t particles, const ValidityRule& rule) {
    const auto n = static_cast<std::size_t>(particles);
    // Where the later state's clusters begin, by particle (ring-order label),
    // as a prefix count so that any label range is checked at once.
    std::vector<std::size_t> begins(n + 1, 0);
    for (const std::size_t j : cluster_starts(later, ring_length, particles, rule))
        begins[static_cast<std::size_t>(later.first_particle[j]) + 1] = 1;
    for (std::size_t i = 0; i < n; ++i) begins[i + 1] += begins[i];
    auto starts_in = [&](std::size_t from, std::size_t to) {  // labels in [from, to), to <= n
        return begins[to] - begins[from];
    };
    const std::vector<std::size_t> starts = cluster_starts(earlier, ring_length, particles, rule);
    const std::size_t clusters = starts.size();
    std::size_t split = 0;
    for (std::size_t c = 0; c < clusters; ++c) {
        const std::size_t begin = starts[c], end = c + 1 < clusters ? starts[c + 1] : earlier.size();
        double mass = 0.0;
        for (std::size_t i = begin; i < end; ++i) mass += earlier.mass[i];
        // The wrapping cluster (its entries at the end and the start of the list) is
        // the last one when entry 0 is not a start; its mass includes the head.
        if (c + 1 == clusters && starts.front() != 0)
            for (std::size_t i = 0; i < starts.front(); ++i) mass += earlier.mass[i];
        const auto first = static_cast<std::size_t>(earlier.first_particle[begin]);
        const auto size = static_cast<std::size_t>(std::llround(mass));
        if (size <= 1) continue;
        // Labels first+1 .. first+size-1 (mod N): a later cluster beginning there splits it.
        const std::size_t last = first + size;  // exclusive, may pass N
        const std::size_t inside = last <= n ? starts_in(first + 1, last)
                                             : starts_in(first + 1, n) + starts_in(0, last - n);
        if (inside > 0) ++split;
    }
    return static_cast<double>(split) / static_cast<double>(clusters) / std::log(later.time / earlier.time);
}

std::vector<ObservableHistory> observable_histories(const std::string& run_path, const ValidityRule& rule) {
    const OutputFile file = read_output(run_path);
    const EnsembleResult& result = file.result;
    const std::int64_t particles = file.parameters.particles;
    const double ring_length = file.parameters.effective_ring_length();
    const std::int64_t realizations = result.realizations;
    std::vector<ObservableHistory> out;
    // T t^(2/3) / kappa at every sample time t > 0 (Eq. 3's middle regime at r = 0).
    {
        std::vector<double> times;
        std::vector<std::size_t> columns;
        for (std::size_t k = 0; k < result.times.size(); ++k)
            if (result.times[k] > 0.0) {
                times.push_back(result.times[k]);
                columns.push_back(k);
            }
        TemperatureHistory history = table(times, realizations);
        for (std::int64_t r = 0; r < realizations; ++r)
            for (std::size_t j = 0; j < times.size(); ++j)
                history.temperature[static_cast<std::size_t>(r) * times.size() + j] =
                    result.temperature[static_cast<std::size_t>(r) * result.times.size() + columns[j]] *
                    two_thirds_power_of_scaled_time(times[j], ring_length, particles) /
                    exact::sticky_gas_temperature_prefactor;
        out.push_back({"temperature", std::move(history)});
    }
    // The snapshots, by realization and time.
    std::vector<double> times;
    for (const auto& snapshot : result.snapshots) times.push_back(snapshot.state.time);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    if (times.size() < 2)
        throw InputError(fmt::format("'{}' has {} snapshot time(s): the validity map needs snapshots at two times or "
                                     "more (--snapshot-times)",
                                     run_path, times.size()));
    std::map<std::pair<std::int64_t, double>, const ClusterState*> states;
    for (const auto& snapshot : result.snapshots) states[{snapshot.realization, snapshot.state.time}] = &snapshot.state;
    std::vector<double> fragment_times(times.begin(), times.end() - 1);
    TemperatureHistory kurtosis = table(times, realizations), density = table(times, realizations),
                       small_gaps = table(times, realizations), structure = table(times, realizations),
                       fragmentation = table(fragment_times, realizations);
    for (std::int64_t r = 0; r < realizations; ++r)
        for (std::size_t j = 0; j < times.size(); ++j) {
            const auto found = states.find({r, times[j]});
            if (found == states.end()) continue;  // the realization did not reach t: NaN
            const SnapshotObservables o = snapshot_observables(*found->second, ring_length, particles, rule);
            const std::size_t at = static_cast<std::size_t>(r) * times.size() + j;
            kurtosis.temperature[at] = o.kurtosis / sticky_gas_kurtosis;
            density.temperature[at] = o.cluster_density;
            small_gaps.temperature[at] = o.small_gap_fraction;
            structure.temperature[at] = o.structure_function;
            if (j + 1 < times.size()) {
                const auto next = states.find({r, times[j + 1]});
                if (next != states.end())
                    fragmentation.temperature[static_cast<std::size_t>(r) * fragment_times.size() + j] =
                        fragmentation_rate(*found->second, *next->second, ring_length, particles, rule);
            }
        }
    out.push_back({"kurtosis", std::move(kurtosis)});
    out.push_back({"cluster_density", std::move(density)});
    out.push_back({"small_gap_fraction", std::move(small_gaps)});
    out.push_back({"structure_function", std::move(structure)});
    out.push_back({"fragmentation_rate", std::move(fragmentation)});
    return out;
}

ValidityDeparture departure(const ObservableHistory& run, const ObservableHistory& reference,
                            const std::string& criterion, const ValidityRule& rule) {
    ValidityDeparture out;
    out.observable = run.observable;
    out.criterion = criterion;
    const Band band = band_of(run.observable, criterion, rule);
    out.departure_time = departure_time(run.values, reference.values, band);
    const std::vector<double>& times = run.values.time;
    const double t_end = times.back();
    if (std::isnan(out.departure_time)) {
        out.departure_sigma = not_a_number;
        out.note = "never joined the sticky gas: not inside the band at two consecutive sample times before "
                   "its final stretch outside";
        return out;
    }
    if (std::isinf(out.departure_time)) {
        out.departure_sigma = not_a_number;
        out.note = fmt::format("still inside the band at t_end = {:g}", t_end);
        return out;
    }
    // Delete-one-pair jackknife of ln t* (a replica that had not departed by
    // t_end, or never joined, counts as t_end or the first time: censored),
    // and the sampling grid's own resolution: t* is a sample time, uniform in
    // ln t over the spacing at t* (variance spacing^2 / 12).
    const std::size_t n = std::min(run.values.realizations, reference.values.realizations);
    double grid_variance = 0.0;
    const auto at = static_cast<std::size_t>(std::find(times.begin(), times.end(), out.departure_time) - times.begin());
    if (at > 0 && at < times.size()) grid_variance = std::pow(std::log(times[at] / times[at - 1]), 2.0) / 12.0;
    const Estimate log_departure = jackknife(n, [&](std::optional<std::size_t> left_out) {
        if (!left_out) return std::log(out.departure_time);
        double t = departure_time(without_realization(run.values, *left_out),
                                  without_realization(reference.values, *left_out), band);
        if (std::isnan(t)) t = times.front();
        if (std::isinf(t)) t = t_end;
        return std::log(t);
    });
    double jackknife_variance = 0.0;
    if (std::isnan(log_departure.sigma))
        out.note = "one realization in common: sigma is the sampling grid's alone";
    else
        jackknife_variance = log_departure.sigma * log_departure.sigma;
    out.departure_sigma = out.departure_time * std::sqrt(jackknife_variance + grid_variance);
    return out;
}

ValidityFit fit_departures(const std::vector<const ValidityRun*>& runs, const std::string& observable,
                           const std::string& criterion) {
    ValidityFit fit;
    fit.observable = observable;
    fit.criterion = criterion;
    if (!runs.empty()) {
        fit.subthreshold = runs.front()->subthreshold;
        fit.restitution = runs.front()->restitution;
        fit.particles = runs.front()->particles;
    }
    std::vector<double> x, y, sigma;
    for (const ValidityRun* run : runs)
        for (const auto& d : run->departures)
            if (d.observable == observable && d.criterion == criterion && std::isfinite(d.departure_time) &&
                d.departure_sigma > 0.0) {
                x.push_back(-std::log(run->velocity_threshold));
                y.push_back(std::log(d.departure_time));
                sigma.push_back(d.departure_sigma / d.departure_time);
            }
    fit.points = static_cast<std::int64_t>(x.size());
    fit.mu = fit.mu_sigma = fit.log_amplitude = fit.log_amplitude_sigma = not_a_number;
    if (x.size() < 2 || std::all_of(x.begin(), x.end(), [&](double v) { return v == x.front(); })) {
        fit.follows = fmt::format("n/a ({} delta(s) departed within the runs: a slope needs two)", x.size());
        return fit;
    }
    // ln t* = ln A + mu ln(1/delta), weighted by each t*'s jackknife-and-grid sigma.
    const LinearFit line = weighted_linear_fit(x, y, sigma);
    fit.mu = line.slope;
    fit.mu_sigma = line.slope_sigma();
    fit.log_amplitude = line.intercept;
    fit.log_amplitude_sigma = line.intercept_sigma();
    // Which of the two predictions lies within 2 sigma.
    const bool one = std::abs(fit.mu - 1.0) < 2.0 * fit.mu_sigma, three = std::abs(fit.mu - 3.0) < 2.0 * fit.mu_sigma;
    fit.follows = one && three ? "both within 2 sigma (undecided)"
                  : one        ? "delta^-1"
                  : three      ? "delta^-3"
                               : "neither";
    return fit;
}

void run_validity(const AnalysisInvocation& invocation, const std::vector<std::string>& inputs,
                  const std::string& output, const std::string& data, const std::string& curves,
                  const std::string& fidelity, const ValidityRule& rule) {
    struct Input {
        std::string path, name, subthreshold;
        double restitution = 0.0, delta = 0.0, cpu_seconds = 0.0;
        std::int64_t particles = 0, seed = 0, realizations = 0;
        bool reference = false;
    };
    std::vector<Input> runs;
    for (const auto& path : inputs) {
        const auto file = h5::File::open_read(path);
        const auto root = file.root();
        Input in;
        in.path = path;
        in.name = std::filesystem::path(path).stem().string();
        in.restitution = root.attribute_double("restitution");
        in.delta = root.attribute_double("velocity_threshold");
        in.subthreshold = root.attribute_string("subthreshold");
        in.particles = root.attribute_integer("particles");
        in.seed = root.attribute_integer("seed");
        in.realizations = root.attribute_integer("realizations");
        in.cpu_seconds = root.attribute_double("cpu_seconds");
        in.reference = in.restitution == 0.0 && in.delta == 0.0;
        runs.push_back(in);
    }
    auto reference_of = [&](const Input& run) -> const Input& {
        for (const auto& candidate : runs)
            if (candidate.reference && candidate.particles == run.particles && candidate.seed == run.seed)
                return candidate;
        throw InputError(fmt::format("'{}' has no sticky-gas reference among the inputs: validity compares each run "
                                     "with a run of r = 0, delta = 0 of the same N ({}) and seed ({})",
                                     run.path, run.particles, run.seed));
    };
    std::map<std::string, std::vector<ObservableHistory>> histories;
    auto histories_of = [&](const Input& in) -> const std::vector<ObservableHistory>& {
        auto found = histories.find(in.path);
        if (found == histories.end())
            try {
                found = histories.emplace(in.path, observable_histories(in.path, rule)).first;
            } catch (const InsufficientData& error) {
                throw InputError(fmt::format("{}, in '{}'", error.what(), in.path));
            }
        return found->second;
    };
    ValidityMap map;
    map.fidelity = fidelity;
    map.version = fmt::format("{} map, {}", fidelity, this_build_description());
    map.observables = validity_observables();
    std::unique_ptr<DataFile> curve_file;
    if (!curves.empty())
        curve_file = std::make_unique<DataFile>(
            curves,
            "each observable's difference from the sticky gas against t (T: <T>/<T_ref> - 1), one block per run "
            "and observable, in the order of the '# block' lines",
            inputs, std::vector<std::string>{"time", "deviation", "sigma"});
    for (const auto& run : runs) {
        if (run.reference) continue;
        const Input& reference = reference_of(run);
        if (const std::string differences = comparison_differences(reference.path, run.path, false);
            !differences.empty())
            throw InputError(fmt::format("'{}' is not comparable with its sticky-gas reference '{}': {}", run.path,
                                         reference.path, differences));
        const auto& mine = histories_of(run);
        const auto& theirs = histories_of(reference);
        ValidityRun entry;
        entry.name = run.name;
        entry.restitution = run.restitution;
        entry.velocity_threshold = run.delta;
        entry.subthreshold = run.subthreshold;
        entry.particles = run.particles;
        entry.realizations = run.realizations;
        entry.cpu_seconds = run.cpu_seconds;
        for (std::size_t o = 0; o < mine.size(); ++o) {
            for (const auto& criterion : criteria())
                entry.departures.push_back(departure(mine[o], theirs[o], criterion, rule));
            if (curve_file) {
                const Band band = band_of(mine[o].observable, "3sigma", rule);
                const TemperatureComparison c = compare_histories(mine[o].values, theirs[o].values,
                                                                  Realizations::paired, band.mode, band.k_sigma, 0.0);
                // Relative for every observable but the fragmentation rate (band_of).
                curve_file->comment(fmt::format("block {} {}", run.name, mine[o].observable));
                for (std::size_t k = 0; k < c.time.size(); ++k)
                    curve_file->row({c.time[k], c.relative_deviation[k], c.relative_sigma[k]});
                curve_file->blank_line();
                curve_file->blank_line();
            }
        }
        // The cost model: the ensemble's mean collisions per particle at its sample times.
        const TimeSeries series = read_timeseries(run.path);
        entry.t_end = mine.front().values.time.back();
        for (std::size_t k = 0; k < series.time.size(); ++k) {
            if (!(series.time[k] > 0.0)) continue;
            double sum = 0.0;
            std::size_t count = 0;
            for (std::int64_t r = 0; r < series.realizations; ++r) {
                const double v = series.at(series.collisions_per_particle, r, k);
                if (std::isfinite(v)) {
                    sum += v;
                    ++count;
                }
            }
            if (count == 0) continue;
            entry.time.push_back(series.time[k]);
            entry.collisions_per_particle.push_back(sum / static_cast<double>(count));
        }
        map.runs.push_back(std::move(entry));
    }
    if (map.runs.empty())
        throw InputError("validity needs at least one run with r > 0 or delta > 0 beside its sticky-gas reference");
    // Fits over delta, per (r, mechanism, N).
    std::map<std::tuple<double, std::string, std::int64_t>, std::vector<const ValidityRun*>> groups;
    for (const auto& run : map.runs) groups[{run.restitution, run.subthreshold, run.particles}].push_back(&run);
    for (const auto& [key, members] : groups) {
        if (members.size() < 2) continue;  // one delta (the N check): no slope
        for (const auto& observable : map.observables) {
            for (const auto& criterion : criteria()) map.fits.push_back(fit_departures(members, observable, criterion));
        }
    }
    ResultsFile results(output, invocation, inputs);
    auto group = results.section("validity_map");
    write_validity_map(group, map);
    std::unique_ptr<DataFile> table;
    if (!data.empty()) {
        table = std::make_unique<DataFile>(
            data,
            "departure time t* of each observable from the sticky gas, per run; then the fits t* = A delta^-mu. "
            "status: 0 departed, 1 still inside at t_end (t* column = t_end), 2 never joined",
            inputs,
            std::vector<std::string>{"restitution", "sticky", "particles", "observable", "criterion", "delta",
                                     "t_star", "t_star_sigma", "status", "mu", "mu_sigma", "ln_A"});
        for (std::size_t o = 0; o < map.observables.size(); ++o)
            for (const std::string& criterion : criteria())
                for (const auto& run : map.runs)
                    for (const auto& d : run.departures) {
                        if (d.observable != map.observables[o] || d.criterion != criterion) continue;
                        const ValidityFit* fit = nullptr;
                        for (const auto& f : map.fits)
                            if (f.observable == d.observable && f.criterion == criterion &&
                                f.restitution == run.restitution && f.subthreshold == run.subthreshold &&
                                f.particles == run.particles)
                                fit = &f;
                        const double status = std::isnan(d.departure_time) ? 2.0 : std::isinf(d.departure_time) ? 1.0 : 0.0;
                        const double shown = status == 1.0 ? run.t_end : d.departure_time;
                        const double criterion_index = criterion == "3sigma" ? 0.0 : criterion == "1percent" ? 1.0 : 2.0;
                        table->row({run.restitution, run.subthreshold == "sticky" ? 1.0 : 0.0,
                                    static_cast<double>(run.particles), static_cast<double>(o), criterion_index,
                                    run.velocity_threshold, shown, d.departure_sigma, status,
                                    fit ? fit->mu : not_a_number, fit ? fit->mu_sigma : not_a_number,
                                    fit ? fit->log_amplitude : not_a_number});
                    }
    }
    commit_outputs(&results, {table.get(), curve_file.get()});
    for (const auto& fit : map.fits)
        fmt::print("validity: r = {:g}, {}, N = {}: {} ({}): mu = {}\n", fit.restitution, fit.subthreshold,
                       fit.particles, fit.observable, fit.criterion,
                       std::isnan(fit.mu) ? fit.follows
                                          : fmt::format("{:.2f} +- {:.2f} ({})", fit.mu, fit.mu_sigma, fit.follows));
}

}  // namespace shockgas::analysis
