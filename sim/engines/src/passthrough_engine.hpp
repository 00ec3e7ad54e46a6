// SPDX-License-Identifier: GPL-3.0-or-later
// The pass-through engine: elastic sub-threshold collisions as world lines
// passing through each other (docs/passthrough-engine.md).
//
// With equal masses an elastic collision exchanges the two velocities. Swap the
// labels too and nothing happened: two straight world lines ("lines") crossed.
// So the engine follows lines, not particles:
//  * Every crossing of two lines is a physical collision of the two
//    neighbouring particles there. Its relative speed g = |v_a - v_b| decides
//    the rule (collision.hpp, classify): below delta the lines pass through
//    and nothing is computed; at or above it the collision is inelastic, and
//    the line that keeps going right (the catching one) takes the physical
//    right particle's new velocity v_a - eps g, the other v_b + eps g, so each
//    line bends by only eps g.
//  * The physical ring at time t is the lines sorted by position: particle k is
//    rank k. The lines are kept in an array in that order (logical index k =
//    particle k), and a crossing of particles N-1 and 0 across the seam swaps
//    the first and last entries, shifting their stored positions by -L and +L;
//    that is the winding.
//
// Time advances in windows of about `crossings_per_window_target` crossings
// per line. The ring is cut at every gap no line can cross in the window, and
// each block between cuts runs to the window's end in its own steps [s, s + h]
// of about `crossings_per_step_target` crossings per line (on a ring with no
// cut, short enough that no pair can meet twice). In a step:
//  1. From the order at s, each line's earliest inelastic crossing, if all
//     lines stayed straight, is found by scanning ahead within its reach
//     ((v - v_min) h), passing over lines that do not end the step behind it
//     and 16-line chunks whose velocity or end-position bounds rule
//     out an inelastic meeting; each line with one goes on a heap once.
//  2. The candidates run in (time, line, line) order. Before a bend at t_e, the
//     stretch of the array around the pair is re-sorted by position at t_e,
//     grown until no line outside it is out of order with it, counting one
//     collision per swap. The bent lines then look for their next crossings;
//     a candidate whose other line bent since is looked for again by its owner
//     (version counters).
//  3. At s + h the block is re-sorted by position (insertion sort: one swap
//     per crossing), counting one collision per swap.
// A block in a burst (a shock compressed nearly to a point: every line within
// reach of every other, so each bend's looks would visit the whole shock) runs
// instead as a kinetic sorted list, every crossing an event in the event
// engine's queue, elastic ones a swap (run_block_kinetic). Which way a block
// runs is chosen from counts only, so runs stay reproducible and resumable:
// a block whose lines' inelastic share last window (their heat) is at least
// kinetic_share starts as a kinetic list; a block in steps turns into one after
// a step whose scans visited more than kinetic_visits_per_crossing lines per
// crossing, or in the middle of a step whose looks exceed a budget (the step
// stops at its last crossing: burst_crossings_factor). A ring with no cut and
// hot lines gets a window short enough for its widest gap to be a cut. Cuts
// are local (find_cuts): a gap is uncrossable if the lines on its two sides,
// with their own velocity bounds, cannot close it.
//
// Because a pair's lines are straight between their last sort and the next
// one, and their relative motion in a step is below L, each swap is exactly one
// crossing: the collision count includes every elastic collision, exactly.
//
// A pair that sorting finds crossed while closing at >= delta is an inelastic
// crossing whose computed time fell, by rounding, just after the sort's time.
// It is never swapped by a sort: the next scan sees it closing with a gap of
// <= 0 and runs it at once, as the event engines run a pair whose gap rounding
// made negative (ring_kinematics.hpp, contact_time).
//
// Valid for equal masses, r in (0, 1], delta > 0 and elastic sub-threshold
// collisions (unsupported_reason()); make_engine refuses anything else with one line.
// No collapse is possible there (every inelastic collision has g >= delta), so
// collapse() is always empty.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <string>
#include <vector>

#include "shockgas/engines/engine.hpp"
#include "quaternary_heap.hpp"

namespace shockgas {

class PassThroughEngine final : public Engine {
public:
    PassThroughEngine(const InitialCondition& initial, const CollisionModel& model, LiveStatus* live = nullptr);
    // From the middle of a run (HybridEngine's hand-over): the lines start
    // straight from the given positions at state.time, line k at particle k,
    // in the state's frame, and the collision counts go on from the state's. Equal masses only (the
    // caller checked unsupported_reason); throws std::invalid_argument for a
    // state that is not one ring in order.
    PassThroughEngine(const MidRunState& state, const CollisionModel& model, LiveStatus* live = nullptr);

    // Empty when the engine is exact for a run whose particles have these
    // masses; otherwise why not, in a phrase for a one-line error.
    static std::string unsupported_reason(const std::vector<double>& mass, const CollisionModel& model,
                                          const CollapseCriterion& collapse);

    bool advance_to(double t) override;
    double time() const override { return now_; }
    void clusters(ClusterState& out) const override;
    std::uint64_t collisions() const override { return collisions_; }
    std::int64_t cluster_count() const override { return static_cast<std::int64_t>(line_.size()); }
    const std::optional<CollapseReport>& collapse() const override { return no_collapse_; }
    std::string name() const override { return "passthrough"; }
    // Taken between windows (advance_to returns only there), where the heap is
    // empty: the lines, the step length and the counters are the whole state.
    std::optional<EngineSnapshot> snapshot() const override;
    void restore(const EngineSnapshot& snapshot) override;
    static constexpr const char* snapshot_kind = "passthrough";

    // Diagnostics for tests and the benchmark.
    std::uint64_t inelastic_collisions() const { return inelastic_; }
    std::uint64_t steps() const { return steps_; }
    std::uint64_t windows() const { return windows_; }
    // Stale candidates followed by their owner's spare instead of a new look
    // (run_step).
    std::uint64_t spares_taken() const { return spares_taken_; }
    // Gaps between physical neighbours at the current time, in ring order from
    // particle 0; they sum to L up to rounding and are never negative beyond it.
    std::vector<double> gaps() const;

    // The line record, its index, its position at the step's end, its spares
    // and heat, and a kinetic block's copy of it and queue entry (a block can
    // span nearly the whole ring); the heap entries are transient (one step's
    // candidates).
    static constexpr std::size_t bytes_per_particle() {
        return sizeof(Line) + sizeof(std::int32_t) + sizeof(double) + sizeof(Spares) + sizeof(double) /* heat */ +
               sizeof(Sorted) + sizeof(QuaternaryHeap::Entry) + sizeof(std::int32_t) /* a kinetic block */;
    }

    // Crossings per line per step the step length aims at. Few enough that a
    // bend's rescans and re-sort, which grow with the step, stay short; many
    // enough that a step's O(N) sweeps are shared by several crossings
    // (docs/passthrough-engine.md, "How it finds only the inelastic
    // crossings"). Where many crossings are inelastic the first matters
    // most, so the target is crossings_per_step_target; where few are, the
    // second, so it grows as the block's last step's inelastic share falls
    // below inelastic_share_for_longer_steps, up to longest_step_target
    // (step_target()). With SHOCKGAS_BENCH_CROSSOVER=paper (r = 0.9,
    // delta = 1e-2, N = 1e5, 0.3-1.5% inelastic) this rule beat a fixed 0.5
    // by a third and a fixed 2 slightly, and the neighbouring settings (0.02
    // for 0.04, 8 for 4) were no better; in Fig. 5's setting, where nearly
    // every crossing is inelastic, a fixed 0.5 was fastest of 0.25-2. The
    // timings: docs/measurements.md, "Measurements behind constants in the
    // code".
    static constexpr double crossings_per_step_target = 0.5;
    static constexpr double longest_step_target = 4.0;
    static constexpr double inelastic_share_for_longer_steps = 0.04;
    static double step_target(std::uint64_t crossings, std::uint64_t inelastic);
    // Crossings per line per window, on average over the ring: a window costs
    // an O(N) sweep to find its cuts, shared by this many crossings.
    static constexpr double crossings_per_window_target = 8.0;
    // Crossings each look keeps beyond its earliest (Spares). More spares
    // save more looks but make each look search further.
    static constexpr std::size_t spares_per_line = 2;
    // A block whose lines' last inelastic share (heat) is at least this runs
    // as a kinetic list: every crossing an event, at about the event engine's
    // cost per crossing; below it, in steps, where an elastic crossing costs a
    // swap and an inelastic one scans and re-sorts.
    static constexpr double kinetic_share = 0.02;
    // A block running in steps turns into a kinetic list for the rest of the
    // window after a step whose scans visited more than this many lines per
    // crossing: a burst, where a bend's looks cover the whole compressed
    // shock (docs/measurements.md, "Bursts: blocks as kinetic lists").
    static constexpr double kinetic_visits_per_crossing = 8.0;
    // A burst can also begin inside a step, and then the step's looks visit
    // the compressed shock at every bend until the step ends. So a step stops
    // early, at the time of the last candidate it took off its heap, once its
    // looks (after the step's first scan) have visited more lines than
    // kinetic_visits_per_crossing times this factor times the crossings the
    // step was sized for, and the block goes on as a kinetic list (never a
    // whole ring with no cut). At r = 0.9, delta = 1e-4 such steps made 70%
    // of all visits (docs/measurements.md, "Bursts that begin inside a step").
    static constexpr double burst_crossings_factor = 4.0;
    // Which ways a block may run: both, chosen as above (the default), or one
    // only (tests, to cover each path, and the benchmark).
    enum class Paths { mixed, steps_only, kinetic_only };
    void set_paths(Paths paths) { paths_ = paths; }
    // burst_crossings_factor in place of the constant (tests: a tiny one stops
    // nearly every step at its first bend, to cover that path).
    void set_burst_crossings_factor(double factor) { burst_factor_ = factor; }
    // Blocks run as kinetic lists and in steps so far, and steps stopped early
    // at a burst (diagnostics).
    std::uint64_t kinetic_runs() const { return kinetic_runs_; }
    std::uint64_t step_runs() const { return step_runs_; }
    std::uint64_t steps_stopped_at_a_burst() const { return steps_stopped_; }

private:
    struct Line {
        double x;      // position at `clock` (unwrapped; shifted by L at seam swaps)
        double v;      // velocity
        double clock;  // time of the last bend
        std::uint32_t id;       // stable identity of the line, for the heap
        std::uint32_t version;  // bends so far, to recognize stale candidates
    };
    // A line's earliest inelastic crossing in the step, as it was when the
    // line (the owner) last looked. If the owner has bent since, a newer one
    // replaced it; if only the other line has, the owner's next spare
    // (Spares) takes its place, or with none left the owner looks again.
    struct Candidate {
        double time = std::numeric_limits<double>::infinity();  // infinity: none
        std::uint32_t behind = 0;  // the catching line
        std::uint32_t ahead = 0;
        std::uint32_t behind_version = 0;
        std::uint32_t ahead_version = 0;
        bool owner_is_behind = false;
        bool same_pair(const Candidate& o) const { return behind == o.behind && ahead == o.ahead; }
        // Earliest first; ties by line ids, so the order is a total order.
        bool operator>(const Candidate& o) const {
            if (time != o.time) return time > o.time;
            if (behind != o.behind) return behind > o.behind;
            return ahead > o.ahead;
        }
    };
    // A line's next earliest crossings (with other lines) from its last
    // scan_line_candidates, after the one on the heap, by line id: run_step
    // takes them one by one when the heap's goes stale. Valid in the step
    // they were found in (step == steps_ + 1; 0: none) while the line is at
    // owner_version; a time of infinity means no further crossing before the
    // step's end.
    struct Spares {
        std::array<Candidate, spares_per_line> candidate{};
        std::uint64_t step = 0;
        std::uint32_t owner_version = 0;
        std::uint32_t next = 0;  // the next one to take
    };
    // A line taken out of the array for sorting, with its position at the
    // sort's time on the unwrapped axis of the stretch being sorted.
    struct Sorted {
        double position;
        std::int64_t frame;  // turns of the ring added to the line's own position
        Line line;
    };

    double position_at(const Line& line, double t) const { return line.x + line.v * (t - line.clock); }
    // Position at t of a line taken out for sorting, on the sort's axis: its
    // own position shifted by `frame` turns of the ring.
    double axis_position(const Line& line, std::int64_t frame, double t) const {
        return position_at(line, t) + static_cast<double>(frame) * ring_length_;
    }
    // Position at t of logical index i (any integer): line i mod N, shifted by
    // L for each time i wraps round the ring.
    double unwrapped_position(std::int64_t i, double t) const;
    // Logical index i (any integer) as line_'s index in [0, N) and the turns
    // of the ring it lies from there (i = index + turn N): the L-shifts of
    // unwrapped_position, load and write_back. One inline helper for both,
    // since the hot scans need both for every index they pass. Indices stay
    // within one turn of [0, N) (blocks and stretches span less than two
    // turns), so a compare or two replaces the division.
    struct Wrapped {
        std::int64_t index;
        std::int64_t turn;
    };
    Wrapped wrap(std::int64_t i) const {
        const auto n = static_cast<std::int64_t>(line_.size());
        if (i >= 0 && i < n) return {i, 0};
        if (i >= n && i < 2 * n) return {i - n, 1};
        if (i < 0 && i >= -n) return {i + n, -1};
        return wrap_far(i);
    }
    Wrapped wrap_far(std::int64_t i) const;
    std::int64_t wrap_index(std::int64_t i) const { return wrap(i).index; }
    void run_window(double window_end);
    // Fills cuts_ for the window [start, end]; returns the widest gap at start.
    double find_cuts(double start, double end);
    void run_block_steps(std::int64_t lo, std::int64_t hi, bool ring, double start, double end);
    void run_block_kinetic(std::int64_t lo, std::int64_t hi, double start, double end);
    bool hot(std::int64_t lo, std::int64_t hi) const;
    QuaternaryHeap kinetic_queue_;
    // Per line id: the inelastic share of the crossings in the block it last
    // ran in (1 at the start, where every collision is inelastic).
    std::vector<double> heat_;
    void run_block(std::int64_t lo, std::int64_t hi, bool ring, double start, double end);
    double run_step(double step_start, double step_end, double visit_budget);
    void scan_step_candidates(double step_start, double step_end);
    void scan_line_candidates(std::int64_t index, double t, double step_end);
    // The meeting time of (behind, ahead), `gap` apart at t, if they cross
    // inelastically by step_end; infinity otherwise.
    double meeting_time(const Line& behind, const Line& ahead, double gap, double t, double step_end) const;
    static void keep_earliest(Candidate& best, const Candidate& found);
    void bend(const Candidate& candidate, double step_end);
    void bend_lines(Sorted& catching, Sorted& caught, double catching_position, double t) const;
    Sorted load(std::int64_t i, double t) const;
    // Re-sorts logical indices [lo, hi] by position at t into buffer_ (stable,
    // closing inelastic pairs never swapped), growing the stretch until nothing
    // outside it is out of order with it; counts the swaps as collisions and
    // returns the final stretch's bounds through lo and hi.
    void sort_stretch(std::int64_t& lo, std::int64_t& hi, double t, bool linear);
    void close_ring();
    void swap_across_seam(bool sink);
    std::uint64_t insertion_sort(std::vector<Sorted>& buffer) const;
    void sort_in_place(std::int64_t lo, std::int64_t hi);
    void place(Line line, std::int64_t from, std::int64_t to);
    std::vector<double> sorted_end_;  // sort_in_place's positions, by axis index
    void write_back(const std::vector<Sorted>& buffer, std::int64_t lo);
    void update_velocity_bounds();
    // The rest of both constructors once line_ holds the lines: identities,
    // chunk bounds and the first window.
    void start_lines();

    std::vector<Line> line_;            // logical (physical ring) order
    std::vector<std::int32_t> where_;   // line id -> logical index
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap_;
    std::vector<Sorted> buffer_;
    std::vector<double> keys_;  // positions at the step's start, on the block's axis
    std::vector<Candidate> earliest_;  // per line of the block, during the step's scan
    std::vector<Spares> spares_;       // by line id, see Spares
    std::vector<double> lowest_end_ahead_;  // per slot of the block, during the step's scan
    // Velocity bounds of the lines at logical indices [16 c, 16 c + 15]: set at
    // each step's start, widened whenever a line is written into the chunk, so
    // that a scan can pass over a chunk none of whose lines it could meet
    // inelastically (a shock's core, all within delta of the line).
    static constexpr int chunk_shift = 4;
    std::vector<double> chunk_min_;
    std::vector<double> chunk_max_;
    // The same for the lines' positions at the step's end, in the frame of
    // index 0..N-1, with end_ holding each line's: a line meets in the rest of
    // the step only lines ahead of it that end it behind it, or behind it that
    // end it ahead, so a scan passes over lines and chunks that do not.
    std::vector<double> chunk_end_min_;
    std::vector<double> chunk_end_max_;
    std::vector<double> end_;
    // end_ of logical index i (any integer), shifted by L per turn, as
    // unwrapped_position.
    double unwrapped_end(std::int64_t i) const;
    void reset_chunk_bounds(std::int64_t lo, std::int64_t hi);
    double step_start_ = 0.0;
    double step_end_ = 0.0;
    double widest_gap_ = 0.0;        // at the step's start, and the index after it
    std::int64_t widest_gap_end_ = 0;
    std::vector<std::int64_t> cuts_;  // the window's uncrossable gaps
    struct Run {
        std::int64_t lo, hi;
        double v_min, v_max;
    };
    std::vector<Run> runs_;  // find_cuts' stack
    // The block being run: logical indices [block_lo_, block_hi_] (hi may
    // exceed N - 1: the block goes round the seam), or the whole ring.
    std::int64_t block_lo_ = 0;
    std::int64_t block_hi_ = 0;
    bool ring_block_ = false;
    std::uint64_t windows_ = 0;
    CollisionModel model_;
    LiveStatus* live_;
    double ring_length_;
    double frame_velocity_ = 0.0;  // lines move relative to it (frame_velocity, state.hpp)
    double mass_;
    double now_ = 0.0;
    double step_ = 0.0;  // the next window's length (adapted)
    double v_min_ = 0.0;
    double v_max_ = 0.0;
    std::uint64_t collisions_ = 0;
    std::uint64_t inelastic_ = 0;
    std::uint64_t steps_ = 0;
    std::uint64_t spares_taken_ = 0;
    std::uint64_t visits_ = 0;  // lines visited by scans: the steps' work
    std::uint64_t kinetic_runs_ = 0;
    std::uint64_t step_runs_ = 0;
    std::uint64_t steps_stopped_ = 0;
    Paths paths_ = Paths::mixed;
    double burst_factor_ = burst_crossings_factor;
    std::optional<CollapseReport> no_collapse_;
};

}  // namespace shockgas
