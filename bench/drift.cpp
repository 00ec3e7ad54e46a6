// shockgas-drift: long-run drift of the conserved and bounded quantities of one
// realization (the stability issue: "measure the drift of total momentum and of
// the smallest gap over the longest run you can afford").
//
// One realization of the paper's initial condition (generate_initial_condition)
// runs on the engine make_engine picks, in chunks (advance_to successive
// times, sized from the measured collision rate to about --chunk collisions).
// After every chunk the clusters are read through the public Engine interface
// and checked; a table row is printed at every decade of the collision count
// (--records-per-decade) and every --record-every collisions:
//
//   P        total momentum sum m v (long double sum: its own rounding,
//            ~N 2^-64 sum m|v|, is far below one ulp of the engine's values)
//   dP       relative drift |P - P0| / sum m |v0|
//   bound    the worst case rounding can reach, C 2^-52 m |v|max0 / sum m |v0|
//            (see momentum_rounding_bound); exceeded means a real leak
//   E/E0     kinetic energy sum m v^2 / 2 over its initial value
//   rise     largest relative increase of E between two consecutive chunks so
//            far; exact dynamics never increase E, rounding may by
//            2^-52 |v|max^2 per collision (energy_rounding_bound)
//   gap      smallest gap between neighbouring clusters at this row, and the
//            smallest over every chunk so far, in units of the mean spacing
//            L/N, from ClusterState positions (no engine exposes its stored
//            gaps through the Engine interface). Their resolution is the row's
//            `res`: positions are walked from the anchor's absolute position,
//            which is not wrapped and grows like |v| t, so a gap is known to
//            about ulp(2L + |v|max0 t) + ulp(L).
//   order    1 while every gap so far was >= -res (ring order holds up to
//            rounding; a pair out of order shows as a negative gap)
//   bad      non-finite positions or velocities seen so far
//
// --check turns the two rounding bounds into pass/fail (exit status 1), and
// with --reference a third, on the ring length (ring_length_rounding_bound);
// the ctests `drift.check` (10^6 collisions) and `drift.ring_length` (10^7,
// --reference) run it.
//
// Example (the long run of docs/testing-and-drift.md, ~20 min of one core):
//   build/bench/shockgas-drift -N 1000 -r 0.5 -d 1e-2 --collisions 1e10 -o drift.h5
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/cli.hpp"
#include "shockgas/engine.hpp"
#include "shockgas/event_engine.hpp"
#include "shockgas/h5.hpp"
#include "shockgas/parameters.hpp"
#include "shockgas/provenance.hpp"
#include "shockgas/ring_kinematics.hpp"
#include "shockgas/state.hpp"

namespace {

using shockgas::InputError;

constexpr double unit_roundoff_2 = 0x1p-52;  // 2u, u = 2^-53 the unit roundoff of double

// Worst-case relative momentum drift after `collisions` equal-mass, non-merging
// collisions. Each collision computes v1' = v1 - h, v2' = v2 + h from one h
// (collision.hpp), so in exact arithmetic P is unchanged and only the two
// final roundings move it, each by at most u |v'| <= u |v|max0 (|v|max never
// grows: convex combinations, see fast_engine.hpp). Hence
//   |P - P0| <= C * 2u * m |v|max0, relative to sum m |v0|.
double momentum_rounding_bound(double collisions, double mass, double max_speed0, double momentum_scale) {
    return collisions * unit_roundoff_2 * mass * max_speed0 / momentum_scale;
}

// |sum(gaps) - L| that rounding alone should stay within (--reference only).
// The engines store gaps, never L, and no collision moves mass across the
// ring, so the sum stays L but for rounding: each collision rewrites three
// gaps (the pair's own contact gap and its two neighbours'), each rounded to
// within 2^-53 of its value. Those errors have random signs, so the sum
// random-walks as sqrt(3 C) 2^-53 g for gaps g of about the mean spacing;
// the factor 20 covers gaps a few spacings wide and a 4-sigma excursion. It is
// not a worst case (that, 3 C 2^-53 g_max, grows too fast to tell anything
// apart). Measured at N = 1000, C = 10^7: 2.4e-13 L/N against a bound of
// 1.2e-11; setting the contact gap to 0 instead, as the engines did until the
// contact gap was kept, gives 1.3e-9, because it drops c * (t rounded - t
// exact) ~ c ulp(t) at every collision.
double ring_length_rounding_bound(double collisions, double spacing) {
    return 20.0 * std::sqrt(3.0 * collisions) * 0x1p-53 * spacing;
}

// Worst-case energy increase over `collisions` collisions, relative to E:
// each rounded velocity v(1 + a), |a| <= u, changes m v^2 / 2 by at most
// m u v^2 (1 + u), and exact collisions never add energy, so
//   E' - E <= C * 2u * m |v|max^2 (two velocities per collision), plus the
// long double measurement error of the two sums, 2 N 2^-64 E.
double energy_rounding_bound(double collisions, double mass, double max_speed, double energy, double particles) {
    return collisions * unit_roundoff_2 * mass * max_speed * max_speed / energy + 2.0 * particles * 0x1p-64;
}

struct Snapshot {
    long double momentum = 0;
    long double energy = 0;
    long double momentum_scale = 0;  // sum m |v|
    double max_speed = 0;
    double min_gap = 0;  // smallest gap, absolute; negative if two clusters are out of order
    std::int64_t nonfinite = 0;
};

Snapshot inspect(const shockgas::ClusterState& state, double ring_length) {
    Snapshot s;
    const std::size_t n = state.size();
    for (std::size_t k = 0; k < n; ++k) {
        const long double m = state.mass[k], v = state.velocity[k];
        if (!std::isfinite(state.velocity[k]) || !std::isfinite(state.position[k]) || !std::isfinite(state.mass[k]))
            ++s.nonfinite;
        s.momentum += m * v;
        s.momentum_scale += m * std::fabs(v);
        s.energy += 0.5L * m * v * v;
        s.max_speed = std::max(s.max_speed, std::fabs(state.velocity[k]));
    }
    // Gaps in ring order from consecutive differences of positions wrapped
    // into [0, L), +L where the ring closes; any other negative difference is
    // a pair out of order.
    if (n == 1) {
        s.min_gap = ring_length;
        return s;
    }
    const std::size_t closing = shockgas::closing_pair(state.position);
    s.min_gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) {
        const double d = state.position[(k + 1) % n] - state.position[k];
        s.min_gap = std::min(s.min_gap, k == closing ? d + ring_length : d);
    }
    return s;
}

// Every pair out of order by more than `resolution`: which clusters, where,
// how fast they separate and how long ago they would have met.
void print_disorder(const shockgas::ClusterState& state, double ring_length, double resolution,
                    std::uint64_t collisions) {
    const std::size_t n = state.size();
    const std::size_t seam = shockgas::closing_pair(state.position);
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t j = (k + 1) % n;
        double d = state.position[j] - state.position[k];
        if (k == seam) d += ring_length;
        if (!(d < -resolution)) continue;
        const double closing = state.velocity[k] - state.velocity[j];
        fmt::print("# disorder at t = {:.17g} after {} collisions: clusters {} (slot {}, x = {:.17g}, v = {:.17g}) and "
                   "{} (slot {}, x = {:.17g}, v = {:.17g}): gap {:.3e}, closing speed {:.3e}, overlap / |closing| = "
                   "{:.3e}\n",
                   state.time, collisions, k, state.first_particle[k], state.position[k], state.velocity[k], j,
                   state.first_particle[j], state.position[j], state.velocity[j], d, closing,
                   closing != 0.0 ? -d / std::fabs(closing) : 0.0);
    }
}

double ulp(double x) { return std::nextafter(std::fabs(x), std::numeric_limits<double>::infinity()) - std::fabs(x); }

struct Row {
    double collisions, time, clusters, momentum, drift, bound, energy_ratio, max_rise, min_gap, min_gap_run,
        gap_resolution, order, nonfinite, cpu_seconds, rate, collision_rate_in_time, stored_min_gap,
        ring_length_drift;
};

const char* const column_names[] = {"collisions", "time", "clusters", "momentum", "momentum_drift",
                                    "momentum_drift_bound", "energy_ratio", "max_energy_rise", "min_gap",
                                    "min_gap_so_far", "gap_resolution", "ring_order", "nonfinite",
                                    "cpu_seconds", "collisions_per_cpu_second", "collisions_per_unit_time",
                                    "stored_min_gap", "ring_length_drift"};

std::vector<double> as_vector(const Row& r) {
    return {r.collisions, r.time,        r.clusters,       r.momentum,  r.drift,       r.bound,
            r.energy_ratio, r.max_rise,  r.min_gap,        r.min_gap_run, r.gap_resolution, r.order,
            r.nonfinite,  r.cpu_seconds, r.rate,           r.collision_rate_in_time, r.stored_min_gap,
            r.ring_length_drift};
}

void print_header() {
    fmt::print("# {:>10} {:>10} {:>6} {:>9} {:>9} {:>10} {:>9} {:>9} {:>9} {:>8} {:>5} {:>3} {:>8} {:>8} {:>8}\n",
               "collisions", "t", "clust", "dP/S0", "bound", "E/E0", "rise", "gap", "gap_min", "res", "order",
               "bad", "cpu_s", "coll/s", "dC/dt");
    std::fflush(stdout);
}

void print_row(const Row& r) {
    fmt::print("  {:>10.4g} {:>10.4g} {:>6} {:>9.2e} {:>9.2e} {:>10.4e} {:>9.2e} {:>9.2e} {:>9.2e} {:>8.1e} {:>5} "
               "{:>3} {:>8.1f} {:>8.3g} {:>8.3g}\n",
               r.collisions, r.time, static_cast<std::int64_t>(r.clusters), r.drift, r.bound, r.energy_ratio,
               r.max_rise, r.min_gap, r.min_gap_run, r.gap_resolution, static_cast<int>(r.order),
               static_cast<std::int64_t>(r.nonfinite), r.cpu_seconds, r.rate, r.collision_rate_in_time);
    std::fflush(stdout);
}

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    shockgas::SimulationParameters p;
    p.particles = 1000;
    p.collision.restitution = 0.5;
    p.collision.velocity_threshold = 1e-2;
    p.engine = "event";
    std::string subthreshold = "elastic";
    std::int64_t realization = 0;
    double target_collisions = 1e8;
    double record_every = 1e8;
    int records_per_decade = 1;
    double chunk_collisions = 1e6;
    std::string output;
    bool check = false;
    double inject_momentum_error = 0.0;
    bool stop_on_disorder = false;
    bool reference = false;

    CLI::App app{"shockgas-drift: drift of total momentum, kinetic energy and the smallest gap over one long "
                 "realization (engine chosen by make_engine). Units: initial spacing 1, velocity scale 1."};
    app.add_option("-N,--particles", p.particles, "number of particles N (>= 2)")->capture_default_str();
    app.add_option("--ring-length", p.ring_length, "ring length L; 0 means L = N")->capture_default_str();
    app.add_option("-r,--restitution", p.collision.restitution, "restitution r in [0, 1]")->capture_default_str();
    app.add_option("-d,--threshold", p.collision.velocity_threshold, "velocity threshold delta")
        ->capture_default_str();
    app.add_option("--subthreshold", subthreshold, "sub-threshold mechanism: elastic or sticky")
        ->capture_default_str();
    app.add_option("-s,--seed", p.seed, "random seed, 0 .. 2^63 - 1")->check(shockgas::cli::seed_in_range)->capture_default_str();
    app.add_option("--realization", realization, "realization index (seed stream)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("-c,--collisions", target_collisions, "stop after this many collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--record-every", record_every, "print a row every this many collisions (and at each decade)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--records-per-decade", records_per_decade, "log-spaced rows per decade of collisions")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--chunk", chunk_collisions, "collisions per advance_to call (the checks run after each)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("-o,--output", output, "also write the rows to FILE.csv or FILE.h5 (with provenance)");
    app.add_flag("--check", check,
                 "exit 1 if the momentum drift or an energy rise exceeds its rounding bound, ring order breaks, a "
                 "value is non-finite or the run ends early (equal masses, no merges only)");
    app.add_option("--engine", p.engine,
                   "engine as for shockgas-sim: event (the windowed engine where it applies), passthrough, hybrid, auto")
        ->capture_default_str();
    app.add_flag("--reference", reference,
                 "run EventEngine, the global-order loop the fast engine is bit-identical to (slower), and read its "
                 "stored gaps: smallest stored gap and ring-length drift sum(gaps) - L per row");
    app.add_flag("--stop-on-disorder", stop_on_disorder,
                 "print every pair out of ring order at the first chunk that has one, and stop there");
    app.add_option("--inject-momentum-error", inject_momentum_error,
                   "testing the check only: the engine starts from v[0] + this while P0 is the unperturbed one");

    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-drift"); status >= 0) return status;

    return shockgas::cli::run("shockgas-drift", [&] {
        p.collision.subthreshold = shockgas::subthreshold_from_string(subthreshold);
        shockgas::validate(p);
        if (!output.empty() && !ends_with(output, ".csv") && !ends_with(output, ".h5"))
            throw InputError("--output must end in .csv or .h5, got '" + output + "'");
        if (!output.empty()) shockgas::h5::check_writable(output);
        const bool merges = p.collision.restitution == 0.0 || p.collision.subthreshold == shockgas::Subthreshold::sticky;
        if (check && merges)
            throw InputError("--check needs a run without merges (r > 0, elastic sub-threshold): the rounding "
                             "bounds assume v' = v -+ h");

        const double ring_length = p.effective_ring_length();
        const double spacing = ring_length / static_cast<double>(p.particles);
        auto initial = shockgas::generate_initial_condition(p.particles, ring_length, p.seed, realization);
        const double mass = initial.mass.front();
        shockgas::ClusterState state;
        state.position = initial.position;
        state.velocity = initial.velocity;
        state.mass = initial.mass;
        const Snapshot start = inspect(state, ring_length);
        initial.velocity.front() += inject_momentum_error;

        std::unique_ptr<shockgas::Engine> engine;
        const shockgas::EventEngine* reference_engine = nullptr;
        if (reference) {
            auto global_loop = std::make_unique<shockgas::EventEngine>(initial, p.collision, p.collapse, nullptr);
            reference_engine = global_loop.get();
            engine = std::move(global_loop);
        } else {
            engine = shockgas::make_engine(p, initial, nullptr);
        }
        fmt::print("# shockgas-drift: N = {}, L = {}, r = {}, delta = {}, {} sub-threshold, seed {}, realization {}; "
                   "engine {} ({})\n",
                   p.particles, ring_length, p.collision.restitution, p.collision.velocity_threshold, subthreshold,
                   p.seed, realization, engine->name(), reference ? "EventEngine, --reference" : "make_engine");
        fmt::print("# P0 = {:.17g}, S0 = sum m|v0| = {:.17g}, E0 = {:.17g}, |v|max0 = {:.17g}\n",
                   static_cast<double>(start.momentum), static_cast<double>(start.momentum_scale),
                   static_cast<double>(start.energy), start.max_speed);
        fmt::print("# dP/S0 = |P - P0| / S0; gaps in units of L/N; rise = largest (E_k - E_(k-1))/E_(k-1) between "
                   "chunks of ~{:.0e} collisions\n",
                   chunk_collisions);
        print_header();

        // Row milestones: the log grid 10^(k / per_decade) and multiples of record_every.
        std::vector<double> milestones;
        for (int k = 0;; ++k) {
            const double c = std::round(std::pow(10.0, static_cast<double>(k) / records_per_decade));
            if (c >= target_collisions) break;
            milestones.push_back(c);
        }
        for (double c = record_every; c < target_collisions; c += record_every) milestones.push_back(c);
        milestones.push_back(target_collisions);
        std::sort(milestones.begin(), milestones.end());
        milestones.erase(std::unique(milestones.begin(), milestones.end()), milestones.end());

        std::vector<Row> rows;
        const std::clock_t cpu_start = std::clock();
        const auto cpu_seconds = [&] { return static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC; };
        double max_rise = 0.0;
        double min_gap_run = start.min_gap;
        std::int64_t nonfinite = 0;
        bool order_held = true;
        bool energy_within_bound = true;
        long double previous_energy = start.energy;
        double previous_max_speed = start.max_speed;
        std::uint64_t previous_chunk_collisions = 0;
        double last_row_time = 0.0;
        std::uint64_t last_row_collisions = 0;
        std::size_t next = 0;
        double dt = 1e-2 * spacing;  // first chunk: a few collisions; later chunks sized from the rate
        std::string ended = "reached the target";
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
            order_held = order_held && order;
            if (!order) print_disorder(state, ring_length, resolution, engine->collisions());
            nonfinite = std::max(nonfinite, now.nonfinite);
            min_gap_run = std::min(min_gap_run, now.min_gap);
            const double rise = static_cast<double>((now.energy - previous_energy) / previous_energy);
            max_rise = std::max(max_rise, rise);
            const double energy_bound =
                energy_rounding_bound(static_cast<double>(collisions - previous_chunk_collisions), mass,
                                      previous_max_speed, static_cast<double>(previous_energy),
                                      static_cast<double>(p.particles));
            if (rise > energy_bound) {
                energy_within_bound = false;
                fmt::print("# energy rose by {:.3e} (relative) over collisions {}..{}: above the rounding bound "
                           "{:.3e}\n",
                           rise, previous_chunk_collisions, collisions, energy_bound);
            }
            previous_energy = now.energy;
            previous_max_speed = now.max_speed;
            previous_chunk_collisions = collisions;

            const bool stopped =
                !running || engine->cluster_count() == 1 || idle_chunks > 60 || (stop_on_disorder && !order);
            if (static_cast<double>(collisions) >= milestones[next] || stopped) {
                Row row{};
                row.collisions = static_cast<double>(collisions);
                row.time = engine->time();
                row.clusters = static_cast<double>(engine->cluster_count());
                row.momentum = static_cast<double>(now.momentum);
                row.drift = static_cast<double>(std::fabs(now.momentum - start.momentum) / start.momentum_scale);
                row.bound = momentum_rounding_bound(row.collisions, mass, start.max_speed,
                                                    static_cast<double>(start.momentum_scale));
                row.energy_ratio = static_cast<double>(now.energy / start.energy);
                row.max_rise = max_rise;
                row.min_gap = now.min_gap / spacing;
                row.min_gap_run = min_gap_run / spacing;
                row.gap_resolution = resolution / spacing;
                row.order = order_held ? 1.0 : 0.0;
                row.nonfinite = static_cast<double>(nonfinite);
                row.cpu_seconds = cpu_seconds();
                row.rate = row.cpu_seconds > 0 ? row.collisions / row.cpu_seconds : 0.0;
                row.collision_rate_in_time =
                    row.time > last_row_time ? static_cast<double>(collisions - last_row_collisions) /
                                                   (row.time - last_row_time)
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
                rows.push_back(row);
                print_row(row);
                if (reference_engine != nullptr)
                    fmt::print("#   stored gaps: smallest {:.3e} L/N, sum(gaps) - L = {:.3e}\n", row.stored_min_gap,
                               row.ring_length_drift);
                std::fflush(stdout);
                while (next < milestones.size() && static_cast<double>(collisions) >= milestones[next]) ++next;
            }
            if (stopped) {
                ended = !order ? "stopped at ring disorder"
                        : !running ? "engine stopped (collapse)"
                        : engine->cluster_count() == 1 ? "one cluster left: no more collisions"
                                                       : "no collisions in 60 chunks";
                break;
            }

            // Next chunk: about chunk_collisions at the rate just seen, within a
            // factor 4 of this chunk's length so one odd chunk cannot derail it.
            const double wanted = std::min(chunk_collisions, milestones[next] - static_cast<double>(collisions));
            idle_chunks = done > 0 ? 0 : idle_chunks + 1;
            const double proposal = done > 0 ? wanted / (done / dt) : 4.0 * dt;
            dt = std::clamp(proposal, 0.25 * dt, 4.0 * dt);
        }

        const Row& last = rows.back();
        fmt::print("# {}: {} collisions, t = {:.6g}, {:.1f} s CPU, {:.3g} collisions/s; final dP/S0 = {:.3e} "
                   "(bound {:.3e}); max energy rise {:.3e}; smallest gap {:.3e} L/N; ring order {}; non-finite {}\n",
                   ended, last.collisions, last.time, last.cpu_seconds, last.rate, last.drift, last.bound,
                   max_rise, last.min_gap_run, order_held ? "held" : "BROKEN", nonfinite);

        if (!output.empty()) {
            if (ends_with(output, ".csv")) {
                std::ofstream csv(output);
                if (!csv) throw InputError("cannot write '" + output + "'");
                for (std::size_t c = 0; c < std::size(column_names); ++c)
                    csv << (c ? "," : "") << column_names[c];
                csv << "\n";
                for (const Row& r : rows) {
                    const auto values = as_vector(r);
                    for (std::size_t c = 0; c < values.size(); ++c) csv << (c ? "," : "") << fmt::format("{:.17g}", values[c]);
                    csv << "\n";
                }
            } else {
                shockgas::h5::AtomicFile file(output);
                auto root = file.root();
                shockgas::write_provenance(root, "shockgas-drift");
                root.set_attribute("particles", static_cast<std::int64_t>(p.particles));
                root.set_attribute("ring_length", ring_length);
                root.set_attribute("restitution", p.collision.restitution);
                root.set_attribute("velocity_threshold", p.collision.velocity_threshold);
                root.set_attribute("subthreshold", subthreshold);
                root.set_attribute("seed", static_cast<std::int64_t>(p.seed));
                root.set_attribute("realization", realization);
                root.set_attribute("engine", engine->name());
                root.set_attribute("target_collisions", target_collisions);
                root.set_attribute("ended", ended);
                root.set_attribute("initial_momentum", static_cast<double>(start.momentum));
                root.set_attribute("momentum_scale", static_cast<double>(start.momentum_scale));
                root.set_attribute("initial_energy", static_cast<double>(start.energy));
                root.set_attribute("momentum_drift_definition", "|P - P0| / sum m |v0|");
                root.set_attribute("gap_units", "mean spacing L/N");
                for (std::size_t c = 0; c < std::size(column_names); ++c) {
                    std::vector<double> column;
                    for (const Row& r : rows) column.push_back(as_vector(r)[c]);
                    root.write(column_names[c], column);
                }
                file.commit();
            }
        }

        if (check) {
            bool ok = true;
            const auto fail = [&](const std::string& why) {
                fmt::print(stderr, "shockgas-drift: check failed: {}\n", why);
                ok = false;
            };
            if (last.collisions < target_collisions) fail("run ended early: " + ended);
            if (last.drift > last.bound)
                fail(fmt::format("momentum drift {:.3e} exceeds the rounding bound {:.3e}", last.drift, last.bound));
            if (!energy_within_bound) fail("kinetic energy rose beyond rounding");
            if (!order_held) fail("ring order broken (a gap below -resolution)");
            if (reference_engine != nullptr) {
                const double bound = ring_length_rounding_bound(last.collisions, spacing);
                if (!(std::fabs(last.ring_length_drift) <= bound))
                    fail(fmt::format("ring length drift sum(gaps) - L = {:.3e} exceeds the rounding bound {:.3e}",
                                     last.ring_length_drift, bound));
            }
            if (nonfinite > 0) fail("non-finite values");
            return ok ? 0 : 1;
        }
        return 0;
    });
}
