// SPDX-License-Identifier: GPL-3.0-or-later
#include "passthrough_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "shockgas/model/collision.hpp"
#include "snapshot_io.hpp"

namespace shockgas {

namespace {
constexpr double never = std::numeric_limits<double>::infinity();
// A step moves any two lines apart by at most (v_max - v_min) h. Keeping that
// below half the ring means no pair can meet twice in one step, so one swap
// in a sort is exactly one crossing, on any ring (N = 2 included).
constexpr double ring_step_fraction = 0.5;
// Relative slack on scan reaches and sort margins: positions and meeting times
// carry a few ulps of rounding; a reach widened by this only costs a check of
// one more line, never a wrong candidate (the meeting time is tested anyway).
constexpr double reach_slack = 1e-9;
// The step length changes by at most this factor from one step to the next, so
// one step with an unusual crossing count cannot swing it.
constexpr double step_change_limit = 2.0;

// The next length of a step or window that lasted `length` and saw
// `crossings` among `lines` lines: the measured rate per line, aimed at
// `target` crossings per line, at most a factor step_change_limit from
// `current`, which doubles when nothing crossed.
double adapted_length(double current, double length, std::uint64_t crossings, double lines, double target) {
    const double per_line = static_cast<double>(crossings) / lines;
    const double proposal = per_line > 0.0 ? length * target / per_line : step_change_limit * current;
    return std::clamp(proposal, current / step_change_limit, current * step_change_limit);
}

// Whether a line behind another has crossed it by time t, from their positions
// at t: it is closing on the other (faster) and beyond it or level with it. A
// crossing at exactly t counts as done, since the state at a sample time
// includes every collision at that time (the event engines run every event due
// by then); a level pair left to the next sort made the collision count at such
// a sample lag by one. Every sort below orders by this, so each swap is one
// crossing. A pair beyond each other but separating (the line behind slower)
// has not crossed: straight lines cannot be in that state, only two nearly
// parallel ones whose positions are rounded apart, and there the computed
// order flips back and forth for as long as they lie within an ulp. Swapping
// it counted every flip as a collision (181 for one meeting at relative speed
// 1e-14, samples every 1e-3; test NearlyParallelLinesCrossOnce); left alone it
// straightens as they part, as in a kinetic list, which swaps closing pairs only.
bool crossed(double behind_position, double behind_velocity, double ahead_position, double ahead_velocity) {
    return behind_velocity > ahead_velocity && behind_position >= ahead_position;
}
}  // namespace

std::string PassThroughEngine::unsupported_reason(const std::vector<double>& mass, const CollisionModel& model,
                                                  const CollapseCriterion& collapse) {
    if (model.restitution == 0.0) return "r = 0 is the sticky gas, where every collision merges (--engine exact)";
    if (!(model.velocity_threshold > 0.0))
        return "delta = 0 puts no collision below the threshold, and only those are passed through (--engine event)";
    if (model.subthreshold != Subthreshold::elastic)
        return "sticky sub-threshold collisions merge particles (--engine event)";
    for (const double m : mass)
        if (m != mass.front())
            return "unequal masses: an elastic collision then does not exchange velocities (--engine event)";
    // The event engines declare collapse at an inelastic collision slower than
    // collapse_speed; with g >= delta >= collapse_speed that cannot happen, so
    // this engine, which reports none, gives the same answer. validate() refuses
    // a collapse speed above delta > 0 for every engine; this keeps the engine's
    // own precondition for callers of the library that skip it.
    if (collapse.collapse_speed > model.velocity_threshold)
        return fmt::format("the collapse speed {} exceeds delta = {}", collapse.collapse_speed,
                           model.velocity_threshold);
    if (mass.size() >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        return "more than 2^31 - 1 particles";
    return "";
}

PassThroughEngine::PassThroughEngine(const InitialCondition& initial, const CollisionModel& model, LiveStatus* live)
    : model_(model),
      live_(live),
      ring_length_(initial.ring_length),
      frame_velocity_(frame_velocity(initial.velocity, initial.mass)) {
    validate(initial);
    const auto n = static_cast<std::size_t>(initial.size());
    mass_ = initial.mass.front();
    line_.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        line_[k] = {initial.position[k], initial.velocity[k] - frame_velocity_, 0.0, 0, 0};
    start_lines();
}

PassThroughEngine::PassThroughEngine(const MidRunState& state, const CollisionModel& model, LiveStatus* live)
    : model_(model), live_(live), ring_length_(state.ring_length), frame_velocity_(state.frame_velocity) {
    const std::size_t n = state.position.size();
    if (n == 0 || state.velocity.size() != n || state.mass.size() != n || !(state.ring_length > 0.0))
        throw std::invalid_argument("PassThroughEngine: a mid-run state needs as many velocities and masses as positions");
    // Positions may be out of order by contact rounding (|gap| ~ ulp(t));
    // anything more is not a ring in order.
    const double tolerance = 1e-6 * state.ring_length / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double next = k + 1 < n ? state.position[k + 1] : state.position[0] + state.ring_length;
        if (!(next - state.position[k] >= -tolerance) || !std::isfinite(state.velocity[k]))
            throw std::invalid_argument("PassThroughEngine: the mid-run state is not one ring in order");
    }
    mass_ = state.mass.front();
    line_.resize(n);
    for (std::size_t k = 0; k < n; ++k) line_[k] = {state.position[k], state.velocity[k], state.time, 0, 0};
    now_ = state.time;
    collisions_ = state.collisions;
    inelastic_ = state.inelastic_collisions;
    start_lines();
}

void PassThroughEngine::start_lines() {
    const std::size_t n = line_.size();
    where_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        line_[k].id = static_cast<std::uint32_t>(k);
        where_[k] = static_cast<std::int32_t>(k);
    }
    const std::size_t chunks = (n >> chunk_shift) + 1;
    chunk_min_.assign(chunks, 0.0);
    chunk_max_.assign(chunks, 0.0);
    chunk_end_min_.assign(chunks, 0.0);
    chunk_end_max_.assign(chunks, 0.0);
    end_.assign(n, 0.0);
    spares_.assign(n, Spares{});
    heat_.assign(n, 1.0);
    update_velocity_bounds();
    // First window: about the target number of crossings for a line moving
    // at the full velocity spread through the mean spacing; adapted_length then
    // follows the measured crossing rate. Infinite if nothing ever crosses.
    const double spread = v_max_ - v_min_;
    const double spacing = ring_length_ / static_cast<double>(n);
    step_ = spread > 0.0 ? crossings_per_window_target * spacing / spread : std::numeric_limits<double>::infinity();
}

// wrap() beyond one turn of [0, N) (not reached by blocks and stretches).
PassThroughEngine::Wrapped PassThroughEngine::wrap_far(std::int64_t i) const {
    const auto n = static_cast<std::int64_t>(line_.size());
    const std::int64_t k = i % n;
    const std::int64_t index = k < 0 ? k + n : k;
    return {index, (i - index) / n};
}

double PassThroughEngine::unwrapped_position(std::int64_t i, double t) const {
    const auto [k, turn] = wrap(i);
    const double x = position_at(line_[static_cast<std::size_t>(k)], t);
    return turn == 0 ? x : x + static_cast<double>(turn) * ring_length_;
}

double PassThroughEngine::unwrapped_end(std::int64_t i) const {
    const auto [k, turn] = wrap(i);
    return end_[static_cast<std::size_t>(k)] + static_cast<double>(turn) * ring_length_;
}

void PassThroughEngine::update_velocity_bounds() {
    const auto [lo, hi] = std::minmax_element(line_.begin(), line_.end(),
                                              [](const Line& a, const Line& b) { return a.v < b.v; });
    v_min_ = lo->v;
    v_max_ = hi->v;
}

bool PassThroughEngine::advance_to(double t) {
    // The state at t includes every collision at time <= t, as in the event
    // engines, so lines that start at one point and close collide in the
    // sample at the starting time: a window of length zero runs them first.
    if (windows_ == 0) run_window(now_);
    while (now_ < t) {
        if (live_ != nullptr && live_->halt_requested()) return false;
        const double window_end = now_ + step_ < t ? now_ + step_ : t;
        run_window(window_end);
        if (live_ != nullptr) {
            live_->time.store(now_, std::memory_order_relaxed);
            live_->collisions.store(collisions_, std::memory_order_relaxed);
        }
    }
    return true;
}

// The window's cuts: gaps no line can cross in [start, end], so that the
// blocks between them run independently. Collisions only form convex
// combinations of velocities, so while no line has crossed a block's ends its
// velocities stay within the block's [v_min, v_max]; then no line of the left
// block gets further than the gap's left end + v_max(left) (t - start), nor
// any of the right one nearer than its right end + v_min(right) (t - start).
// A gap wider than (v_max(left) - v_min(right)) W therefore stays uncrossed,
// and by induction over the first crossing, so do all such gaps together.
// Blocks are grown from single lines: a stack of runs, the top two merged
// while the gap between them is crossable with their merged bounds (merging
// widens the bounds, so the run below is checked again), then the run round
// the seam likewise. Cuts land between clusters that cannot meet in the
// window, however fast the lines elsewhere on the ring.
double PassThroughEngine::find_cuts(double start, double end) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const double w = end - start;
    cuts_.clear();
    // Start after the widest gap, which is a cut if any gap is.
    std::int64_t first = 0;
    double widest = -never;
    double previous = unwrapped_position(0, start);
    for (std::int64_t k = 0; k < n; ++k) {
        const double next = unwrapped_position(k + 1, start);
        if (next - previous > widest) {
            widest = next - previous;
            first = k + 1;
        }
        previous = next;
    }
    const auto crossable = [&](const Run& left, const Run& right) {
        const double gap = unwrapped_position(left.hi + 1, start) - unwrapped_position(left.hi, start);
        return !(gap > (left.v_max - right.v_min) * w * (1.0 + reach_slack) + reach_slack * ring_length_);
    };
    const auto merge = [](Run& left, const Run& right) {
        left.hi = right.hi;
        left.v_min = std::min(left.v_min, right.v_min);
        left.v_max = std::max(left.v_max, right.v_max);
    };
    runs_.clear();
    for (std::int64_t i = first; i < first + n; ++i) {
        const double v = line_[static_cast<std::size_t>(wrap_index(i))].v;
        runs_.push_back({i, i, v, v});
        while (runs_.size() >= 2 && crossable(runs_[runs_.size() - 2], runs_.back())) {
            merge(runs_[runs_.size() - 2], runs_.back());
            runs_.pop_back();
        }
    }
    // Round the seam: the last run against the first (one turn on).
    std::size_t front = 0;
    for (;;) {
        if (runs_.size() - front == 1) {
            // One run round the whole ring: a block cut at its ends if the gap
            // there (the widest) cannot be crossed even by its own spread.
            Run itself = runs_.back();
            itself.lo += n;
            itself.hi += n;
            if (!crossable(runs_.back(), itself)) cuts_.push_back(wrap_index(runs_.back().hi));
            return widest;
        }
        Run wrapped = runs_[front];
        wrapped.lo += n;
        wrapped.hi += n;
        if (crossable(runs_.back(), wrapped)) {
            merge(runs_.back(), wrapped);
            ++front;
        } else if (crossable(runs_[runs_.size() - 2], runs_.back())) {
            merge(runs_[runs_.size() - 2], runs_.back());
            runs_.pop_back();
        } else {
            break;
        }
    }
    for (std::size_t r = front; r < runs_.size(); ++r) cuts_.push_back(wrap_index(runs_[r].hi));
    std::sort(cuts_.begin(), cuts_.end());
    return widest;
}

// One window [now, window_end]. A gap at the window's start wider than the
// spread's travel in the window, (v_max - v_min) W, cannot be crossed in it:
// the ring is cut at every such gap, and the blocks between cuts run to the
// window's end one after the other, each with steps fitted to its own
// crossing rate (a shock's lines cross each other far more often than lines
// in the voids between shocks). With no such gap the ring is one block.
void PassThroughEngine::run_window(double window_end) {
    const double window_start = now_;
    const auto n = static_cast<std::int64_t>(line_.size());
    update_velocity_bounds();
    const std::uint64_t collisions_before = collisions_;
    const double widest_gap = find_cuts(window_start, window_end);
    // A hot ring with no cut (the dense early gas) gets a window short enough
    // for its widest gap to be one, so that its blocks can run as kinetic
    // lists, which need two ends.
    const double spread = v_max_ - v_min_;
    if (cuts_.empty() && spread > 0.0 && paths_ != Paths::steps_only &&
        (paths_ == Paths::kinetic_only || hot(0, n - 1))) {
        window_end = std::min(window_end, window_start + 0.5 * widest_gap / spread);
        find_cuts(window_start, window_end);
    }
    if (cuts_.empty()) {
        run_block(0, n - 1, true, window_start, window_end);
    } else {
        // Blocks (cut_i, cut_{i+1}], the last one round the seam.
        for (std::size_t c = 0; c < cuts_.size(); ++c) {
            const std::int64_t lo = cuts_[c] + 1;
            const std::int64_t hi = c + 1 < cuts_.size() ? cuts_[c + 1] : cuts_[0] + n;
            run_block(lo, hi, false, window_start, window_end);
        }
    }
    now_ = window_end;
    ++windows_;
    // The next window: about crossings_per_window_target crossings per line.
    if (window_end > window_start)
        step_ = adapted_length(step_, window_end - window_start, collisions_ - collisions_before,
                               static_cast<double>(n), crossings_per_window_target);
}

// Crossings per line the next step aims at, after a step with these counts:
// crossings_per_step_target, or more in proportion as the share of inelastic
// crossings falls below inelastic_share_for_longer_steps (see the header).
double PassThroughEngine::step_target(std::uint64_t crossings, std::uint64_t inelastic) {
    if (inelastic == 0) return longest_step_target;
    const double share = static_cast<double>(inelastic) / static_cast<double>(crossings);
    return std::clamp(crossings_per_step_target * inelastic_share_for_longer_steps / share,
                      crossings_per_step_target, longest_step_target);
}

// Block [lo, hi] of logical indices from `start` to `end`: as a kinetic list
// if its lines were hot (hot()), otherwise in steps of about step_target()
// crossings per line, which turn into a kinetic list at a burst. `ring`: the
// block is the whole ring with nothing to cut it (steps only). Afterwards
// every line of the block carries the block's inelastic share as its heat.
void PassThroughEngine::run_block(std::int64_t lo, std::int64_t hi, bool ring, double start, double end) {
    if (hi == lo && !ring) return;  // a lone line crosses nobody
    const std::uint64_t crossings_before = collisions_;
    const std::uint64_t inelastic_before = inelastic_;
    if (!ring && paths_ != Paths::steps_only && (paths_ == Paths::kinetic_only || hot(lo, hi)))
        run_block_kinetic(lo, hi, start, end);
    else
        run_block_steps(lo, hi, ring, start, end);
    const std::uint64_t crossings = collisions_ - crossings_before;
    if (crossings == 0) return;
    const double share = static_cast<double>(inelastic_ - inelastic_before) / static_cast<double>(crossings);
    for (std::int64_t i = lo; i <= hi; ++i) heat_[line_[static_cast<std::size_t>(wrap_index(i))].id] = share;
}

// Whether the lines at logical indices [lo, hi] crossed inelastically often
// enough, the last time they ran, for a kinetic list to beat steps: their
// mean heat against kinetic_share (see the header).
bool PassThroughEngine::hot(std::int64_t lo, std::int64_t hi) const {
    double sum = 0.0;
    for (std::int64_t i = lo; i <= hi; ++i) sum += heat_[line_[static_cast<std::size_t>(wrap_index(i))].id];
    return sum >= kinetic_share * static_cast<double>(hi - lo + 1);
}

// Block [lo, hi] in steps (the header's steps 1-3).
void PassThroughEngine::run_block_steps(std::int64_t lo, std::int64_t hi, bool ring, double start, double end) {
    ++step_runs_;
    block_lo_ = lo;
    block_hi_ = hi;
    ring_block_ = ring;
    // Velocity bounds of the block: collisions only form convex combinations
    // of velocities, so they hold for the whole window.
    v_min_ = std::numeric_limits<double>::infinity();
    v_max_ = -std::numeric_limits<double>::infinity();
    for (std::int64_t i = lo; i <= hi; ++i) {
        const double v = line_[static_cast<std::size_t>(wrap_index(i))].v;
        v_min_ = std::min(v_min_, v);
        v_max_ = std::max(v_max_, v);
    }
    const double spread = v_max_ - v_min_;
    if (!(spread > 0.0)) return;  // equal velocities never cross
    // First step: the block's lines spread over its extent, meeting at about
    // the spread; then the measured rate.
    const double extent = std::max(unwrapped_position(hi, start) - unwrapped_position(lo, start),
                                   ring_length_ / static_cast<double>(line_.size()));
    const double lines = static_cast<double>(hi - lo + 1);
    double target = crossings_per_step_target;  // crossings per line the step is sized for
    double step = target * extent / (lines * spread);
    const double longest = ring ? ring_step_fraction * ring_length_ / spread : end - start;
    const bool may_turn_kinetic = !ring && paths_ != Paths::steps_only;
    for (double t = start; t < end;) {
        step = std::min(step, longest);
        const double step_end = t + step < end ? t + step : end;
        const std::uint64_t before = collisions_;
        const std::uint64_t inelastic_before = inelastic_;
        const std::uint64_t visits_before = visits_;
        const double visit_budget =
            may_turn_kinetic ? kinetic_visits_per_crossing * burst_factor_ * std::max(target * lines, 16.0)
                             : never;
        const double stopped = run_step(t, step_end, visit_budget);
        if (stopped < step_end) {  // a burst began inside the step: the lines are in order at `stopped`
            run_block_kinetic(lo, hi, stopped, end);
            return;
        }
        const std::uint64_t crossings = collisions_ - before;
        const std::uint64_t inelastic = inelastic_ - inelastic_before;
        target = step_target(crossings, inelastic);
        step = adapted_length(step, step_end - t, crossings, lines, target);
        t = step_end;
        // A burst: the rest of the window as a kinetic list (the lines are in
        // order at the step's end).
        if (may_turn_kinetic && t < end && crossings >= 16 &&
            static_cast<double>(visits_ - visits_before) > kinetic_visits_per_crossing * static_cast<double>(crossings)) {
            run_block_kinetic(lo, hi, t, end);
            return;
        }
    }
}

// Block [lo, hi] (not the whole ring; in order at `start`) from `start` to
// `end` as a kinetic sorted list: the lines in their exact order, each
// adjacent pair's next crossing in the event engine's queue (quaternary_heap.hpp),
// every crossing processed in time order. An elastic crossing only swaps two
// entries (the lines pass through); an inelastic one bends both lines by the
// one collision rule (Eq. (1), as bend() does) and swaps them. Either way the
// pair then diverges (an inelastic pair separates at r g), so only the two new
// neighbour pairs need new crossing times. Every crossing is counted as it
// happens. This is what a burst needs: a shock compressed to a point, where
// every line is within reach of every other and a step's scans would visit
// the whole shock at each bend.
void PassThroughEngine::run_block_kinetic(std::int64_t lo, std::int64_t hi, double start, double end) {
    const auto m = static_cast<std::size_t>(hi - lo + 1);
    ++kinetic_runs_;
    buffer_.clear();
    for (std::int64_t i = lo; i <= hi; ++i) buffer_.push_back(load(i, start));
    const auto position = [this](const Sorted& s, double t) { return axis_position(s.line, s.frame, t); };
    // Only crossings due by `end` are queued, so the heap holds only the
    // pairs that cross in this window (as the event engine's windows do).
    // Gap <= 0 (crossed by rounding): meeting now, as in meeting_time().
    const auto pair_time = [&](std::size_t k, double t) {
        const Sorted& a = buffer_[k];
        const Sorted& b = buffer_[k + 1];
        if (!(a.line.v > b.line.v)) return never;
        const double gap = position(b, t) - position(a, t);
        const double meeting = t + std::max(gap, 0.0) / (a.line.v - b.line.v);
        return meeting <= end ? meeting : never;
    };
    kinetic_queue_.reset(static_cast<std::int32_t>(m));
    for (std::size_t k = 0; k + 1 < m; ++k) {
        const double t = pair_time(k, start);
        if (t != never) kinetic_queue_.append_unordered(static_cast<std::int32_t>(k), t);
    }
    kinetic_queue_.heapify();
    std::uint64_t crossings = 0;
    std::uint64_t inelastic = 0;
    while (!kinetic_queue_.empty()) {
        const auto k = static_cast<std::size_t>(kinetic_queue_.top_slot());
        const double t = kinetic_queue_.top_time();
        Sorted& catching = buffer_[k];
        Sorted& caught = buffer_[k + 1];
        if (classify(model_, catching.line.v - caught.line.v) == CollisionKind::inelastic) {
            caught.position = position(caught, t);
            bend_lines(catching, caught, caught.position, t);  // from one point, as in bend()
            ++inelastic;
        }
        std::swap(catching, caught);
        ++crossings;
        // The crossed pair now diverges and leaves the queue; its neighbour
        // pairs get new times.
        kinetic_queue_.pop_top_and_schedule(k > 0 ? static_cast<std::int32_t>(k) - 1 : -1,
                                            k > 0 ? pair_time(k - 1, t) : never,
                                            k + 2 < m ? static_cast<std::int32_t>(k) + 1 : -1,
                                            k + 2 < m ? pair_time(k + 1, t) : never, end);
    }
    collisions_ += crossings;
    inelastic_ += inelastic;
    step_end_ = end;
    write_back(buffer_, lo);
}

// Chunk bounds from the velocities now, for every chunk that holds an index
// of [lo, hi] (lines outside the block in those chunks do not change while
// the block runs, so their velocities now are bounds too).
void PassThroughEngine::reset_chunk_bounds(std::int64_t lo, std::int64_t hi) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const std::int64_t first = lo;
    const std::int64_t last = std::min(hi, lo + n - 1);
    for (std::int64_t i = first; i <= last;) {
        const std::int64_t k = wrap_index(i);
        const std::int64_t chunk_begin = (k >> chunk_shift) << chunk_shift;
        const std::int64_t chunk_end = std::min(chunk_begin + (std::int64_t{1} << chunk_shift), n);
        double v_lo = never;
        double v_hi = -never;
        double end_lo = never;
        double end_hi = -never;
        for (std::int64_t m = chunk_begin; m < chunk_end; ++m) {
            const Line& line = line_[static_cast<std::size_t>(m)];
            const double end = position_at(line, step_end_);
            end_[static_cast<std::size_t>(m)] = end;
            v_lo = std::min(v_lo, line.v);
            v_hi = std::max(v_hi, line.v);
            end_lo = std::min(end_lo, end);
            end_hi = std::max(end_hi, end);
        }
        const auto c = static_cast<std::size_t>(k >> chunk_shift);
        chunk_min_[c] = v_lo;
        chunk_max_[c] = v_hi;
        chunk_end_min_[c] = end_lo;
        chunk_end_max_[c] = end_hi;
        i += chunk_end - k;
    }
}

// One step [step_start, step_end] of the current block. Returns the time it
// ended: step_end, or, if the looks after the step's first scan visited more
// than visit_budget lines (a burst: burst_crossings_factor in the header), the
// time of the last candidate taken off the heap (before step_end), with every
// inelastic crossing before that time run and the block sorted by position at
// that time (one swap per crossing, as at a step's end), so that a kinetic list
// can take the block from there.
double PassThroughEngine::run_step(double step_start, double step_end, double visit_budget) {
    step_start_ = step_start;
    step_end_ = step_end;
    reset_chunk_bounds(block_lo_, block_hi_);
    scan_step_candidates(step_start, step_end);
    const std::uint64_t visits_after_scan = visits_;
    double last_run = step_start;  // the time of the last candidate taken off the heap
    while (!heap_.empty()) {
        // (Not at step_end itself: there the step ends as usual, and the
        // crossings due at that time are run before it ends.)
        if (static_cast<double>(visits_ - visits_after_scan) > visit_budget && last_run < step_end) {
            // Candidates still on the heap are not before the last one taken
            // off it (they come in time order), so none is lost: the kinetic
            // list finds each again, and a pair crossed by rounding or due at
            // exactly this time meets at once.
            const double now = last_run;
            heap_ = {};
            std::int64_t lo = block_lo_;
            std::int64_t hi = block_hi_;
            sort_stretch(lo, hi, now, true);  // a block is never crossed at its ends in the window
            write_back(buffer_, lo);
            ++steps_;
            ++steps_stopped_;
            return now;
        }
        const Candidate candidate = heap_.top();
        heap_.pop();
        last_run = candidate.time;
        const Line& behind = line_[static_cast<std::size_t>(where_[candidate.behind])];
        const Line& ahead = line_[static_cast<std::size_t>(where_[candidate.ahead])];
        const bool behind_current = behind.version == candidate.behind_version;
        const bool ahead_current = ahead.version == candidate.ahead_version;
        if (behind_current && ahead_current) {
            bend(candidate, step_end);
        } else if (candidate.owner_is_behind ? behind_current : ahead_current) {
            // The other line bent since the owner looked. Its crossings with
            // lines that changed since were found by those lines when they
            // changed; with the others it meets none before its next spare,
            // the next earliest crossing of that look with another line
            // (infinity: none before step_end). So that spare goes on the
            // heap, checked like any candidate when it comes up; with none
            // left, the owner looks again from now.
            const std::uint32_t owner = candidate.owner_is_behind ? candidate.behind : candidate.ahead;
            Spares& spares = spares_[owner];
            const std::uint32_t owner_version =
                candidate.owner_is_behind ? candidate.behind_version : candidate.ahead_version;
            if (spares.step == steps_ + 1 && spares.owner_version == owner_version &&
                spares.next < spares_per_line) {
                const Candidate& spare = spares.candidate[spares.next++];
                ++spares_taken_;
                if (spare.time != never) heap_.push(spare);
            } else {
                scan_line_candidates(where_[owner], candidate.time, step_end);
            }
        }
    }
    // The block to step_end. A whole ring is cut after its widest gap at the
    // step's start: if no line can cross that in the step the sort is linear;
    // otherwise sort_stretch closes the ring itself.
    std::int64_t lo = block_lo_;
    std::int64_t hi = block_hi_;
    bool linear = true;
    if (ring_block_) {
        lo = widest_gap_end_;
        hi = lo + static_cast<std::int64_t>(line_.size()) - 1;
        linear = widest_gap_ > (v_max_ - v_min_) * (step_end - step_start) * (1.0 + reach_slack);
    }
    if (linear) {
        sort_in_place(lo, hi);
    } else {
        sort_stretch(lo, hi, step_end, false);
        write_back(buffer_, lo);
    }
    ++steps_;
    return step_end;
}

// Indices [lo, hi] (axis), which no line crosses into or out of in the step,
// re-sorted in place by position at the step's end as insertion_sort would
// sort them: one swap per crossing, counted as a collision, and a closing
// inelastic pair left as it is. Most lines are in order already, so only the
// ones out of order are moved; each moved line is shifted by L per turn of the
// ring between its old and new index, as write_back does.
void PassThroughEngine::sort_in_place(std::int64_t lo, std::int64_t hi) {
    // Positions at the step's end on the axis: end_, kept current through the
    // step's bends, holds them (the same doubles load() computes); copied,
    // since the sort moves them with their lines.
    sorted_end_.resize(static_cast<std::size_t>(hi - lo + 1));
    for (std::int64_t i = lo; i <= hi; ++i) sorted_end_[static_cast<std::size_t>(i - lo)] = unwrapped_end(i);
    std::uint64_t swaps = 0;
    for (std::int64_t i = lo + 1; i <= hi; ++i) {
        const auto m = static_cast<std::size_t>(i - lo);
        const double item_end = sorted_end_[m];
        // Most lines are ahead of the one before: one compare, no line loaded.
        if (sorted_end_[m - 1] < item_end) continue;
        const Line item = line_[static_cast<std::size_t>(wrap_index(i))];
        if (!crossed(sorted_end_[m - 1], line_[static_cast<std::size_t>(wrap_index(i - 1))].v, item_end, item.v))
            continue;
        std::int64_t j = i;
        for (; j > lo; --j) {
            const auto before = static_cast<std::size_t>(j - 1 - lo);
            const Line& previous = line_[static_cast<std::size_t>(wrap_index(j - 1))];
            if (!crossed(sorted_end_[before], previous.v, item_end, item.v) ||
                classify(model_, previous.v - item.v) == CollisionKind::inelastic)
                break;
            place(previous, j - 1, j);
            sorted_end_[before + 1] = sorted_end_[before];
            ++swaps;
        }
        if (j != i) {
            place(item, i, j);
            sorted_end_[static_cast<std::size_t>(j - lo)] = item_end;
        }
    }
    collisions_ += swaps;
}

// A copy of `line`, taken from axis index `from`, written to axis index `to`.
void PassThroughEngine::place(Line line, std::int64_t from, std::int64_t to) {
    const auto [k, to_turn] = wrap(to);
    const std::int64_t turns = wrap(from).turn - to_turn;
    if (turns != 0) line.x += static_cast<double>(turns) * ring_length_;
    line_[static_cast<std::size_t>(k)] = line;
    where_[line.id] = static_cast<std::int32_t>(k);
}

// Every line's earliest inelastic crossing in the step, if all lines stayed
// straight: line k can catch only lines ahead of it within (v_k - v_min) h at
// the step's start, since nothing ahead moves slower than v_min. Each pair
// found is offered to both its lines; each line with a crossing goes on the
// heap once.
void PassThroughEngine::scan_step_candidates(double step_start, double step_end) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const std::int64_t lo = block_lo_;
    const std::int64_t size = block_hi_ - block_lo_ + 1;
    const double h = step_end - step_start;
    const auto block_slot = [size](std::int64_t j) { return static_cast<std::size_t>(j < size ? j : j - size); };
    keys_.resize(static_cast<std::size_t>(size));
    for (std::int64_t m = 0; m < size; ++m) keys_[static_cast<std::size_t>(m)] = unwrapped_position(lo + m, step_start);
    earliest_.assign(static_cast<std::size_t>(size), Candidate{never, 0, 0, 0, 0, false});
    widest_gap_ = -std::numeric_limits<double>::infinity();
    widest_gap_end_ = lo;
    // lowest_end_ahead_[m]: the lowest end position of the block's lines from
    // slot m on, so that a line overtaking none of them costs one compare (not
    // kept on a ring block, where lines past the seam are ahead too).
    if (!ring_block_) {
        lowest_end_ahead_.resize(static_cast<std::size_t>(size) + 1);
        lowest_end_ahead_[static_cast<std::size_t>(size)] = never;
        for (std::int64_t m = size - 1; m >= 0; --m)
            lowest_end_ahead_[static_cast<std::size_t>(m)] =
                std::min(lowest_end_ahead_[static_cast<std::size_t>(m) + 1], unwrapped_end(lo + m));
    }
    for (std::int64_t m = 0; m < size; ++m) {
        const auto ms = static_cast<std::size_t>(m);
        const Line& a = line_[static_cast<std::size_t>(wrap_index(lo + m))];
        if (ring_block_) {
            const double gap = (m + 1 < size ? keys_[ms + 1] : keys_[0] + ring_length_) - keys_[ms];
            if (gap > widest_gap_) {
                widest_gap_ = gap;
                widest_gap_end_ = lo + m + 1;
            }
        }
        if (classify(model_, a.v - v_min_) != CollisionKind::inelastic) continue;  // can catch nobody
        const double slack = reach_slack * (std::abs(keys_[ms]) + (a.v - v_min_) * h);
        // a meets only lines that end the step at or behind it.
        const double end_bound = unwrapped_end(lo + m) + slack;
        if (!ring_block_ && lowest_end_ahead_[ms + 1] > end_bound) continue;  // overtakes nobody
        const std::int64_t last = ring_block_ ? m + n - 1 : size - 1;
        for (std::int64_t j = m + 1; j <= last;) {
            ++visits_;
            const std::size_t js = block_slot(j);
            const double distance = keys_[js] + (j >= size ? ring_length_ : 0.0) - keys_[ms];
            // Beyond what a can reach before its earliest crossing so far.
            const double horizon = std::min(earliest_[ms].time, step_end) - step_start;
            if (distance > (a.v - v_min_) * horizon + slack) break;
            const auto [index, turns] = wrap(lo + j);
            const auto chunk = static_cast<std::size_t>(index >> chunk_shift);
            const double turn = static_cast<double>(turns) * ring_length_;
            const double chunk_min = chunk_min_[chunk];
            if (classify(model_, a.v - chunk_min) != CollisionKind::inelastic ||
                distance > (a.v - chunk_min) * horizon + slack || chunk_end_min_[chunk] + turn > end_bound) {
                j += std::min<std::int64_t>(((index >> chunk_shift) + 1) << chunk_shift, n) - index;
                continue;
            }
            if (end_[static_cast<std::size_t>(index)] + turn > end_bound) {
                ++j;
                continue;
            }
            const Line& b = line_[static_cast<std::size_t>(index)];
            const double meeting = meeting_time(a, b, distance, step_start, step_end);
            ++j;
            if (meeting == never) continue;
            keep_earliest(earliest_[ms], Candidate{meeting, a.id, b.id, a.version, b.version, true});
            keep_earliest(earliest_[js], Candidate{meeting, a.id, b.id, a.version, b.version, false});
        }
    }
    for (const Candidate& c : earliest_)
        if (c.time != never) heap_.push(c);
}

void PassThroughEngine::keep_earliest(Candidate& best, const Candidate& found) {
    if (best.time == never || best > found) best = found;
}

// Pair (behind, ahead), `gap` apart at time t (<= 0: crossed by rounding, so
// meeting now), both straight from t on: they meet at t + gap / g if they
// close at g >= delta (Eq. (1)'s rule applies there) and that is before
// step_end.
double PassThroughEngine::meeting_time(const Line& behind, const Line& ahead, double gap, double t,
                                       double step_end) const {
    const double closing_speed = behind.v - ahead.v;
    if (classify(model_, closing_speed) != CollisionKind::inelastic) return never;
    const double meeting = t + std::max(gap, 0.0) / closing_speed;
    return meeting > step_end ? never : meeting;
}

// The earliest inelastic crossing of the line at logical index k, looking
// from time t to step_end: it can meet lines ahead within
// (v - v_min)(step_end - t) and behind within (v_max - v)(step_end - t).
// Lines outside the last sorted stretch are in their order of some earlier
// time of this step, which may be off by the spread's travel in a step, so the
// scan looks that much further. Pushed on the heap, owned by this line.
void PassThroughEngine::scan_line_candidates(std::int64_t k, double t, double step_end) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const Line& line = line_[static_cast<std::size_t>(k)];
    // Only lines of the block (no other can be met in the window); a ring
    // block is the whole ring, once round.
    const std::int64_t at = ring_block_ ? k : block_lo_ + wrap_index(k - block_lo_);  // on the block's axis
    const std::int64_t last_ahead = ring_block_ ? at + n - 1 : block_hi_;
    const std::int64_t last_behind = ring_block_ ? at - n + 1 : block_lo_;
    const double here = unwrapped_position(at, t);
    const double disorder = (v_max_ - v_min_) * (t - step_start_);  // drift since the lines were last sorted
    const double slack = reach_slack * (std::abs(here) + disorder);
    // It meets only lines ahead that end the step at or behind it, and lines
    // behind that end at or ahead of it.
    const double end_here = unwrapped_end(at);
    const double end_slack = reach_slack * (std::abs(end_here) + (v_max_ - v_min_) * (step_end - t));
    // The earliest crossing goes on the heap; the next spares_per_line (with
    // other lines) are kept as the line's spares, so that if the first one's
    // other line bends before it, run_step can go on to the next without
    // scanning again. The search ends sooner once all are found: nothing
    // beyond (speed) (last kept - t) can be met before the last kept.
    std::array<Candidate, spares_per_line + 1> kept{};  // earliest first
    const auto offer = [&](const Candidate& found) {
        std::size_t slot = 0;
        for (; slot < kept.size() && kept[slot].time != never && !(kept[slot] > found); ++slot)
            if (kept[slot].same_pair(found)) return;  // an earlier crossing of this pair is kept
        if (slot == kept.size()) return;
        std::size_t drop = kept.size() - 1;  // a later crossing of the same pair, or the last
        for (std::size_t i = slot; i < kept.size(); ++i)
            if (kept[i].time != never && kept[i].same_pair(found)) {
                drop = i;
                break;
            }
        for (std::size_t i = drop; i > slot; --i) kept[i] = kept[i - 1];
        kept[slot] = found;
    };
    const auto horizon = [&] { return std::min(kept.back().time, step_end) - t; };
    for (std::int64_t j = at + 1; j <= last_ahead;) {
        ++visits_;
        const auto [index, turns] = wrap(j);
        const auto chunk = static_cast<std::size_t>(index >> chunk_shift);
        const std::int64_t chunk_rest =
            std::min<std::int64_t>(((index >> chunk_shift) + 1) << chunk_shift, n) - index;  // indices left in it
        const double turn = static_cast<double>(turns) * ring_length_;
        const Line& other = line_[static_cast<std::size_t>(index)];
        const double distance = position_at(other, t) + turn - here;
        if (distance > (line.v - v_min_) * horizon() + disorder + slack) break;
        // Pass over the rest of the chunk if none of it is slow enough to be
        // caught inelastically, or near enough to be caught at all.
        if (classify(model_, line.v - chunk_min_[chunk]) != CollisionKind::inelastic ||
            distance > (line.v - chunk_min_[chunk]) * horizon() + 2.0 * disorder + slack ||
            chunk_end_min_[chunk] + turn > end_here + end_slack) {
            j += chunk_rest;
            continue;
        }
        if (end_[static_cast<std::size_t>(index)] + turn > end_here + end_slack) {
            ++j;
            continue;
        }
        const double meeting = meeting_time(line, other, distance, t, step_end);
        if (meeting != never) offer({meeting, line.id, other.id, line.version, other.version, true});
        ++j;
    }
    for (std::int64_t j = at - 1; j >= last_behind;) {
        ++visits_;
        const auto [index, turns] = wrap(j);
        const auto chunk = static_cast<std::size_t>(index >> chunk_shift);
        const std::int64_t chunk_rest = index - ((index >> chunk_shift) << chunk_shift) + 1;
        const double turn = static_cast<double>(turns) * ring_length_;
        const Line& other = line_[static_cast<std::size_t>(index)];
        const double distance = here - (position_at(other, t) + turn);
        if (distance > (v_max_ - line.v) * horizon() + disorder + slack) break;
        if (classify(model_, chunk_max_[chunk] - line.v) != CollisionKind::inelastic ||
            distance > (chunk_max_[chunk] - line.v) * horizon() + 2.0 * disorder + slack ||
            chunk_end_max_[chunk] + turn < end_here - end_slack) {
            j -= chunk_rest;
            continue;
        }
        if (end_[static_cast<std::size_t>(index)] + turn < end_here - end_slack) {
            --j;
            continue;
        }
        const double meeting = meeting_time(other, line, distance, t, step_end);
        if (meeting != never) offer({meeting, other.id, line.id, other.version, line.version, false});
        --j;
    }
    if (kept.front().time == never) return;
    heap_.push(kept.front());
    Spares& spares = spares_[line.id];
    std::copy(kept.begin() + 1, kept.end(), spares.candidate.begin());
    spares.step = steps_ + 1;
    spares.owner_version = line.version;
    spares.next = 0;
}

// The inelastic collision of a candidate, at its time t_e.
void PassThroughEngine::bend(const Candidate& candidate, double step_end) {
    const double t = candidate.time;
    const auto n = static_cast<std::int64_t>(line_.size());
    // The stretch between the two lines: on the block's axis, or the short
    // way round a ring block.
    std::int64_t lo = 0;
    std::int64_t hi = 0;
    if (ring_block_) {
        const std::int64_t behind_index = where_[candidate.behind];
        const std::int64_t ahead_index = where_[candidate.ahead];
        const std::int64_t forward = wrap_index(ahead_index - behind_index);
        lo = forward <= n / 2 ? behind_index : ahead_index;
        hi = forward <= n / 2 ? behind_index + forward : ahead_index + (n - forward);
    } else {
        const std::int64_t behind_at = block_lo_ + wrap_index(where_[candidate.behind] - block_lo_);
        const std::int64_t ahead_at = block_lo_ + wrap_index(where_[candidate.ahead] - block_lo_);
        lo = std::min(behind_at, ahead_at);
        hi = std::max(behind_at, ahead_at);
    }
    sort_stretch(lo, hi, t, false);

    // Sorting never swaps the closing pair, so the catching line is still
    // behind: it crosses the other now. Normally they are neighbours; a line
    // between them sits at the same place up to rounding, and is crossed too.
    // On a whole ring the other may be ahead across the seam (as on a ring of
    // two): the catching line moves to the end, the other to the front, and
    // they cross there.
    const auto slot_of = [this](std::uint32_t id) {
        return static_cast<std::size_t>(
            std::find_if(buffer_.begin(), buffer_.end(), [id](const Sorted& s) { return s.line.id == id; }) -
            buffer_.begin());
    };
    std::size_t behind_slot = slot_of(candidate.behind);
    std::size_t ahead_slot = slot_of(candidate.ahead);
    const auto begin = buffer_.begin();
    if (behind_slot < ahead_slot) {
        std::rotate(begin + static_cast<std::ptrdiff_t>(behind_slot), begin + static_cast<std::ptrdiff_t>(behind_slot) + 1,
                    begin + static_cast<std::ptrdiff_t>(ahead_slot) + 1);
        collisions_ += ahead_slot - behind_slot;
        behind_slot = ahead_slot;
        ahead_slot = behind_slot - 1;
    } else {
        const std::size_t end = buffer_.size() - 1;
        std::rotate(begin + static_cast<std::ptrdiff_t>(behind_slot), begin + static_cast<std::ptrdiff_t>(behind_slot) + 1,
                    buffer_.end());
        std::rotate(begin, begin + static_cast<std::ptrdiff_t>(ahead_slot), begin + static_cast<std::ptrdiff_t>(ahead_slot) + 1);
        collisions_ += (end - behind_slot) + ahead_slot;
        swap_across_seam(false);  // catching last, caught first: they cross at the seam
        behind_slot = 0;
        ahead_slot = end;
    }
    Sorted& catching = buffer_[behind_slot];  // now the physical right particle
    Sorted& caught = buffer_[ahead_slot];     // now the physical left particle
    // Both leave from one point (the caught line's; one ring length apart if
    // they crossed at the seam), so their order cannot be undone by rounding.
    bend_lines(catching, caught, caught.position - (behind_slot < ahead_slot ? ring_length_ : 0.0), t);
    ++inelastic_;
    write_back(buffer_, lo);
    scan_line_candidates(where_[candidate.behind], t, step_end);
    scan_line_candidates(where_[candidate.ahead], t, step_end);
}

// The inelastic collision of two lines at time t, the catching line leaving
// from catching_position and the caught one from its own position (both on
// the sort's axis). The one collision rule (collision.hpp, Eq. (1)): the
// physical left particle (on the catching line) leaves with v_b + eps g, the
// right one with v_a - eps g; the catching line keeps going right, so it
// carries the right particle's velocity and each line bends by eps g.
void PassThroughEngine::bend_lines(Sorted& catching, Sorted& caught, double catching_position, double t) const {
    const PostCollision after = collide(mass_, catching.line.v, mass_, caught.line.v, model_.restitution);
    catching.line.v = after.right_velocity;
    caught.line.v = after.left_velocity;
    catching.position = catching_position;
    for (Sorted* s : {&catching, &caught}) {
        s->line.x = s->position - static_cast<double>(s->frame) * ring_length_;
        s->line.clock = t;
        ++s->line.version;
    }
}

PassThroughEngine::Sorted PassThroughEngine::load(std::int64_t i, double t) const {
    const auto [k, frame] = wrap(i);
    const Line& line = line_[static_cast<std::size_t>(k)];
    return {axis_position(line, frame, t), frame, line};
}

// Insertion sort by crossed() (stable for level lines that do not close); one
// swap per crossing. A pair found crossed while closing at >= delta is left
// as it is: its inelastic collision is due (see the header).
std::uint64_t PassThroughEngine::insertion_sort(std::vector<Sorted>& buffer) const {
    std::uint64_t swaps = 0;
    for (std::size_t i = 1; i < buffer.size(); ++i) {
        if (!crossed(buffer[i - 1].position, buffer[i - 1].line.v, buffer[i].position, buffer[i].line.v)) continue;
        const Sorted item = buffer[i];
        std::size_t j = i;
        while (j > 0 && crossed(buffer[j - 1].position, buffer[j - 1].line.v, item.position, item.line.v) &&
               classify(model_, buffer[j - 1].line.v - item.line.v) != CollisionKind::inelastic) {
            buffer[j] = buffer[j - 1];
            --j;
            ++swaps;
        }
        buffer[j] = item;
    }
    return swaps;
}

// Indices [lo, hi] sorted by position at t into buffer_ (not yet written
// back). A line outside the stretch whose position at t is beyond the
// stretch's smallest (left side) or largest (right side) is out of order with
// it, and joins it; lines further than the spread's travel in a step cannot
// be, so the search stops there. `linear`: the caller knows nothing crosses
// the stretch's ends (a whole ring cut at a gap no line can cross).
void PassThroughEngine::sort_stretch(std::int64_t& lo, std::int64_t& hi, double t, bool linear) {
    const auto n = static_cast<std::int64_t>(line_.size());
    buffer_.clear();
    for (std::int64_t i = lo; i <= hi; ++i) buffer_.push_back(load(i, t));
    collisions_ += insertion_sort(buffer_);
    if (linear) return;
    const double disorder = (v_max_ - v_min_) * (t - step_start_);  // drift since the lines were last sorted
    for (;;) {
        if (static_cast<std::int64_t>(buffer_.size()) >= n) {
            close_ring();
            return;
        }
        double smallest = buffer_.front().position;
        double largest = buffer_.front().position;
        for (const Sorted& s : buffer_) {
            smallest = std::min(smallest, s.position);
            largest = std::max(largest, s.position);
        }
        const double margin = disorder + reach_slack * (std::abs(smallest) + std::abs(largest) + disorder);
        // A block's stretch stays in the block; a ring block's may go round.
        const std::int64_t left_end = ring_block_ ? hi - n + 1 : block_lo_;
        std::int64_t new_lo = lo;
        for (std::int64_t j = lo - 1; j >= left_end; --j) {
            const double p = unwrapped_position(j, t);
            if (p < smallest - margin) break;
            if (p >= smallest) new_lo = j;  // level: possibly crossed (crossed()); the sort decides
        }
        const std::int64_t right_end = ring_block_ ? new_lo + n - 1 : block_hi_;
        std::int64_t new_hi = hi;
        for (std::int64_t j = hi + 1; j <= right_end; ++j) {
            const double p = unwrapped_position(j, t);
            if (p > largest + margin) break;
            if (p <= largest) new_hi = j;
        }
        if (new_lo == lo && new_hi == hi) return;
        if (new_hi - new_lo + 1 > n) new_hi = new_lo + n - 1;
        std::vector<Sorted> grown;
        grown.reserve(static_cast<std::size_t>(new_hi - new_lo + 1));
        for (std::int64_t i = new_lo; i < lo; ++i) grown.push_back(load(i, t));
        grown.insert(grown.end(), buffer_.begin(), buffer_.end());
        for (std::int64_t i = hi + 1; i <= new_hi; ++i) grown.push_back(load(i, t));
        buffer_.swap(grown);
        lo = new_lo;
        hi = new_hi;
        collisions_ += insertion_sort(buffer_);
    }
}

// buffer_ holds the whole ring, sorted on the axis of its first line. The
// ring is closed if the last line is not beyond the first one's image one
// ring length on; if it is, it crossed that image (particles N-1 and 0
// collided across the seam): the two swap places, one ring length moved each
// way, and sink to their places. Rare: only when no gap is wide enough to cut
// the ring (small rings, the dense early gas).
void PassThroughEngine::close_ring() {
    for (;;) {
        const Sorted& last = buffer_.back();
        const Sorted& first = buffer_.front();
        if (!crossed(last.position, last.line.v, first.position + ring_length_, first.line.v)) return;
        if (classify(model_, last.line.v - first.line.v) == CollisionKind::inelastic) return;  // due now
        swap_across_seam(true);
    }
}

// The last line of a whole-ring buffer and the first one's image cross: the
// first takes the last place one ring length on, the last the first place one
// ring length back; with `sink`, each then sinks to its place (one crossing
// per swap).
void PassThroughEngine::swap_across_seam(bool sink) {
    Sorted& first = buffer_.front();
    Sorted& last = buffer_.back();
    std::swap(first, last);
    first.position -= ring_length_;
    first.frame -= 1;
    last.position += ring_length_;
    last.frame += 1;
    ++collisions_;
    if (!sink) return;
    const auto closing = [this](const Sorted& behind, const Sorted& ahead) {
        return crossed(behind.position, behind.line.v, ahead.position, ahead.line.v) &&
               classify(model_, behind.line.v - ahead.line.v) != CollisionKind::inelastic;
    };
    for (std::size_t j = 0; j + 1 < buffer_.size() && closing(buffer_[j], buffer_[j + 1]); ++j) {
        std::swap(buffer_[j], buffer_[j + 1]);
        ++collisions_;
    }
    for (std::size_t j = buffer_.size() - 1; j > 0 && closing(buffer_[j - 1], buffer_[j]); --j) {
        std::swap(buffer_[j - 1], buffer_[j]);
        ++collisions_;
    }
}

// The sorted stretch back into the array from logical index lo on. A line's
// stored position is relative to its index's turn of the ring, so a line that
// moved across the seam is shifted by the ring length.
void PassThroughEngine::write_back(const std::vector<Sorted>& buffer, std::int64_t lo) {
    for (std::size_t m = 0; m < buffer.size(); ++m) {
        const std::int64_t i = lo + static_cast<std::int64_t>(m);
        const auto [k, frame] = wrap(i);
        Line line = buffer[m].line;
        if (buffer[m].frame != frame) line.x += static_cast<double>(buffer[m].frame - frame) * ring_length_;
        line_[static_cast<std::size_t>(k)] = line;
        where_[line.id] = static_cast<std::int32_t>(k);
        const auto c = static_cast<std::size_t>(k >> chunk_shift);
        const double end = position_at(line, step_end_);
        end_[static_cast<std::size_t>(k)] = end;
        chunk_min_[c] = std::min(chunk_min_[c], line.v);
        chunk_max_[c] = std::max(chunk_max_[c], line.v);
        chunk_end_min_[c] = std::min(chunk_end_min_[c], end);
        chunk_end_max_[c] = std::max(chunk_end_max_[c], end);
    }
}

void PassThroughEngine::clusters(ClusterState& out) const {
    out.clear();
    out.time = now_;
    out.frame_velocity = frame_velocity_;
    const std::size_t n = line_.size();
    out.position.reserve(n);
    out.velocity.reserve(n);
    out.mass.reserve(n);
    out.first_particle.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
        out.position.push_back(wrap_position(position_at(line_[k], now_), ring_length_));
        out.velocity.push_back(line_[k].v);
        out.mass.push_back(mass_);
        out.first_particle.push_back(static_cast<std::int64_t>(k));
    }
    frame_to_lab_positions(out, ring_length_);
}

std::vector<double> PassThroughEngine::gaps() const {
    const auto n = static_cast<std::int64_t>(line_.size());
    std::vector<double> out;
    out.reserve(line_.size());
    for (std::int64_t k = 0; k < n; ++k) out.push_back(unwrapped_position(k + 1, now_) - unwrapped_position(k, now_));
    return out;
}

std::optional<EngineSnapshot> PassThroughEngine::snapshot() const {
    EngineSnapshot out;
    out.kind = snapshot_kind;
    auto& x = out.reals["x"];
    auto& v = out.reals["v"];
    auto& clock = out.reals["clock"];
    auto& id = out.integers["id"];
    for (const Line& line : line_) {
        x.push_back(line.x);
        v.push_back(line.v);
        clock.push_back(line.clock);
        id.push_back(line.id);
    }
    out.reals["heat"] = heat_;  // by line id
    out.reals["scalars"] = {now_, step_};
    out.integers["counters"] = {static_cast<std::int64_t>(collisions_), static_cast<std::int64_t>(inelastic_),
                                static_cast<std::int64_t>(steps_), static_cast<std::int64_t>(windows_)};
    return out;
}

// Versions restart at 0: they only tell candidates of one step apart, and a
// snapshot is taken between windows.
void PassThroughEngine::restore(const EngineSnapshot& snapshot) {
    snapshot_io::expect_kind(snapshot, snapshot_kind, name());
    const std::size_t n = line_.size();
    const auto& x = snapshot_io::array(snapshot.reals, "x", n, snapshot);
    const auto& v = snapshot_io::array(snapshot.reals, "v", n, snapshot);
    const auto& clock = snapshot_io::array(snapshot.reals, "clock", n, snapshot);
    const auto& id = snapshot_io::array(snapshot.integers, "id", n, snapshot);
    const auto& heat = snapshot_io::array(snapshot.reals, "heat", n, snapshot);
    const auto& scalars = snapshot_io::array(snapshot.reals, "scalars", 2, snapshot);
    const auto& counters = snapshot_io::array(snapshot.integers, "counters", 4, snapshot);
    std::vector<bool> seen(n, false);
    for (std::size_t k = 0; k < n; ++k) {
        if (id[k] < 0 || static_cast<std::size_t>(id[k]) >= n || seen[static_cast<std::size_t>(id[k])])
            throw InputError("checkpoint: passthrough engine state's line ids are not a permutation");
        seen[static_cast<std::size_t>(id[k])] = true;
        line_[k] = {x[k], v[k], clock[k], static_cast<std::uint32_t>(id[k]), 0};
        where_[static_cast<std::size_t>(id[k])] = static_cast<std::int32_t>(k);
    }
    heat_ = heat;
    // Spares belong to the step they were found in, and versions restart.
    spares_.assign(n, Spares{});
    now_ = scalars[0];
    step_ = scalars[1];
    collisions_ = static_cast<std::uint64_t>(counters[0]);
    inelastic_ = static_cast<std::uint64_t>(counters[1]);
    steps_ = static_cast<std::uint64_t>(counters[2]);
    windows_ = static_cast<std::uint64_t>(counters[3]);
}

}  // namespace shockgas
