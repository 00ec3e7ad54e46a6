// SPDX-License-Identifier: GPL-3.0-or-later
// The disk and sphere engine on hand-built cases: single collisions against the
// rule written out, the threshold, and adversarial starts (touching, grazing,
// three-body contacts, particles on cell walls) that must neither hang nor let
// particles pass through each other.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shockgas/model/state.hpp"
#include "shockgas/spheres/ensemble.hpp"
#include "shockgas/spheres/engine.hpp"
#include "shockgas/spheres/job.hpp"
#include "shockgas/spheres/start.hpp"

#include "calendar_queue.hpp"  // the engine's private header (sim/spheres/src)
#include "quaternary_heap.hpp"

using namespace shockgas;
using namespace shockgas::spheres;

namespace {

const CollisionModel elastic{1.0, 0.0, Subthreshold::elastic};

SphereState two_particles(int d, double box, std::vector<double> x, std::vector<double> v) {
    SphereState s;
    s.dimension = d;
    s.box_length = box;
    s.positions = std::move(x);
    s.velocities = std::move(v);
    return s;
}

// The closest pair's centre distance under the minimum image, over all pairs.
// A small inelastic run (r = 0.9, delta = 1e-2, phi = 0.2) with histograms at
// `first_sample` and t_max and a snapshot of 4^d field cells at `snapshot`:
// every dataset kind, for the tests that compare runs bit for bit.
SphereParameters inelastic_run(int d, std::int64_t particles, double t_max, int realizations, double first_sample,
                               double snapshot) {
    SphereParameters p;
    p.dimension = d;
    p.particles = particles;
    p.packing_fraction = 0.2;
    p.collision = {0.9, 1e-2, Subthreshold::elastic};
    p.t_max = t_max;
    p.realizations = realizations;
    p.histogram_times = {first_sample, t_max};
    p.snapshot_times = {snapshot};
    p.field_cells = 4;
    return p;
}

double closest_distance(const SphereState& s) {
    const int d = s.dimension;
    const auto n = static_cast<std::size_t>(s.particles());
    double closest = INFINITY;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            double r2 = 0.0;
            for (int k = 0; k < d; ++k) {
                double dx = s.positions[j * d + k] - s.positions[i * d + k];
                dx -= s.box_length * std::round(dx / s.box_length);
                r2 += dx * dx;
            }
            closest = std::min(closest, std::sqrt(r2));
        }
    return closest;
}

// Pairs may come closer than one diameter only by the round-off of the contact
// time and of positions of size L (a few ulp of 10): 10^-12 is far above that
// and far below any overlap a missed collision makes (~ speed x mean free time).
constexpr double overlap_tolerance = 1e-12;

}  // namespace

// Head-on: contact at t = 0.5; the rule gives v -> -r v for each (collision.hpp, Eq. (1)).
TEST(SpheresEngine, HeadOnCollisionFollowsTheRule) {
    HardSphereEngine engine(two_particles(3, 10.0, {2, 5, 5, 4, 5, 5}, {1, 0, 0, -1, 0, 0}),
                            CollisionModel{0.8, 0.0, Subthreshold::elastic});
    engine.advance_to(1.0);
    const auto v = engine.velocities();
    EXPECT_EQ(v[0], -0.8);
    EXPECT_EQ(v[3], 0.8);
    EXPECT_EQ(engine.counts().inelastic, 1u);
    const auto s = engine.state();
    EXPECT_NEAR(s.positions[0], 2.5 - 0.8 * 0.5, 1e-14);
}

// Oblique: only the normal component changes; the tangential one is kept.
TEST(SpheresEngine, ObliqueCollisionKeepsTangentialVelocity) {
    const double b = 0.6;  // impact parameter: contact normal (sqrt(1 - b^2), b)
    HardSphereEngine engine(two_particles(2, 20.0, {5, 10, 8, 10 + b}, {1, 0, 0, 0}),
                            CollisionModel{0.5, 0.0, Subthreshold::elastic});
    engine.advance_to(10.0);
    const auto v = engine.velocities();
    const double nx = std::sqrt(1 - b * b), ny = b;
    const double g = 1.0 * nx;             // normal relative speed
    const double kick = (1 + 0.5) * g / 2;  // (1 + r) g_n / 2
    EXPECT_NEAR(v[0], 1 - kick * nx, 1e-12);
    EXPECT_NEAR(v[1], -kick * ny, 1e-12);
    EXPECT_NEAR(v[2], kick * nx, 1e-12);
    EXPECT_NEAR(v[3], kick * ny, 1e-12);
    // Momentum exactly as before, to round-off.
    EXPECT_NEAR(v[0] + v[2], 1.0, 1e-15);
    EXPECT_NEAR(v[1] + v[3], 0.0, 1e-15);
}

// Below the threshold the collision is elastic; at or above it, inelastic.
TEST(SpheresEngine, ThresholdDecidesElasticOrInelastic) {
    for (double speed : {0.004, 0.006}) {
        HardSphereEngine engine(two_particles(3, 10.0, {2, 5, 5, 3.5, 5, 5}, {speed, 0, 0, -speed, 0, 0}),
                                CollisionModel{0.5, 0.01, Subthreshold::elastic});
        engine.advance_to(100.0);
        const auto v = engine.velocities();
        const double g = 2 * speed;
        const double expected = g < 0.01 ? -speed : -0.5 * speed;
        EXPECT_NEAR(v[0], expected, 1e-15) << "speed " << speed;
        EXPECT_EQ(engine.counts().elastic, g < 0.01 ? 1u : 0u);
    }
}

// A touching pair (distance exactly 1, or 10^-15 less by round-off) that
// approaches collides at once, at t = 0; a touching pair that recedes does not.
TEST(SpheresEngine, TouchingPairsCollideAtOnceOrSeparate) {
    for (double gap : {1.0, 1.0 - 1e-15}) {
        HardSphereEngine approaching(two_particles(2, 10.0, {3, 5, 3 + gap, 5}, {1, 0, -1, 0}), elastic);
        approaching.advance_to(0.0);
        EXPECT_EQ(approaching.counts().collisions(), 1u);
        approaching.advance_to(1.0);
        EXPECT_GE(closest_distance(approaching.state()), 1.0 - overlap_tolerance);
        HardSphereEngine receding(two_particles(2, 10.0, {3, 5, 3 + gap, 5}, {-1, 0, 1, 0}), elastic);
        receding.advance_to(1.0);
        EXPECT_EQ(receding.counts().collisions(), 0u);
    }
}

// A grazing collision (impact parameter 1 - 10^-15) happens and leaves the
// pair apart; an impact parameter of 1 + 10^-12 is a miss.
TEST(SpheresEngine, GrazingCollisions) {
    HardSphereEngine grazing(two_particles(3, 10.0, {1, 5, 5, 4, 5 + (1 - 1e-15), 5}, {1, 0, 0, 0, 0, 0}), elastic);
    grazing.advance_to(8.0);
    EXPECT_EQ(grazing.counts().collisions(), 1u);
    EXPECT_GE(closest_distance(grazing.state()), 1.0 - overlap_tolerance);
    HardSphereEngine miss(two_particles(3, 10.0, {1, 5, 5, 4, 5 + (1 + 1e-12), 5}, {1, 0, 0, 0, 0, 0}), elastic);
    miss.advance_to(8.0);
    EXPECT_EQ(miss.counts().collisions(), 0u);
}

// Three spheres in a row touching (a Newton's cradle) and a fourth striking
// them: the momentum passes down the row, elastic, and nothing overlaps.
TEST(SpheresEngine, ThreeBodyContactsPassMomentumOn) {
    HardSphereEngine engine(two_particles(3, 12.0, {1, 6, 6, 3, 6, 6, 4, 6, 6, 5, 6, 6}, {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}),
                            elastic);
    engine.advance_to(1.5);
    const auto v = engine.velocities();
    EXPECT_NEAR(v[9], 1.0, 1e-15);  // the last of the row leaves with the striker's velocity
    for (int i : {0, 3, 6}) EXPECT_NEAR(v[i], 0.0, 1e-15);
    EXPECT_EQ(engine.counts().collisions(), 3u);
    EXPECT_GE(closest_distance(engine.state()), 1.0 - overlap_tolerance);
}

// A dense 2D triangle of touching disks, each moving at random, many on cell
// walls: the engine resolves every contact at once and never overlaps.
TEST(SpheresEngine, ClusterOfTouchingDisksNeverOverlaps) {
    SphereState s;
    s.dimension = 2;
    s.box_length = 12.0;  // 12 cells of side 1: the rows sit on cell walls
    std::mt19937_64 random(7);
    for (int row = 0; row < 5; ++row)
        for (int column = 0; column <= row; ++column) {
            s.positions.push_back(3.0 + column - 0.5 * row);
            s.positions.push_back(3.0 + row * std::sqrt(3.0) / 2.0);
            s.velocities.push_back(unit_uniform(random) - 0.5);
            s.velocities.push_back(unit_uniform(random) - 0.5);
        }
    HardSphereEngine engine(s, CollisionModel{0.7, 1e-3, Subthreshold::elastic});
    const double p0x = [&] { double p = 0; for (std::size_t i = 0; i < s.velocities.size(); i += 2) p += s.velocities[i]; return p; }();
    for (double t = 0.0; t <= 20.0; t += 0.25) {
        engine.advance_to(t);
        ASSERT_GE(closest_distance(engine.state()), 1.0 - overlap_tolerance) << "t = " << t;
    }
    double px = 0;
    const auto v = engine.velocities();
    for (std::size_t i = 0; i < v.size(); i += 2) px += v[i];
    EXPECT_NEAR(px, p0x, 1e-13);
    EXPECT_GT(engine.counts().collisions(), 15u);
}

// A particle moving exactly along a cell wall and one at rest on a corner of
// four cells: crossings are found, the collision happens.
TEST(SpheresEngine, ParticlesOnCellWalls) {
    HardSphereEngine engine(two_particles(2, 10.0, {0.0, 5.0, 6.0, 5.0}, {1, 0, 0, 0}), elastic);
    engine.advance_to(10.0);  // contact at t = 5; the struck disk comes round the box to it again at t = 13
    EXPECT_EQ(engine.counts().collisions(), 1u);
    const auto v = engine.velocities();
    EXPECT_EQ(v[0], 0.0);
    EXPECT_EQ(v[2], 1.0);
    // Across the periodic boundary: 9.8 and 0.3 are 0.5 apart through the wall.
    HardSphereEngine across(two_particles(2, 10.0, {9.3, 5.0, 1.3, 5.0}, {1, 0, -1, 0}), elastic);
    across.advance_to(1.0);
    EXPECT_EQ(across.counts().collisions(), 1u);
}

TEST(SpheresEngine, RefusesOverlappingStarts) {
    EXPECT_THROW(HardSphereEngine(two_particles(2, 10.0, {3, 5, 3.9, 5}, {0, 0, 0, 0}), elastic), InputError);
    EXPECT_THROW(HardSphereEngine(two_particles(2, 2.5, {0.5, 0.5, 1.5, 1.5}, {0, 0, 0, 0}), elastic), InputError);
}

// The pure inelastic gas (delta = 0) of a dense 2D start collapses: the run
// ends, reported collapsed, instead of hanging (McNamara & Young's collapse).
TEST(SpheresEngine, InelasticCollapseIsDetected) {
    SphereParameters p;
    p.dimension = 2;
    p.particles = 400;
    p.packing_fraction = 0.4;
    p.collision = {0.3, 0.0, Subthreshold::elastic};
    p.melt_collisions_per_particle = 2.0;
    HardSphereEngine engine(make_start(p, 0), p.collision, p.collapse_speed);
    engine.advance_to(1e6);
    EXPECT_EQ(engine.status(), EngineStatus::collapsed);
    EXPECT_LT(engine.time(), 1e6);
}

TEST(SpheresParameters, RefusalsNameTheProblem) {
    SphereParameters p;
    auto message = [&](auto change) {
        SphereParameters q = p;
        change(q);
        try {
            validate(q);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message([](auto&) {}), "accepted");
    EXPECT_NE(message([](auto& q) { q.dimension = 4; }).find("not 2 or 3"), std::string::npos);
    EXPECT_NE(message([](auto& q) { q.packing_fraction = 0.37; }).find("--start lattice goes further"), std::string::npos);
    EXPECT_NE(message([](auto& q) { q.start = StartMethod::lattice; q.packing_fraction = 0.53; }).find("outside"),
              std::string::npos);
    EXPECT_NE(message([](auto& q) { q.particles = 2; }).find("less than 3"), std::string::npos);
    EXPECT_NE(message([](auto& q) { q.collision.restitution = 0.0; }).find("do not merge"), std::string::npos);
    EXPECT_NE(message([](auto& q) { q.collision.velocity_threshold = -1; }).find(">= 0"), std::string::npos);
    EXPECT_NE(message([](auto& q) { q.collision.subthreshold = Subthreshold::sticky; }).find("ring's rule"),
              std::string::npos);
}

// The same seed gives the same start and the same run, bit for bit, and the
// ensemble's datasets do not depend on the number of threads.
TEST(SpheresEngine, DeterministicForAnyThreadCount) {
    SphereParameters p;
    p.dimension = 3;
    p.particles = 500;
    p.packing_fraction = 0.2;
    p.t_max = 5.0;
    p.realizations = 3;
    p.histogram_times = {5.0};
    p.snapshot_times = {5.0};
    p.threads = 1;
    const SphereResult one = run_spheres(p);
    p.threads = 3;
    const SphereResult three = run_spheres(p);
    EXPECT_EQ(one.temperature, three.temperature);
    EXPECT_EQ(one.collisions_per_particle, three.collisions_per_particle);
    EXPECT_EQ(one.histograms[0].counts, three.histograms[0].counts);
    EXPECT_EQ(one.snapshots[0].positions, three.snapshots[0].positions);
    EXPECT_EQ(one.snapshots[0].density, three.snapshots[0].density);
}

// Output round trip: what is written is read back.
TEST(SpheresOutput, RoundTrip) {
    SphereParameters p;
    p.dimension = 2;
    p.particles = 300;
    p.packing_fraction = 0.2;
    p.t_max = 2.0;
    p.realizations = 2;
    p.histogram_times = {1.0};
    p.snapshot_times = {2.0};
    p.field_cells = 4;
    const SphereResult result = run_spheres(p);
    write_spheres_output("spheres_round_trip.h5", p, result);
    const SphereOutput back = read_spheres_output("spheres_round_trip.h5");
    EXPECT_EQ(back.parameters.particles, 300);
    EXPECT_EQ(back.parameters.histogram_times, p.histogram_times);
    EXPECT_TRUE(back.parameters.sample_times.empty());
    EXPECT_EQ(back.result.temperature, result.temperature);
    EXPECT_EQ(back.result.histograms[0].counts, result.histograms[0].counts);
    EXPECT_EQ(back.result.snapshots[0].velocity_field, result.snapshots[0].velocity_field);
    EXPECT_EQ(back.result.counts.collisions(), result.counts.collisions());
    EXPECT_EQ(back.spheres_sha256.size(), 64u);
}

// Parts (--first-realization k) joined by shockgas-merge's work equal one run
// of all their realizations, bit for bit; parts that are not one run's, or
// that leave a gap, are refused with the part named.
TEST(SpheresMerge, PartsEqualOneRun) {
    const SphereParameters p = inelastic_run(2, 300, 3.0, 5, 1.0, 3.0);
    const SphereResult whole = run_spheres(p);
    const std::string folder = ::testing::TempDir();
    std::vector<std::string> names;
    for (const auto& [first, count] : {std::pair{0, 2}, std::pair{2, 1}, std::pair{3, 2}}) {
        SphereParameters part = p;
        part.first_realization = first;
        part.realizations = count;
        names.push_back(folder + "spheres_part" + std::to_string(first) + ".h5");
        write_spheres_output(names.back(), part, run_spheres(part));
    }
    const std::string merged_path = folder + "spheres_merged.h5";
    EXPECT_EQ(merge_spheres_files(names, merged_path, "test"), 5);
    const SphereOutput merged = read_spheres_output(merged_path);
    EXPECT_EQ(merged.parameters.realizations, 5);
    EXPECT_EQ(merged.parameters.first_realization, 0);
    EXPECT_EQ(merged.result.temperature, whole.temperature);
    EXPECT_EQ(merged.result.velocity_kurtosis, whole.velocity_kurtosis);
    EXPECT_EQ(merged.result.end_time, whole.end_time);
    for (std::size_t h = 0; h < 2; ++h) EXPECT_EQ(merged.result.histograms[h].counts, whole.histograms[h].counts);
    EXPECT_EQ(merged.result.snapshots[0].positions, whole.snapshots[0].positions);
    EXPECT_EQ(merged.result.snapshots[0].density, whole.snapshots[0].density);
    EXPECT_EQ(merged.result.snapshots[0].velocity_field, whole.snapshots[0].velocity_field);
    EXPECT_EQ(merged.result.counts.collisions(), whole.counts.collisions());

    // A gap (realization 2 left out), parts out of order, and a part of another run.
    const auto refusal = [&](const std::vector<std::string>& parts) {
        try {
            merge_spheres_files(parts, folder + "spheres_refused.h5", "test");
        } catch (const InputError& error) {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(refusal({names[0], names[2]}).find("starts at realization 3, the parts before it end at 1"),
              std::string::npos);
    EXPECT_NE(refusal({names[1], names[0]}).find("starts at realization 0"), std::string::npos);
    SphereParameters other = p;
    other.first_realization = 2;
    other.realizations = 1;
    other.collision.restitution = 0.8;
    write_spheres_output(folder + "spheres_other.h5", other, run_spheres(other));
    EXPECT_NE(refusal({names[0], folder + "spheres_other.h5"}).find("restitution 0.9 vs 0.8"), std::string::npos);
}

// An engine restored from save() continues bit for bit as the one it was
// taken from, in 2D and 3D, inelastic with the threshold, mid-run (between
// samples, with stale events and delayed states pending).
TEST(SpheresEngine, SavedEngineContinuesBitForBit) {
    for (int d : {2, 3}) {
        SphereParameters p;
        p.dimension = d;
        p.particles = 800;
        p.packing_fraction = 0.25;
        p.collision = {0.8, 1e-2, Subthreshold::elastic};
        HardSphereEngine original(make_start(p, 3), p.collision);
        original.run_collisions(20000);
        HardSphereEngine restored(original.save(), p.collision);
        original.advance_to(original.time() + 5.0);
        restored.advance_to(restored.time() + 5.0);
        EXPECT_EQ(original.velocities(), restored.velocities()) << "d = " << d;
        EXPECT_EQ(original.state().positions, restored.state().positions) << "d = " << d;
        EXPECT_EQ(original.counts().collisions(), restored.counts().collisions());
        EXPECT_EQ(original.counts().stale_events, restored.counts().stale_events);
        EXPECT_GT(original.counts().collisions(), 20000u);
    }
}

// A run stopped mid-interval and resumed from its checkpoint gives the
// uninterrupted run's datasets bit for bit; a run without --resume refuses
// the checkpoint, and a resume with other parameters names what differs.
TEST(SpheresCheckpoint, StoppedAndResumedRunEqualsUninterrupted) {
    SphereParameters p = inelastic_run(3, 3000, 30.0, 3, 1.0, 10.0);
    p.threads = 2;
    const SphereResult whole = run_spheres(p);

    const std::string checkpoint = "spheres_resume.ckpt.h5";
    remove_spheres_checkpoint(checkpoint);
    std::atomic<bool> stop{true};  // raised from the start: every realization stops in its first interval
    SphereRunOptions options;
    options.checkpoint = checkpoint;
    options.stop = &stop;
    const SphereResult first = run_spheres(p, {}, options);
    EXPECT_TRUE(first.interrupted);
    SphereRunOptions again = options;
    EXPECT_THROW(run_spheres(p, {}, again), InputError);  // without --resume
    SphereParameters other = p;
    other.collision.restitution = 0.8;
    again.resume = true;
    try {
        run_spheres(other, {}, again);
        ADD_FAILURE() << "another run's checkpoint was accepted";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("restitution 0.8 vs 0.9"), std::string::npos) << error.what();
    }
    // Resume again and again with the flag raised: each time every running
    // realization gets 4096 events further (the engine reads the flag every
    // 4096 events) or through samples, saving at each, until the run is done.
    again.checkpoint_interval_seconds = 0.0;
    SphereResult last = run_spheres(p, {}, again);
    int resumes = 1;
    for (; last.interrupted && resumes < 100000; ++resumes) last = run_spheres(p, {}, again);
    EXPECT_GT(resumes, 10);
    EXPECT_FALSE(last.interrupted);
    EXPECT_EQ(last.temperature, whole.temperature);
    EXPECT_EQ(last.collisions_per_particle, whole.collisions_per_particle);
    EXPECT_EQ(last.velocity_kurtosis, whole.velocity_kurtosis);
    EXPECT_EQ(last.histograms[1].counts, whole.histograms[1].counts);
    EXPECT_EQ(last.snapshots[0].positions, whole.snapshots[0].positions);
    EXPECT_EQ(last.snapshots[0].density, whole.snapshots[0].density);
    EXPECT_EQ(last.counts.collisions(), whole.counts.collisions());
    remove_spheres_checkpoint(checkpoint);
}

// The calendar pops in exactly the ring's heap's order, (time, particle),
// through rescheduling, removals, equal times, far-future entries, a day
// width off by 10^6 both ways, and times that jump by decades (a cooling gas).
TEST(SpheresCalendar, PopsInTheHeapsOrder) {
    for (const double spread : {1e-6, 1.0, 1e6}) {
        const std::int32_t slots = 3000;
        shockgas::spheres::CalendarQueue calendar(slots);
        shockgas::QuaternaryHeap heap(slots);
        std::mt19937_64 random(11);
        double now = 0.0;
        for (std::int32_t s = 0; s < slots; ++s) {
            const double t = std::floor(unit_uniform(random) * 1000.0) * 1e-3 * spread;  // many equal times
            calendar.append_unordered(s, t);
            heap.append_unordered(s, t);
        }
        calendar.heapify();
        heap.heapify();
        for (int step = 0; step < 200000; ++step) {
            ASSERT_EQ(calendar.top_slot(), heap.top_slot()) << "step " << step;
            ASSERT_EQ(calendar.top_time(), heap.top_time());
            now = heap.top_time();
            const std::int32_t top = heap.top_slot();
            calendar.popped();
            // The top moves on; one other slot is rescheduled or removed.
            const double scale = spread * (step > 100000 ? 100.0 : 1.0);  // events slow down 100x
            const double gap = unit_uniform(random) < 0.01 ? 1e4 * scale : unit_uniform(random) * scale;
            calendar.schedule(top, now + gap);
            heap.schedule(top, now + gap);
            const auto other = static_cast<std::int32_t>(unit_uniform(random) * slots);
            if (unit_uniform(random) < 0.05) {
                calendar.remove(other);
                heap.remove(other);
            } else if (other != top) {
                const double t = now + std::floor(unit_uniform(random) * 8.0) * 0.125 * scale;
                calendar.schedule(other, t);
                heap.schedule(other, t);
            }
            ASSERT_EQ(calendar.size(), heap.size());
        }
    }
}
