// SPDX-License-Identifier: GPL-3.0-or-later
// Shocks in a velocity snapshot (Eq. 7, Fig. 5): the late profile is a
// sawtooth v = (x - q)/t, linear segments of slope 1/t between velocity
// drops (shocks, i.e. clusters); the number of shocks is about N t^(-2/3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/model/records.hpp"

namespace shockgas::analysis {

// One /snapshots/<i>: clusters (or particles) in ring order.
struct Snapshot {
    double time = 0.0;
    std::int64_t realization = 0;
    double ring_length = 0.0;
    std::vector<double> position;
    std::vector<double> velocity;
    std::vector<double> mass;
    double total_mass() const;
};
std::vector<Snapshot> snapshots_from(const EnsembleResult& result, double ring_length);
std::vector<Snapshot> read_snapshots(const std::string& path);

// Detection (see analysis/README.md, "Shocks"): walking around the ring, a
// pair of neighbours is compressive if its velocity difference v_{i+1} - v_i
// is negative or the two are closer than cluster_gap (the members of one
// cluster); a maximal run of compressive pairs is counted as a shock when
// its total velocity drop exceeds jump_fraction * v_rms (v_rms = sqrt(T) of
// the snapshot). An ideal sawtooth of slope 1/t and segment length l has
// v_rms = l / (t sqrt 12) and jumps l / t = sqrt(12) v_rms ~ 3.5 v_rms; the
// threshold v_rms keeps shocks with jumps down to a third of that while two
// free particles about to collide differ by much less. Segments are cut at
// every run whose drop exceeds segment_break_fraction * v_rms, so that the
// small shocks inside a segment do not bias its slope.
// One shock is one velocity drop of the profile, however its mass is held: merged into one cluster
// (the sticky gas), or a bunch of particles that have not merged (elastic or r > 0 collisions below
// the threshold keep them about 1e-4 spacings apart, bouncing, moving together between the streams
// that feed it). Inside such a bunch half the pairs are expanding; with a cluster_gap of 1e-6 the
// bunch split the drop into two compressive runs, one at each edge, and a strong shock counted
// twice (the quick Fig. 5 snapshot: 15 counted, or 12 in cells of 20 particles, at 7 bunches).
struct ShockRule {
    double jump_fraction = 1.0;          // counted shocks drop v by at least v_rms
    double segment_break_fraction = 0.1; // segments end at drops above 0.1 v_rms
    // Neighbours this close (in initial spacings) belong to one cluster: far below a rarefaction
    // segment's spacings (density < 1/2: 2 and more), far above a bunch's (~1e-4).
    double cluster_gap = 1e-2;
    std::size_t min_segment_points = 5;  // a straight line fitted to fewer says little
    // When > 0: the segments are fitted to cells of at least this mass
    // (consecutive clusters merged, mass-weighted position and velocity), so
    // that the velocity jitter inside a bunch does not bend them. A cell much
    // smaller than a sawtooth tooth (N t^(-2/3) teeth of mass ~t^(2/3))
    // leaves the slopes intact. Shocks are counted on the clusters themselves,
    // so that the count does not depend on the cell.
    double coarse_grain_mass = 0.0;
    // Compressive runs separated by at most this many expanding pairs are one
    // shock (0: every run stands alone): a stream's last particles on their
    // way into a bunch can still separate.
    std::size_t merge_gap_points = 2;
};

// Consecutive clusters merged into cells of mass >= cell_mass (the last cell
// takes the remainder): mass summed, position and velocity mass-weighted,
// positions unwrapped across the seam inside a cell.
Snapshot coarse_grained(const Snapshot& snapshot, double cell_mass);

struct SegmentFit {
    double x_lo = 0.0, x_hi = 0.0;  // unwrapped positions of the first and last point
    std::size_t points = 0;
    double slope = 0.0;             // dv/dx, weighted by nothing: sigma from residuals
    double slope_sigma = 0.0;
    double density = 0.0;           // segment mass / (x_hi - x_lo), initial density 1
};

struct ShockProfile {
    double time = 0.0;
    std::vector<double> shock_position;  // mass-weighted centre of each shock run
    std::vector<double> shock_drop;      // velocity drop across it (positive)
    std::vector<SegmentFit> segments;
};
ShockProfile find_shocks(const Snapshot& snapshot, const ShockRule& rule = {});

// Over every snapshot at one time: mean shock count (SE over snapshots)
// against N t^(-2/3), and the segment slope times t (Eq. 7 predicts 1 for a
// sparse segment; (1 - rho)/t with rho the segment's number density, since
// x - q = v t for particles that have not collided). slope_times_t: mean
// over the sparse segments (rho < 1/2; denser runs are clusters, counted in
// dense_segments and left out), SE from their scatter.
struct ShockSummary {
    double time = 0.0;
    std::size_t snapshots = 0;
    Estimate shocks;
    double expected_shocks = 0.0;  // N t^(-2/3)
    Estimate slope_times_t;
    // Eq. (7) for particles: x - q = v t along a segment, so dv/dx = (1 - dq/dx)/t
    // = (1 - rho)/t; slope t / (1 - rho) should be 1 (segments with rho < 1/2).
    Estimate density_corrected_slope_times_t;
    std::size_t segments = 0;        // sparse segments, behind both slope estimates
    std::size_t dense_segments = 0;  // runs with rho >= 1/2 (clusters), left out
};
ShockSummary summarize_shocks(const std::vector<Snapshot>& snapshots, const ShockRule& rule = {});

}  // namespace shockgas::analysis
