// SPDX-License-Identifier: GPL-3.0-or-later
// bench_spheres: the disk and sphere engine's speed, as a table (docs/spheres.md,
// "Speed"). Each row: a start of N particles at phi, made and equilibrated
// (not timed), then `collisions` collisions with restitution r and threshold
// delta timed on one core (thread CPU time and wall time). The rows are the
// workloads the anchors were measured on, and N from 10^3 to 10^6.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/start.hpp"

namespace {

struct Workload {
    std::string name;
    int dimension;
    std::int64_t particles;
    double packing_fraction;
    double restitution;
    double threshold;
};

void run(const Workload& w, double collisions_per_particle, double equilibrate) {
    using namespace shockgas::spheres;
    SphereParameters p;
    p.dimension = w.dimension;
    p.particles = w.particles;
    p.packing_fraction = w.packing_fraction;
    p.melt_collisions_per_particle = equilibrate;
    validate(p);
    const SphereState start = make_start(p, 0);
    HardSphereEngine engine(start, shockgas::CollisionModel{w.restitution, w.threshold, shockgas::Subthreshold::elastic});
    const auto collisions = static_cast<std::uint64_t>(collisions_per_particle * static_cast<double>(w.particles) / 2.0);
    const double cpu0 = shockgas::spheres::thread_cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    engine.run_collisions(collisions);
    const double cpu = shockgas::spheres::thread_cpu_seconds() - cpu0;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    fmt::print("{:<22} {:>2} {:>8} {:>5} {:>5} {:>6} {:>11} {:>8.2f} {:>8.2f} {:>12.0f} {:>10.0f} {:>9.1f}\n", w.name,
               w.dimension, w.particles, w.packing_fraction, w.restitution, w.threshold,
               engine.counts().collisions(), cpu, wall, static_cast<double>(engine.counts().collisions()) / cpu,
               static_cast<double>(engine.counts().collisions()) / engine.time(),
               static_cast<double>(engine.memory_bytes()) / static_cast<double>(w.particles));
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Speed of the disk and sphere engine: collisions per CPU second on the anchors' workloads"};
    double collisions_per_particle = 20.0, equilibrate = 5.0;
    bool scaling = false, quick = false;
    std::string only;
    app.add_option("--collisions-per-particle", collisions_per_particle, "timed collisions per particle")
        ->capture_default_str();
    app.add_option("--equilibrate", equilibrate, "collisions per particle of the start's elastic run (not timed)")
        ->capture_default_str();
    app.add_flag("--scaling", scaling, "also N = 10^3 ... 10^6 (3D elastic, phi = 0.25)");
    app.add_flag("--quick", quick, "N = 10^4 instead of 10^5 (a smoke test)");
    app.add_option("--workload", only, "run only the workload of this name (e.g. '3D elastic')");
    CLI11_PARSE(app, argc, argv);
    const std::int64_t n3 = quick ? 10648 : 97556, n2 = quick ? 10000 : 99856;
    std::vector<Workload> workloads{
        {"3D elastic", 3, n3, 0.25, 1.0, 0.0},
        {"3D r=0.9 delta=1e-2", 3, n3, 0.25, 0.9, 1e-2},
        {"2D elastic", 2, n2, 0.25, 1.0, 0.0},
        {"2D r=0.9 delta=1e-2", 2, n2, 0.25, 0.9, 1e-2},
    };
    if (scaling)
        for (std::int64_t n : {1000, 10000, 100000, 1000000})
            workloads.push_back({fmt::format("3D elastic N={}", n), 3, n, 0.25, 1.0, 0.0});
    fmt::print("{:<22} {:>2} {:>8} {:>5} {:>5} {:>6} {:>11} {:>8} {:>8} {:>12} {:>10} {:>9}\n", "# workload", "d", "N",
               "phi", "r", "delta", "collisions", "CPU s", "wall s", "coll/CPU-s", "coll/time", "B/part");
    for (const auto& w : workloads)
        if (only.empty() || w.name == only) run(w, collisions_per_particle, equilibrate);
}
