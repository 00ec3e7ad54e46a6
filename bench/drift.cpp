// SPDX-License-Identifier: GPL-3.0-or-later
#include "drift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <memory>

#include <fmt/format.h>

#include "shockgas/engines/engine.hpp"
#include "reference_event_engine.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/provenance.hpp"
#include "ring_kinematics.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::drift {

namespace {

constexpr double unit_roundoff_2 = 0x1p-52;  // 2u, u = 2^-53 the unit roundoff of double

struct Snapshot {
    long double momentum = 0;
    long double energy = 0;
    long double momentum_scale = 0;  // sum m |v|
    double max_speed = 0;
    double min_gap = 0;  // smallest gap, absolute; negative if two clusters are out of order
    std::int64_t nonfinite = 0;
};

Snapshot inspect(const ClusterState& state, double ring_length) {
    Snapshot s;
    const std::size_t n = state.size();
    for (std::size_t k = 0; k < n; ++k) {
        // In the lab, as the start's (the engines' frame is at rest for the
        // generated starts this runs, ClusterState).
        const double lab = state.lab_velocity(k);
        const long double m = state.mass[k], v = lab;
        if (!std::isfinite(lab) || !std::isfinite(state.position[k]) || !std::isfinite(state.mass[k])) ++s.nonfinite;
        s.momentum += m * v;
        s.momentum_scale += m * std::fabs(v);
        s.energy += 0.5L * m * v * v;
        s.max_speed = std::max(s.max_speed, std::fabs(lab));
    }
    // Gaps in ring order from consecutive differences of positions wrapped
    // into [0, L), +L where the ring closes; any other negative difference is
    // a pair out of order.
    if (n == 1) {
        s.min_gap = ring_length;
        return s;
    }
    const std::size_t closing = closing_pair(state.position);
    s.min_gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) {
        const double d = state.position[(k + 1) % n] - state.position[k];
        s.min_gap = std::min(s.min_gap, k == closing ? d + ring_length : d);
    }
    return s;
}

// Every pair out of order by more than `resolution`: which clusters, where,
// how fast they separate and how long ago they would have met.
void note_disorder(const ClusterState& state, double ring_length, double resolution, std::uint64_t collisions,
                   const DriftListener& listener) {
    if (!listener.note) return;
    const std::size_t n = state.size();
    const std::size_t seam = closing_pair(state.position);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t j = (k + 1) % n;
        double d = state.position[j] - state.position[k];
        if (k == seam) d += ring_length;
        if (!(d < -resolution)) continue;
        const double closing = state.velocity[k] - state.velocity[j];
        listener.note(fmt::format(
            "disorder at t = {:.17g} after {} collisions: clusters {} (slot {}, x = {:.17g}, v = {:.17g}) and "
            "{} (slot {}, x = {:.17g}, v = {:.17g}): gap {:.3e}, closing speed {:.3e}, overlap / |closing| = {:.3e}",
            state.time, collisions, k, state.first_particle[k], state.position[k], state.velocity[k], j,
            state.first_particle[j], state.position[j], state.velocity[j], d, closing,
            closing != 0.0 ? -d / std::fabs(closing) : 0.0));
    }
}

double ulp(double x) { return std::nextafter(std::fabs(x), std::numeric_limits<double>::infinity()) - std::fabs(x); }

// Row milestones: the log grid 10^(k / per_decade) and multiples of record_every, up to the target.
std::vector<double> milestones_of(const DriftOptions& options) {
    std::vector<double> milestones;
    for (int k = 0;; ++k) {
        const double c = std::round(std::pow(10.0, static_cast<double>(k) / options.records_per_decade));
        if (c >= options.target_collisions) break;
        milestones.push_back(c);
    }
    for (double c = options.record_every; c < options.target_collisions; c += options.record_every)
        milestones.push_back(c);
    milestones.push_back(options.target_collisions);
    std::sort(milestones.begin(), milestones.end());
    milestones.erase(std::unique(milestones.begin(), milestones.end()), milestones.end());
    return milestones;
}

}  // namespace

void require_checkable(const SimulationParameters& p) {
    if (p.collision.restitution == 0.0 || p.collision.subthreshold == Subthreshold::sticky)
        throw InputError("--check needs a run without merges (r > 0, elastic sub-threshold): the rounding "
                         "bounds assume v' = v -+ h");
}

double momentum_rounding_bound(double collisions, double mass, double max_speed0, double momentum_scale) {
    return collisions * unit_roundoff_2 * mass * max_speed0 / momentum_scale;
}

double ring_length_rounding_bound(double collisions, double spacing) {
    return 20.0 * std::sqrt(3.0 * collisions) * 0x1p-53 * spacing;
}

double energy_rounding_bound(double collisions, double mass, double max_speed, double energy, double particles) {
    return collisions * unit_roundoff_2 * mass * max_speed * max_speed / energy + 2.0 * particles * 0x1p-64;
}

const std::vector<std::string>& column_names() {
    static const std::vector<std::string> names = {
        "collisions",     "time",           "clusters",       "momentum",       "momentum_drift",
        "momentum_drift_bound", "energy_ratio", "max_energy_rise", "min_gap",   "min_gap_so_far",
        "gap_resolution", "ring_order",     "nonfinite",      "cpu_seconds",    "collisions_per_cpu_second",
        "collisions_per_unit_time", "stored_min_gap", "ring_length_drift"};
    return names;
}

std::vector<double> row_values(const DriftRow& r) {
    return {r.collisions,   r.time,      r.clusters, r.momentum,    r.drift,       r.bound,
            r.energy_ratio, r.max_rise,  r.min_gap,  r.min_gap_run, r.gap_resolution, r.order,
            r.nonfinite,    r.cpu_seconds, r.rate,   r.collision_rate_in_time, r.stored_min_gap,
            r.ring_length_drift};
}

DriftReport run_drift(const SimulationParameters& p, const DriftOptions& options, const DriftListener& listener) {
    validate(p);
    DriftReport report;
    report.ring_length = p.effective_ring_length();
    report.spacing = report.ring_length / static_cast<double>(p.particles);
    const double ring_length = report.ring_length, spacing = report.spacing;
    auto initial = generate_initial_condition(p.particles, ring_length, p.seed, options.realization);
    const double mass = initial.mass.front();
    ClusterState state;
    state.position = initial.position;
    state.velocity = initial.velocity;
    state.mass = initial.mass;
    const Snapshot start = inspect(state, ring_length);
    report.start = {static_cast<double>(start.momentum), static_cast<double>(start.momentum_scale),
                    static_cast<double>(start.energy), start.max_speed};
    initial.velocity.front() += options.inject_momentum_error;

    std::unique_ptr<Engine> engine;
    const ReferenceEventEngine* reference_engine = nullptr;
    if (options.reference) {
        auto global_loop = std::make_unique<ReferenceEventEngine>(initial, p.collision, p.collapse, nullptr);
        reference_engine = global_loop.get();
        engine = std::move(global_loop);
    } else {
        engine = make_engine(p, initial, nullptr);
    }
    report.engine = engine->name();
    if (listener.started) listener.started(report);

    const std::vector<double> milestones = milestones_of(options);
    const std::clock_t cpu_start = std::clock();
    const auto cpu_seconds = [&] { return static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC; };
    double min_gap_run = start.min_gap;
    long double previous_energy = start.energy;
    double previous_max_speed = start.max_speed;
    std::uint64_t previous_chunk_collisions = 0;
    double last_row_time = 0.0;
    std::uint64_t last_row_collisions = 0;
    std::size_t next = 0;
    double dt = 1e-2 * spacing;  // first chunk: a few collisions; later chunks sized from the rate
    report.ended = "reached the target";
    int idle_chunks = 0;

    while (next < milestones.size()) {
        const double before = static_cast<double>(engine->collisions());
        const double t_before = engine->time();
        const bool running = engine->advance_to(t_before + dt);
        engine->clusters(state);
        const std::uint64_t collisions = engine->collisions();
        const double done = static_cast<double>(collisions) - before;

        const Snapshot now = inspect(state, ring_length);
        const double resolution = ulp(2.0 * ring_length + start.max_speed * engine->time()) + ulp(ring_length);
        const bool order = now.min_gap >= -resolution;
        report.order_held = report.order_held && order;
        if (!order) note_disorder(state, ring_length, resolution, engine->collisions(), listener);
        report.nonfinite = std::max(report.nonfinite, now.nonfinite);
        min_gap_run = std::min(min_gap_run, now.min_gap);
        const double rise = static_cast<double>((now.energy - previous_energy) / previous_energy);
        report.max_rise = std::max(report.max_rise, rise);
        const double energy_bound =
            energy_rounding_bound(static_cast<double>(collisions - previous_chunk_collisions), mass,
                                  previous_max_speed, static_cast<double>(previous_energy),
                                  static_cast<double>(p.particles));
        if (rise > energy_bound) {
            report.energy_within_bound = false;
            if (listener.note)
                listener.note(fmt::format("energy rose by {:.3e} (relative) over collisions {}..{}: above the "
                                          "rounding bound {:.3e}",
                                          rise, previous_chunk_collisions, collisions, energy_bound));
        }
        previous_energy = now.energy;
        previous_max_speed = now.max_speed;
        previous_chunk_collisions = collisions;

        const bool stopped =
            !running || engine->cluster_count() == 1 || idle_chunks > 60 || (options.stop_on_disorder && !order);
        if (static_cast<double>(collisions) >= milestones[next] || stopped) {
            DriftRow row{};
            row.collisions = static_cast<double>(collisions);
            row.time = engine->time();
            row.clusters = static_cast<double>(engine->cluster_count());
            row.momentum = static_cast<double>(now.momentum);
            row.drift = static_cast<double>(std::fabs(now.momentum - start.momentum) / start.momentum_scale);
            row.bound = momentum_rounding_bound(row.collisions, mass, start.max_speed,
                                                static_cast<double>(start.momentum_scale));
            row.energy_ratio = static_cast<double>(now.energy / start.energy);
            row.max_rise = report.max_rise;
            row.min_gap = now.min_gap / spacing;
            row.min_gap_run = min_gap_run / spacing;
            row.gap_resolution = resolution / spacing;
            row.order = report.order_held ? 1.0 : 0.0;
            row.nonfinite = static_cast<double>(report.nonfinite);
            row.cpu_seconds = cpu_seconds();
            row.rate = row.cpu_seconds > 0 ? row.collisions / row.cpu_seconds : 0.0;
            row.collision_rate_in_time =
                row.time > last_row_time
                    ? static_cast<double>(collisions - last_row_collisions) / (row.time - last_row_time)
                    : 0.0;
            row.stored_min_gap = row.ring_length_drift = std::numeric_limits<double>::quiet_NaN();
            if (reference_engine != nullptr) {
                const std::vector<double> gaps = reference_engine->gaps();
                long double total = 0;
                for (double g : gaps) total += g;
                row.stored_min_gap = *std::min_element(gaps.begin(), gaps.end()) / spacing;
                row.ring_length_drift = static_cast<double>(total - static_cast<long double>(ring_length));
            }
            last_row_time = row.time;
            last_row_collisions = collisions;
            report.rows.push_back(row);
            if (listener.row) listener.row(row);
            while (next < milestones.size() && static_cast<double>(collisions) >= milestones[next]) ++next;
        }
        if (stopped) {
            report.ended = !order                      ? "stopped at ring disorder"
                           : !running                  ? "engine stopped (collapse)"
                           : engine->cluster_count() == 1 ? "one cluster left: no more collisions"
                                                          : "no collisions in 60 chunks";
            break;
        }

        // Every row taken: done. (Sizing a next chunk here would read one milestone
        // past the end; Drift.TheReferenceLoopKeepsTheRingLength under AddressSanitizer
        // covers it.)
        if (next == milestones.size()) break;
        // Next chunk: about chunk_collisions at the rate just seen, within a
        // factor 4 of this chunk's length so one odd chunk cannot derail it.
        const double wanted = std::min(options.chunk_collisions, milestones[next] - static_cast<double>(collisions));
        idle_chunks = done > 0 ? 0 : idle_chunks + 1;
        const double proposal = done > 0 ? wanted / (done / dt) : 4.0 * dt;
        dt = std::clamp(proposal, 0.25 * dt, 4.0 * dt);
    }
    return report;
}

std::vector<std::string> check_failures(const SimulationParameters& p, const DriftOptions& options,
                                        const DriftReport& report) {
    require_checkable(p);
    std::vector<std::string> failures;
    const DriftRow& last = report.rows.back();
    if (last.collisions < options.target_collisions) failures.push_back("run ended early: " + report.ended);
    if (last.drift > last.bound)
        failures.push_back(
            fmt::format("momentum drift {:.3e} exceeds the rounding bound {:.3e}", last.drift, last.bound));
    if (!report.energy_within_bound) failures.emplace_back("kinetic energy rose beyond rounding");
    if (!report.order_held) failures.emplace_back("ring order broken (a gap below -resolution)");
    if (options.reference) {
        const double bound = ring_length_rounding_bound(last.collisions, report.spacing);
        if (!(std::fabs(last.ring_length_drift) <= bound))
            failures.push_back(fmt::format("ring length drift sum(gaps) - L = {:.3e} exceeds the rounding bound {:.3e}",
                                           last.ring_length_drift, bound));
    }
    if (report.nonfinite > 0) failures.emplace_back("non-finite values");
    return failures;
}

void write_csv(const std::string& path, const DriftReport& report) {
    std::ofstream csv(path);
    if (!csv) throw InputError("cannot write '" + path + "'");
    const auto& names = column_names();
    for (std::size_t c = 0; c < names.size(); ++c) csv << (c ? "," : "") << names[c];
    csv << "\n";
    for (const DriftRow& r : report.rows) {
        const auto values = row_values(r);
        for (std::size_t c = 0; c < values.size(); ++c) csv << (c ? "," : "") << fmt::format("{:.17g}", values[c]);
        csv << "\n";
    }
    if (!csv.flush()) throw InputError("cannot write '" + path + "'");
}

void write_h5(const std::string& path, const SimulationParameters& p, const DriftOptions& options,
              const DriftReport& report) {
    h5::AtomicFile file(path);
    auto root = file.root();
    write_provenance(root, "shockgas-drift");
    root.set_attribute("particles", static_cast<std::int64_t>(p.particles));
    root.set_attribute("ring_length", report.ring_length);
    root.set_attribute("restitution", p.collision.restitution);
    root.set_attribute("velocity_threshold", p.collision.velocity_threshold);
    root.set_attribute("subthreshold", to_string(p.collision.subthreshold));
    root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
    root.set_attribute("realization", options.realization);
    root.set_attribute("engine", report.engine);
    root.set_attribute("target_collisions", options.target_collisions);
    root.set_attribute("ended", report.ended);
    root.set_attribute("initial_momentum", report.start.momentum);
    root.set_attribute("momentum_scale", report.start.momentum_scale);
    root.set_attribute("initial_energy", report.start.energy);
    root.set_attribute("momentum_drift_definition", "|P - P0| / sum m |v0|");
    root.set_attribute("gap_units", "mean spacing L/N");
    const auto& names = column_names();
    std::vector<std::vector<double>> columns(names.size());
    for (const DriftRow& r : report.rows) {
        const auto values = row_values(r);
        for (std::size_t c = 0; c < names.size(); ++c) columns[c].push_back(values[c]);
    }
    for (std::size_t c = 0; c < names.size(); ++c) root.write(names[c], columns[c]);
    file.commit();
}

namespace {

void print_header() {
    fmt::print("# {:>10} {:>10} {:>6} {:>9} {:>9} {:>10} {:>9} {:>9} {:>9} {:>8} {:>5} {:>3} {:>8} {:>8} {:>8}\n",
               "collisions", "t", "clust", "dP/S0", "bound", "E/E0", "rise", "gap", "gap_min", "res", "order", "bad",
               "cpu_s", "coll/s", "dC/dt");
    std::fflush(stdout);
}

void print_row(const DriftRow& r) {
    fmt::print(
        "  {:>10.4g} {:>10.4g} {:>6} {:>9.2e} {:>9.2e} {:>10.4e} {:>9.2e} {:>9.2e} {:>9.2e} {:>8.1e} {:>5} "
        "{:>3} {:>8.1f} {:>8.3g} {:>8.3g}\n",
        r.collisions, r.time, static_cast<std::int64_t>(r.clusters), r.drift, r.bound, r.energy_ratio, r.max_rise,
        r.min_gap, r.min_gap_run, r.gap_resolution, static_cast<int>(r.order), static_cast<std::int64_t>(r.nonfinite),
        r.cpu_seconds, r.rate, r.collision_rate_in_time);
    if (!std::isnan(r.stored_min_gap))
        fmt::print("#   stored gaps: smallest {:.3e} L/N, sum(gaps) - L = {:.3e}\n", r.stored_min_gap,
                   r.ring_length_drift);
    std::fflush(stdout);
}

// The run's parameters, its start and the columns, before the first row.
void print_start(const DriftRequest& request, const DriftReport& report) {
    const SimulationParameters& p = request.parameters;
    const DriftOptions& o = request.options;
    fmt::print(
        "# shockgas-drift: N = {}, L = {}, r = {}, delta = {}, {} sub-threshold, seed {}, realization "
        "{}; engine {} ({})\n",
        p.particles, report.ring_length, p.collision.restitution, p.collision.velocity_threshold, request.subthreshold,
        p.seed, o.realization, report.engine, o.reference ? "ReferenceEventEngine, --reference" : "make_engine");
    fmt::print("# P0 = {:.17g}, S0 = sum m|v0| = {:.17g}, E0 = {:.17g}, |v|max0 = {:.17g}\n", report.start.momentum,
               report.start.momentum_scale, report.start.energy, report.start.max_speed);
    fmt::print(
        "# dP/S0 = |P - P0| / S0; gaps in units of L/N; rise = largest (E_k - E_(k-1))/E_(k-1) "
        "between chunks of ~{:.0e} collisions\n",
        o.chunk_collisions);
    print_header();
}

}  // namespace

std::string drift_summary(const DriftReport& report) {
    const DriftRow& last = report.rows.back();
    return fmt::format(
        "# {}: {} collisions, t = {:.6g}, {:.1f} s CPU, {:.3g} collisions/s; final dP/S0 = {:.3e} "
        "(bound {:.3e}); max energy rise {:.3e}; smallest gap {:.3e} L/N; ring order {}; non-finite {}",
        report.ended, last.collisions, last.time, last.cpu_seconds, last.rate, last.drift, last.bound, report.max_rise,
        last.min_gap_run, report.order_held ? "held" : "BROKEN", report.nonfinite);
}

int run_drift_command(DriftRequest request) {
    SimulationParameters& p = request.parameters;
    const DriftOptions& o = request.options;
    const std::string& output = request.output;
    p.collision.subthreshold = subthreshold_from_string(request.subthreshold);
    validate(p);
    const bool csv = output.ends_with(".csv"), h5 = output.ends_with(".h5");
    if (!output.empty() && !csv && !h5) throw InputError("--output must end in .csv or .h5, got '" + output + "'");
    if (!output.empty()) h5::check_writable(output);
    if (request.check) require_checkable(p);

    DriftListener listener;
    listener.started = [&request](const DriftReport& report) { print_start(request, report); };
    listener.row = print_row;
    listener.note = [](const std::string& line) { fmt::print("# {}\n", line); };
    const DriftReport report = run_drift(p, o, listener);
    fmt::print("{}\n", drift_summary(report));
    if (csv) write_csv(output, report);
    if (h5) write_h5(output, p, o, report);

    if (!request.check) return 0;
    const auto failures = check_failures(p, o, report);
    for (const auto& why : failures) fmt::print(stderr, "shockgas-drift: check failed: {}\n", why);
    return failures.empty() ? 0 : 1;
}

}  // namespace shockgas::drift
