// shockgas-burgers: the Burgers velocity profile from the initial condition of
// a particle run, for Fig. 5 (docs/continuum.md: Burgers with nu -> 0 is the sticky
// gas; shocks <-> clusters, v = (x - q)/t between shocks, Eq. 7).
//
//   shockgas-burgers --run RUN.h5 [--realization k] [--time t] [--cells-per-particle k]
//                    [--viscosity nu1,nu2,...] [--points P] --output profile.dat
//                    [--summary vars.gp] [--study study.dat]
//   shockgas-burgers --particles N [--ring-length L] --seed S --time t ...   (the same initial
//                    condition shockgas-sim draws) or --init FILE.h5 (none of these with --run: a
//                    run's start is its own)
// The profile is built on the lattice of the particles' start (burgers.hpp): a run's or an
// init file's particles must be equally spaced, as shockgas-sim --positions lattice places them.
//
// Every text output begins with '#' lines naming this program's version, the date and the
// start (seed, realization and law, or the run or init file).
// profile.dat: block 0 "x v_inviscid v_nu..." on P equally spaced points; block 1 the
// inviscid shocks "position mass velocity jump/v_rms". With --run and a snapshot at t,
// the shocks found in the particles (shockgas::analysis::find_shocks, the Fig. 5 detector)
// are matched to the Burgers shocks with the same jump criterion (drop >= v_rms), and the
// distances are printed and written to --summary as gnuplot variables.
// --study: nu -> 0 and grid-refinement convergence tables (docs/continuum.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/io/initial_condition.hpp"
#include "shockgas/analysis/burgers_comparison.hpp"
#include "shockgas/analysis/shocks.hpp"
#include "shockgas/analysis/burgers.hpp"
#include "shockgas/io/checksum.hpp"
#include "shockgas/cli/cli.hpp"
#include "shockgas/io/h5.hpp"
#include "shockgas/io/memory_limits.hpp"
#include "shockgas/io/output.hpp"
#include "shockgas/io/provenance.hpp"
#include "shockgas/model/state.hpp"
#include "shockgas/io/text_file.hpp"

using shockgas::burgers::Shock;
using shockgas::burgers::Solver;

int main(int argc, char** argv) {
    CLI::App app{"shockgas-burgers: inviscid and viscous Burgers profiles from a particle run's initial condition"};
    app.set_version_flag("--version", "shockgas-burgers " + shockgas::build_info().version);
    std::string run_path, init_path, output, summary, study;
    std::int64_t particles = 0, realization = 0, cells_per_particle = 4, points = 0;
    double ring_length = 0.0, time = 0.0, jump_fraction = 1.0;
    std::uint64_t seed = 1;
    std::vector<double> viscosities;
    auto* run_option =
        app.add_option("--run", run_path,
                       "shockgas-sim output: N, L, seed (or init_file) and the snapshot time; its start must be "
                       "equally spaced (--positions lattice, the default)")
            ->check(CLI::ExistingFile);
    auto* init_option = app.add_option("--init", init_path,
                                       "initial condition file (as shockgas-sim --init) of equally spaced particles")
                            ->check(CLI::ExistingFile);
    auto* particles_option =
        app.add_option("-N,--particles", particles, "particles (with --seed: shockgas-sim's initial condition)");
    auto* ring_length_option = app.add_option("-L,--ring-length", ring_length, "ring length (default N)");
    auto* seed_option = app.add_option("-s,--seed", seed, "seed (as shockgas-sim)")
                            ->check(shockgas::cli::seed_in_range)
                            ->capture_default_str();
    // --run takes the start from the run itself (its N, L, seed and initial law, or its init file
    // checked against the run's init_file_sha256). -N, -L and -s beside it were ignored without a
    // word until 2026-11-27 (the profile was the run's, whatever they said); an --init would replace
    // that start unchecked, and the run's particles would be compared with another start's profile.
    const auto run_supplies = shockgas::cli::exclude(
        run_option, {init_option, particles_option, ring_length_option, seed_option},
        "--run takes the initial condition from the run (its N, L, seed and law, or its init file)");
    auto* realization_option = app.add_option("--realization", realization, "realization")->capture_default_str();
    // --init's file is the start itself (its N, L and velocities): -N, -L, -s and --realization beside it
    // were ignored without a word as well.
    const auto init_supplies =
        shockgas::cli::exclude(init_option, {particles_option, ring_length_option, seed_option, realization_option},
                               "--init's file is the initial condition itself (its N, L and velocities)");
    app.add_option("-t,--time", time, "time (default: the run's first snapshot time)");
    app.add_option("--cells-per-particle", cells_per_particle, "grid cells per particle")->capture_default_str();
    app.add_option("--viscosity", viscosities, "viscous profiles (Hopf-Cole) at these nu")->delimiter(',');
    app.add_option("--points", points, "output points (default: 4 per particle)");
    app.add_option("--jump-fraction", jump_fraction, "a counted shock drops v by >= this x v_rms")->capture_default_str();
    app.add_option("-o,--output", output, "profile data file")->required();
    app.add_option("--summary", summary, "gnuplot variables: shock counts and particle-vs-Burgers distances");
    app.add_option("--study", study, "convergence tables (nu -> 0, grid refinement)");
    if (const int status = shockgas::cli::parse(app, argc, argv, "shockgas-burgers", {run_supplies, init_supplies}); status >= 0)
        return status;

    return shockgas::cli::run("shockgas-burgers", [&] {
        // Written as !(x > 0) so that NaN is refused too.
        if (cells_per_particle < 1) throw shockgas::InputError("--cells-per-particle must be at least 1");
        if (time != 0.0 && !(time > 0.0 && std::isfinite(time)))
            throw shockgas::InputError(fmt::format("--time must be positive and finite, not {}", time));
        for (double nu : viscosities)
            if (!(nu > 0.0 && std::isfinite(nu)))
                throw shockgas::InputError(fmt::format("--viscosity must be positive and finite, not {}", nu));
        if (!(jump_fraction >= 0.0 && std::isfinite(jump_fraction)))
            throw shockgas::InputError(fmt::format("--jump-fraction must be >= 0 and finite, not {}", jump_fraction));
        if (points < 0) throw shockgas::InputError("--points must be >= 0 (0: four per particle)");
        if (realization < 0) throw shockgas::InputError("--realization must be >= 0");
        // Every output can be written and none may replace an input (h5::check_not_an_input),
        // checked before the work.
        for (const std::string* path : {&output, &summary, &study})
            if (!path->empty()) {
                shockgas::check_text_writable(*path);
                shockgas::h5::check_not_an_input(*path, {run_path, init_path});
            }
        // Each output names its own file: written one after another, a shared
        // name would keep only the last (the profile lost under the summary).
        const std::vector<std::pair<const char*, const std::string*>> outputs{
            {"-o", &output}, {"--summary", &summary}, {"--study", &study}};
        for (std::size_t a = 0; a < outputs.size(); ++a)
            for (std::size_t b = a + 1; b < outputs.size(); ++b)
                if (!outputs[a].second->empty() && !outputs[b].second->empty() &&
                    std::filesystem::weakly_canonical(*outputs[a].second) ==
                        std::filesystem::weakly_canonical(*outputs[b].second))
                    throw shockgas::InputError(fmt::format("{} and {} name the same file '{}': give each its own",
                                                           outputs[a].first, outputs[b].first, *outputs[a].second));
        // The memory a solve of n particles takes, refused before the work when
        // more than the machine offers (as shockgas-sim refuses a run). Bytes
        // measured with /usr/bin/time (2026-11-27): about 150 per particle (the
        // start and the grid), 45 per output point (4 per particle by default)
        // and 20 more per point and viscous profile; rounded up.
        const auto check_memory = [&](std::int64_t n) {
            const double profile_points = points > 0 ? static_cast<double>(points) : 4.0 * static_cast<double>(n);
            const double needed = 200.0 * static_cast<double>(n) * static_cast<double>(cells_per_particle) +
                                  profile_points * (48.0 + 24.0 * static_cast<double>(viscosities.size()));
            std::string source;
            const double available = shockgas::available_memory_bytes(&source);
            if (needed > available)
                throw shockgas::InputError(fmt::format("not enough memory: N = {} needs about {}, but {} may be "
                                                       "used ({}); give a smaller N, --points or --cells-per-particle",
                                                       n, shockgas::format_bytes(needed),
                                                       shockgas::format_bytes(available), source));
        };
        shockgas::InitialCondition initial;
        std::vector<shockgas::analysis::Snapshot> snapshots;
        // The initial condition's law and realization number: a run's own, read from it,
        // else shockgas-sim's defaults for --particles and --seed.
        shockgas::InitialLaw law;
        std::int64_t first_realization = 0;
        std::string init_sha256;
        // What the start was, for the outputs' headers (two profiles of other seeds or runs
        // differed in nothing else), and the file it came from, for the lattice refusal below.
        std::string start, start_file;
        if (!run_path.empty()) {
            const shockgas::OutputFile run = shockgas::read_output(run_path);
            const shockgas::SimulationParameters& p = run.parameters;
            if (realization >= p.realizations)
                throw shockgas::InputError(fmt::format("--realization {}: '{}' holds realizations 0 to {}", realization,
                                                       run_path, p.realizations - 1));
            particles = p.particles;
            ring_length = p.effective_ring_length();
            seed = p.seed;
            law = p.initial_law;
            // A part of an ensemble (--first-realization F) numbers its realizations from 0
            // in the file, but drew realization k's start as realization F + k.
            first_realization = p.first_realization;
            if (!p.init_file.empty()) {
                init_path = p.init_file;
                init_sha256 = p.init_file_sha256;
            }
            start = p.init_file.empty()
                        ? fmt::format("run '{}' realization {} (drawn as realization {} of seed {}, positions {}, "
                                      "velocities {})",
                                      run_path, realization, first_realization + realization, seed,
                                      to_string(law.positions), to_string(law.velocities))
                        : fmt::format("run '{}' realization {} (init file '{}')", run_path, realization, p.init_file);
            start_file = p.init_file.empty() ? fmt::format("'{}'", run_path)
                                             : fmt::format("the init file '{}' of '{}'", p.init_file, run_path);
            snapshots = shockgas::analysis::snapshots_from(run.result, ring_length);
            std::erase_if(snapshots, [&](const auto& s) { return s.realization != realization; });
            if (time <= 0.0 && !snapshots.empty()) time = snapshots.front().time;
        }
        if (!init_path.empty()) {
            // The run names its init file by path; refuse a file at that path that is not the one it ran.
            if (!init_sha256.empty() && shockgas::file_sha256(init_path) != init_sha256)
                throw shockgas::InputError(fmt::format("'{}' is not the initial condition '{}' was run from (its "
                                                       "SHA-256 differs from the run's init_file_sha256)",
                                                       init_path, run_path));
            initial = shockgas::read_initial_condition(init_path);
            check_memory(initial.size());
            if (run_path.empty()) {
                start = fmt::format("init file '{}'", init_path);
                start_file = start;
            }
        } else {
            if (particles < 2) throw shockgas::InputError("give --run, --init or --particles (at least 2)");
            check_memory(particles);
            if (!(ring_length > 0.0)) ring_length = static_cast<double>(particles);
            initial = shockgas::generate_initial_condition(particles, ring_length, seed, first_realization + realization,
                                                           law);
            if (run_path.empty())
                start = fmt::format("seed {} realization {} (positions {}, velocities {}, as shockgas-sim draws them)",
                                    seed, realization, to_string(law.positions), to_string(law.velocities));
        }
        // The profile is built on the lattice of the particles' start (grid_from_particles:
        // particle i's cells centred on x_0 + i L/N); a start with other positions (a run made
        // with --positions uniform, an init file's own) has no profile here. Refused naming its
        // file before the work (the library's own refusal said only "particle 1").
        if (const std::int64_t off = shockgas::burgers::first_off_lattice(initial); off >= 0)
            throw shockgas::InputError(fmt::format(
                "{} starts from particles that are not equally spaced (particle {} is off the lattice x_0 + i L/N): "
                "the Burgers profile is built on the lattice of the particles' start, so it needs equally spaced "
                "particles, as shockgas-sim --positions lattice (the default) places them",
                start_file.empty() ? std::string("the start") : start_file, off));
        if (!(time > 0.0)) throw shockgas::InputError("no time: give --time or a run with snapshots");
        const std::int64_t n = initial.size();
        const double length = initial.ring_length;
        if (points <= 0) points = 4 * n;
        const Solver solver(shockgas::burgers::grid_from_particles(initial, cells_per_particle * n));
        const auto x = shockgas::burgers::sample_points(length, points);
        const auto v0 = solver.inviscid(x, time);
        std::vector<std::vector<double>> viscous;
        for (double nu : viscosities) viscous.push_back(solver.viscous(x, time, nu));
        const double v_rms = std::sqrt(solver.temperature(time));

        // The texts are built here and written at the end, each through shockgas::TextFile.
        // Each begins with the program's version, the date and the start (provenance_comment).
        const std::string provenance = shockgas::provenance_comment("shockgas-burgers", start, true);
        std::string profile = provenance, convergence = provenance;
        fmt::format_to(std::back_inserter(profile), "# Burgers profile at t = {:.9g}: N = {}, L = {:.9g}, {} cells per particle, v_rms = {:.6g}\n",
                   time, n, length, cells_per_particle, v_rms);
        fmt::format_to(std::back_inserter(profile), "# x v_inviscid");
        for (double nu : viscosities) fmt::format_to(std::back_inserter(profile), " v_nu={:g}", nu);
        fmt::format_to(std::back_inserter(profile), "\n");
        for (std::size_t j = 0; j < x.size(); ++j) {
            fmt::format_to(std::back_inserter(profile), "{:.10g} {:.10g}", x[j], v0[j]);
            for (const auto& v : viscous) fmt::format_to(std::back_inserter(profile), " {:.10g}", v[j]);
            fmt::format_to(std::back_inserter(profile), "\n");
        }
        fmt::format_to(std::back_inserter(profile), "\n\n# shock_position mass velocity jump_over_v_rms\n");
        for (const Shock& s : solver.shocks(time))
            fmt::format_to(std::back_inserter(profile), "{:.10g} {:.10g} {:.10g} {:.6g}\n", s.position, s.mass(),
                           s.velocity, s.mass() / time / v_rms);

        const auto burgers_shocks = shockgas::analysis::strong_burgers_shocks(solver, time, jump_fraction);
        std::string vars = provenance + fmt::format("burgers_time = {:.10g}\nburgers_shock_count = {}\nburgers_v_rms = {:.10g}\n"
                                       "burgers_cells_per_particle = {}\n",
                                       time, burgers_shocks.size(), v_rms, cells_per_particle);
        fmt::print("Burgers at t = {:g}: {} shocks with drop >= {:g} v_rms (v_rms = {:.4g})\n", time,
                   burgers_shocks.size(), jump_fraction, v_rms);
        const auto snapshot = std::find_if(snapshots.begin(), snapshots.end(), [&](const auto& s) { return s.time == time; });
        if (snapshot != snapshots.end()) {
            const auto c = shockgas::analysis::compare_with_burgers(*snapshot, solver, time, jump_fraction, burgers_shocks, n);
            fmt::print("particle shocks from {}; mean |v - v_Burgers| / v_rms = {:.4g}\n",
                       c.clusters_are_shocks ? "clusters" : "the Fig. 5 detector", c.velocity_misfit);
            vars += fmt::format("burgers_velocity_misfit = {:.10g}\n", c.velocity_misfit);
            fmt::print("particles: {} shocks; distance to the nearest Burgers shock: median {:.4g}, max {:.4g} "
                       "(mean Burgers shock separation {:.4g}); {} within 0.1 separation; Burgers -> particles median {:.4g}\n",
                       c.particle_shocks, c.median_distance, c.max_distance, c.mean_separation, c.matched,
                       c.median_distance_reverse);
            vars += fmt::format("burgers_particle_shock_count = {}\nburgers_median_distance = {:.10g}\n"
                                "burgers_max_distance = {:.10g}\nburgers_mean_separation = {:.10g}\n"
                                "burgers_matched = {}\nburgers_median_distance_reverse = {:.10g}\n",
                                c.particle_shocks, c.median_distance, c.max_distance, c.mean_separation, c.matched,
                                c.median_distance_reverse);
        }
        if (!study.empty()) {
            const auto study_result = shockgas::analysis::burgers_convergence(initial, solver, x, v0, time, jump_fraction);
            fmt::format_to(std::back_inserter(convergence), "# nu -> 0 at {} cells per particle, t = {:g}: nu mean|v_nu - v_0| (v_rms = {:.6g})\n",
                       cells_per_particle, time, v_rms);
            for (const auto& row : study_result.viscous_limit)
                fmt::format_to(std::back_inserter(convergence), "{:g} {:.6g}\n", row.viscosity, row.mean_deviation);
            fmt::format_to(std::back_inserter(convergence), "\n\n# grid: cells_per_particle shocks(drop>=v_rms) median|dx| max|dx| mean|v - v_exact|\n");
            for (const auto& level : study_result.grid) {
                if (level.skipped)
                    fmt::format_to(std::back_inserter(convergence), "# {:g}: skipped, N = {} is not a multiple of {}\n",
                                   level.cells_per_particle, n, std::llround(1.0 / level.cells_per_particle));
                else
                    fmt::format_to(std::back_inserter(convergence), "{:g} {} {:.6g} {:.6g} {:.6g}\n", level.cells_per_particle,
                                   level.strong_shocks, level.median_shift, level.max_shift, level.mean_deviation);
            }
        }
        // Each written beside its name and closed (where a full disk shows) before any is
        // renamed into place: a failure leaves none of them, nor one that looks whole.
        std::vector<std::unique_ptr<shockgas::TextFile>> files;
        for (const auto& [path, text] : {std::pair{&output, &profile}, std::pair{&summary, &vars},
                                         std::pair{&study, &convergence}}) {
            if (path->empty()) continue;
            files.push_back(std::make_unique<shockgas::TextFile>(*path));
            files.back()->write(*text);
            files.back()->close();
        }
        for (const auto& file : files) file->commit();
        return 0;
    });
}
