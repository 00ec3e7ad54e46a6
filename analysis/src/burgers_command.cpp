// SPDX-License-Identifier: GPL-3.0-or-later
// shockgas-burgers' work (shockgas/analysis/burgers_command.hpp).
#include "shockgas/analysis/burgers_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "shockgas/analysis/burgers.hpp"
#include "shockgas/analysis/burgers_comparison.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/io/checksum.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/initial_condition.hpp"
#include "shockgas/io/memory_limits.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/io/text_file.hpp"
#include "shockgas/model/parameters.hpp"
#include "shockgas/model/state.hpp"

namespace shockgas::analysis {

using burgers::Shock;
using burgers::Solver;

double burgers_memory_bytes(std::int64_t particles, std::int64_t cells_per_particle, std::int64_t points,
                            std::size_t viscosities) {
    const double n = static_cast<double>(particles);
    const double profile_points = points > 0 ? static_cast<double>(points) : 4.0 * n;
    return 200.0 * n * static_cast<double>(cells_per_particle) +
           profile_points * (48.0 + 24.0 * static_cast<double>(viscosities));
}

void check_burgers_memory(const BurgersRequest& request, std::int64_t particles) {
    const double needed =
        burgers_memory_bytes(particles, request.cells_per_particle, request.points, request.viscosities.size());
    std::string source;
    const double available = available_memory_bytes(&source);
    if (needed > available)
        throw InputError(
            fmt::format("not enough memory: N = {} needs about {}, but {} may be used ({}); give a "
                        "smaller N, --points or --cells-per-particle",
                        particles, format_bytes(needed), format_bytes(available), source));
}

namespace {

// The request's values, and its outputs: each can be written, none replaces an input or another.
void check_request(const BurgersRequest& request) {
    // Written as !(x > 0) so that NaN is refused too.
    if (request.cells_per_particle < 1) throw InputError("--cells-per-particle must be at least 1");
    if (request.time != 0.0 && !(request.time > 0.0 && std::isfinite(request.time)))
        throw InputError(fmt::format("--time must be positive and finite, not {}", request.time));
    for (double nu : request.viscosities)
        if (!(nu > 0.0 && std::isfinite(nu)))
            throw InputError(fmt::format("--viscosity must be positive and finite, not {}", nu));
    if (!(request.jump_fraction >= 0.0 && std::isfinite(request.jump_fraction)))
        throw InputError(fmt::format("--jump-fraction must be >= 0 and finite, not {}", request.jump_fraction));
    if (request.points < 0) throw InputError("--points must be >= 0 (0: four per particle)");
    if (request.realization < 0) throw InputError("--realization must be >= 0");
    // Every output can be written and none may replace an input (h5::check_not_an_input),
    // checked before the work.
    for (const std::string* path : {&request.output, &request.summary, &request.study})
        if (!path->empty()) {
            check_text_writable(*path);
            h5::check_not_an_input(*path, {request.run_path, request.init_path});
        }
    // Each output names its own file: written one after another, a shared
    // name would keep only the last (the profile lost under the summary).
    const std::vector<std::pair<const char*, const std::string*>> outputs{
        {"-o", &request.output}, {"--summary", &request.summary}, {"--study", &request.study}};
    for (std::size_t a = 0; a < outputs.size(); ++a)
        for (std::size_t b = a + 1; b < outputs.size(); ++b)
            if (!outputs[a].second->empty() && !outputs[b].second->empty() &&
                std::filesystem::weakly_canonical(*outputs[a].second) ==
                    std::filesystem::weakly_canonical(*outputs[b].second))
                throw InputError(fmt::format("{} and {} name the same file '{}': give each its own", outputs[a].first,
                                             outputs[b].first, *outputs[a].second));
}

// What the profile starts from, with the run's snapshots of the realization (none without a run)
// and what the start was, for the outputs' headers.
struct Start {
    InitialCondition initial;
    std::vector<Snapshot> snapshots;
    std::string description;
};

// The start a request names: a run's (whose N, L, seed, law and time, or init file, replace
// the request's), an init file's, or the one shockgas-sim draws for N, L and the seed; refused
// unless its particles are equally spaced.
Start read_start(BurgersRequest& request) {
    Start result;
    InitialCondition& initial = result.initial;
    std::vector<Snapshot>& snapshots = result.snapshots;
    // The initial condition's law and realization number: a run's own, read from it,
    // else shockgas-sim's defaults for --particles and --seed.
    InitialLaw law;
    std::int64_t first_realization = 0;
    std::string init_sha256;
    // What the start was, for the outputs' headers (two profiles of other seeds or runs
    // differed in nothing else), and the file it came from, for the lattice refusal below.
    std::string& start = result.description;
    std::string start_file;
    if (!request.run_path.empty()) {
        const OutputFile run = read_output(request.run_path);
        const SimulationParameters& p = run.parameters;
        if (request.realization >= p.realizations)
            throw InputError(fmt::format("--realization {}: '{}' holds realizations 0 to {}", request.realization,
                                         request.run_path, p.realizations - 1));
        request.particles = p.particles;
        request.ring_length = p.effective_ring_length();
        request.seed = p.seed;
        law = p.initial_law;
        // A part of an ensemble (--first-realization F) numbers its realizations from 0
        // in the file, but drew realization k's start as realization F + k.
        first_realization = p.first_realization;
        if (!p.init_file.empty()) {
            request.init_path = p.init_file;
            init_sha256 = p.init_file_sha256;
        }
        start = p.init_file.empty()
                    ? fmt::format(
                          "run '{}' realization {} (drawn as realization {} of seed {}, positions {}, "
                          "velocities {})",
                          request.run_path, request.realization, first_realization + request.realization, request.seed,
                          to_string(law.positions), to_string(law.velocities))
                    : fmt::format("run '{}' realization {} (init file '{}')", request.run_path, request.realization,
                                  p.init_file);
        start_file = p.init_file.empty() ? fmt::format("'{}'", request.run_path)
                                         : fmt::format("the init file '{}' of '{}'", p.init_file, request.run_path);
        snapshots = snapshots_from(run.result, request.ring_length);
        std::erase_if(snapshots, [&](const auto& s) { return s.realization != request.realization; });
        if (request.time <= 0.0 && !snapshots.empty()) request.time = snapshots.front().time;
    }
    if (!request.init_path.empty()) {
        // The run names its init file by path; refuse a file at that path that is not the one it ran.
        if (!init_sha256.empty() && file_sha256(request.init_path) != init_sha256)
            throw InputError(
                fmt::format("'{}' is not the initial condition '{}' was run from (its "
                            "SHA-256 differs from the run's init_file_sha256)",
                            request.init_path, request.run_path));
        initial = read_initial_condition(request.init_path);
        check_burgers_memory(request, initial.size());
        if (request.run_path.empty()) {
            start = fmt::format("init file '{}'", request.init_path);
            start_file = start;
        }
    } else {
        if (request.particles < 2) throw InputError("give --run, --init or --particles (at least 2)");
        check_burgers_memory(request, request.particles);
        if (!(request.ring_length > 0.0)) request.ring_length = static_cast<double>(request.particles);
        initial = generate_initial_condition(request.particles, request.ring_length, request.seed,
                                             first_realization + request.realization, law);
        if (request.run_path.empty())
            start = fmt::format("seed {} realization {} (positions {}, velocities {}, as shockgas-sim draws them)",
                                request.seed, request.realization, to_string(law.positions), to_string(law.velocities));
    }
    // The profile is built on the lattice of the particles' start (grid_from_particles:
    // particle i's cells centred on x_0 + i L/N); a start with other positions (a run made
    // with --positions uniform, an init file's own) has no profile here. Refused naming its
    // file before the work (the library's own refusal said only "particle 1").
    if (const std::int64_t off = burgers::first_off_lattice(initial); off >= 0)
        throw InputError(fmt::format(
            "{} starts from particles that are not equally spaced (particle {} is off the lattice x_0 + i L/N): "
            "the Burgers profile is built on the lattice of the particles' start, so it needs equally spaced "
            "particles, as shockgas-sim --positions lattice (the default) places them",
            start_file.empty() ? std::string("the start") : start_file, off));
    return result;
}

}  // namespace

void run_burgers(BurgersRequest request) {
    check_request(request);
    const Start start = read_start(request);
    if (!(request.time > 0.0)) throw InputError("no time: give --time or a run with snapshots");
    const InitialCondition& initial = start.initial;
    const std::int64_t n = initial.size();
    const double length = initial.ring_length;
    if (request.points <= 0) request.points = 4 * n;
    const Solver solver(burgers::grid_from_particles(initial, request.cells_per_particle * n));
    const auto x = burgers::sample_points(length, request.points);
    const auto v0 = solver.inviscid(x, request.time);
    std::vector<std::vector<double>> viscous;
    for (double nu : request.viscosities) viscous.push_back(solver.viscous(x, request.time, nu));
    const double v_rms = std::sqrt(solver.temperature(request.time));

    // The texts are built here and written at the end, each through TextFile.
    // Each begins with the program's version, the date and the start (provenance_comment).
    const std::string provenance = provenance_comment("shockgas-burgers", start.description, true);
    std::string profile = provenance, convergence = provenance;
    fmt::format_to(std::back_inserter(profile),
                   "# Burgers profile at t = {:.9g}: N = {}, L = {:.9g}, {} cells per particle, v_rms = {:.6g}\n",
                   request.time, n, length, request.cells_per_particle, v_rms);
    fmt::format_to(std::back_inserter(profile), "# x v_inviscid");
    for (double nu : request.viscosities) fmt::format_to(std::back_inserter(profile), " v_nu={:g}", nu);
    fmt::format_to(std::back_inserter(profile), "\n");
    for (std::size_t j = 0; j < x.size(); ++j) {
        fmt::format_to(std::back_inserter(profile), "{:.10g} {:.10g}", x[j], v0[j]);
        for (const auto& v : viscous) fmt::format_to(std::back_inserter(profile), " {:.10g}", v[j]);
        fmt::format_to(std::back_inserter(profile), "\n");
    }
    fmt::format_to(std::back_inserter(profile), "\n\n# shock_position mass velocity jump_over_v_rms\n");
    for (const Shock& s : solver.shocks(request.time))
        fmt::format_to(std::back_inserter(profile), "{:.10g} {:.10g} {:.10g} {:.6g}\n", s.position, s.mass(),
                       s.velocity, s.mass() / request.time / v_rms);

    const auto burgers_shocks = strong_burgers_shocks(solver, request.time, request.jump_fraction);
    std::string vars = provenance + fmt::format(
                                        "burgers_time = {:.10g}\nburgers_shock_count = {}\nburgers_v_rms = {:.10g}\n"
                                        "burgers_cells_per_particle = {}\n",
                                        request.time, burgers_shocks.size(), v_rms, request.cells_per_particle);
    fmt::print("Burgers at t = {:g}: {} shocks with drop >= {:g} v_rms (v_rms = {:.4g})\n", request.time,
               burgers_shocks.size(), request.jump_fraction, v_rms);
    const auto snapshot = std::find_if(start.snapshots.begin(), start.snapshots.end(),
                                       [&](const auto& s) { return s.time == request.time; });
    if (snapshot != start.snapshots.end()) {
        const auto c = compare_with_burgers(*snapshot, solver, request.time, request.jump_fraction, burgers_shocks, n);
        fmt::print("particle shocks from {}; mean |v - v_Burgers| / v_rms = {:.4g}\n",
                   c.clusters_are_shocks ? "clusters" : "the Fig. 5 detector", c.velocity_misfit);
        vars += fmt::format("burgers_velocity_misfit = {:.10g}\n", c.velocity_misfit);
        fmt::print(
            "particles: {} shocks; distance to the nearest Burgers shock: median {:.4g}, max {:.4g} "
            "(mean Burgers shock separation {:.4g}); {} within 0.1 separation; Burgers -> particles median {:.4g}\n",
            c.particle_shocks, c.median_distance, c.max_distance, c.mean_separation, c.matched,
            c.median_distance_reverse);
        vars += fmt::format(
            "burgers_particle_shock_count = {}\nburgers_median_distance = {:.10g}\n"
            "burgers_max_distance = {:.10g}\nburgers_mean_separation = {:.10g}\n"
            "burgers_matched = {}\nburgers_median_distance_reverse = {:.10g}\n",
            c.particle_shocks, c.median_distance, c.max_distance, c.mean_separation, c.matched,
            c.median_distance_reverse);
    }
    if (!request.study.empty()) {
        const auto study_result = burgers_convergence(initial, solver, x, v0, request.time, request.jump_fraction);
        fmt::format_to(std::back_inserter(convergence),
                       "# nu -> 0 at {} cells per particle, t = {:g}: nu mean|v_nu - v_0| (v_rms = {:.6g})\n",
                       request.cells_per_particle, request.time, v_rms);
        for (const auto& row : study_result.viscous_limit)
            fmt::format_to(std::back_inserter(convergence), "{:g} {:.6g}\n", row.viscosity, row.mean_deviation);
        fmt::format_to(std::back_inserter(convergence),
                       "\n\n# grid: cells_per_particle shocks(drop>=v_rms) median|dx| max|dx| mean|v - v_exact|\n");
        for (const auto& level : study_result.grid) {
            if (level.skipped)
                fmt::format_to(std::back_inserter(convergence), "# {:g}: skipped, N = {} is not a multiple of {}\n",
                               level.cells_per_particle, n, std::llround(1.0 / level.cells_per_particle));
            else
                fmt::format_to(std::back_inserter(convergence), "{:g} {} {:.6g} {:.6g} {:.6g}\n",
                               level.cells_per_particle, level.strong_shocks, level.median_shift, level.max_shift,
                               level.mean_deviation);
        }
    }
    // Each written beside its name and closed (where a full disk shows) before any is
    // renamed into place: a failure leaves none of them, nor one that looks whole.
    std::vector<std::unique_ptr<TextFile>> files;
    for (const auto& [path, text] : {std::pair{&request.output, &profile}, std::pair{&request.summary, &vars},
                                     std::pair{&request.study, &convergence}}) {
        if (path->empty()) continue;
        files.push_back(std::make_unique<TextFile>(*path));
        files.back()->write(*text);
        files.back()->close();
    }
    for (const auto& file : files) file->commit();
}

}  // namespace shockgas::analysis
