#include "shockgas/passthrough_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "shockgas/collision.hpp"
#include "shockgas/engine_snapshot.hpp"

namespace shockgas {

namespace {
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
}  // namespace

std::string PassThroughEngine::unsupported_reason(const InitialCondition& initial, const CollisionModel& model,
                                                  const CollapseCriterion& collapse) {
    if (model.restitution == 0.0) return "r = 0 is the sticky gas, where every collision merges (--engine exact)";
    if (!(model.velocity_threshold > 0.0))
        return "delta = 0 has no elastic collisions to pass through (--engine event)";
    if (model.subthreshold != Subthreshold::elastic)
        return "sticky sub-threshold collisions merge particles (--engine event)";
    for (const double m : initial.mass)
        if (m != initial.mass.front())
            return "unequal masses: an elastic collision then does not exchange velocities (--engine event)";
    // The event engines declare collapse at an inelastic collision slower than
    // collapse_speed; with g >= delta >= collapse_speed that cannot happen, so
    // this engine, which reports none, gives the same answer.
    if (collapse.collapse_speed > model.velocity_threshold)
        return fmt::format("the collapse speed {} exceeds delta = {} (--engine event)", collapse.collapse_speed,
                           model.velocity_threshold);
    if (initial.size() >= std::numeric_limits<std::int32_t>::max())
        return "more than 2^31 - 1 particles";
    return "";
}

PassThroughEngine::PassThroughEngine(const InitialCondition& initial, const CollisionModel& model, LiveStatus* live)
    : model_(model), live_(live), ring_length_(initial.ring_length) {
    validate(initial);
    const auto n = static_cast<std::size_t>(initial.size());
    mass_ = initial.mass.front();
    line_.resize(n);
    where_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        line_[k] = {initial.position[k], initial.velocity[k], 0.0, static_cast<std::uint32_t>(k), 0};
        where_[k] = static_cast<std::int32_t>(k);
    }
    update_velocity_bounds();
    // First step: about the target number of crossings for a line moving at
    // the full velocity spread through the mean spacing; adapt_step then
    // follows the measured crossing rate.
    const double spread = v_max_ - v_min_;
    const double spacing = ring_length_ / static_cast<double>(n);
    step_ = spread > 0.0 ? crossings_per_step_target * spacing / spread : std::numeric_limits<double>::infinity();
    adapt_step(0.0, 0);
}

std::int64_t PassThroughEngine::wrap_index(std::int64_t i) const {
    const auto n = static_cast<std::int64_t>(line_.size());
    const std::int64_t k = i % n;
    return k < 0 ? k + n : k;
}

double PassThroughEngine::unwrapped_position(std::int64_t i, double t) const {
    const std::int64_t k = wrap_index(i);
    const auto wraps = (i - k) / static_cast<std::int64_t>(line_.size());
    return position_at(line_[static_cast<std::size_t>(k)], t) + static_cast<double>(wraps) * ring_length_;
}

void PassThroughEngine::update_velocity_bounds() {
    const auto [lo, hi] = std::minmax_element(line_.begin(), line_.end(),
                                              [](const Line& a, const Line& b) { return a.v < b.v; });
    v_min_ = lo->v;
    v_max_ = hi->v;
}

// Step length for the next step from the crossings of the last one: the
// measured rate, crossings / (N length), times the target; at most a factor
// step_change_limit from the current length, and short enough that no pair
// can meet twice in a step (ring_step_fraction).
void PassThroughEngine::adapt_step(double length, std::uint64_t crossings) {
    if (length > 0.0) {
        const double per_line = static_cast<double>(crossings) / static_cast<double>(line_.size());
        const double proposal =
            per_line > 0.0 ? length * crossings_per_step_target / per_line : step_change_limit * step_;
        step_ = std::clamp(proposal, step_ / step_change_limit, step_ * step_change_limit);
    }
    const double spread = v_max_ - v_min_;
    if (spread > 0.0) step_ = std::min(step_, ring_step_fraction * ring_length_ / spread);
}

bool PassThroughEngine::advance_to(double t) {
    while (now_ < t) {
        if (live_ != nullptr && live_->halt_requested()) return false;
        const double step_end = now_ + step_ < t ? now_ + step_ : t;
        run_step(step_end);
        if (live_ != nullptr) {
            live_->time.store(now_, std::memory_order_relaxed);
            live_->collisions.store(collisions_, std::memory_order_relaxed);
        }
    }
    return true;
}

void PassThroughEngine::run_step(double step_end) {
    const double step_start = now_;
    update_velocity_bounds();
    const std::uint64_t collisions_before = collisions_;
    step_start_ = step_start;
    step_end_ = step_end;
    scan_step_candidates(step_start, step_end);
    while (!heap_.empty()) {
        const Candidate candidate = heap_.top();
        heap_.pop();
        const Line& behind = line_[static_cast<std::size_t>(where_[candidate.behind])];
        const Line& ahead = line_[static_cast<std::size_t>(where_[candidate.ahead])];
        if (behind.version != candidate.behind_version || ahead.version != candidate.ahead_version) continue;
        bend(candidate, step_end);
    }
    // The whole ring to step_end. The stretch starts after the widest gap at
    // the step's start: if no line can cross it in the step, the sort is
    // linear; otherwise sort_stretch closes the ring itself.
    std::int64_t lo = widest_gap_end_;
    std::int64_t hi = lo + static_cast<std::int64_t>(line_.size()) - 1;
    sort_stretch(lo, hi, step_end, widest_gap_ > (v_max_ - v_min_) * (step_end - step_start) * (1.0 + reach_slack));
    write_back(buffer_, lo);
    now_ = step_end;
    ++steps_;
    adapt_step(step_end - step_start, collisions_ - collisions_before);
}

// Every pair that crosses inelastically before step_end if both lines stay
// straight: line k can catch only lines ahead of it within (v_k - v_min) h at
// the step's start, since nothing ahead moves slower than v_min.
void PassThroughEngine::scan_step_candidates(double step_start, double step_end) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const double h = step_end - step_start;
    keys_.resize(line_.size());
    for (std::size_t k = 0; k < line_.size(); ++k) keys_[k] = position_at(line_[k], step_start);
    widest_gap_ = -std::numeric_limits<double>::infinity();
    widest_gap_end_ = 0;
    for (std::int64_t k = 0; k < n; ++k) {
        const auto ks = static_cast<std::size_t>(k);
        const Line& a = line_[ks];
        const double gap = (k + 1 < n ? keys_[ks + 1] : keys_[0] + ring_length_) - keys_[ks];
        if (gap > widest_gap_) {
            widest_gap_ = gap;
            widest_gap_end_ = k + 1;
        }
        if (classify(model_, a.v - v_min_) != CollisionKind::inelastic) continue;  // can catch nobody
        const double reach = (a.v - v_min_) * h * (1.0 + reach_slack) + reach_slack * std::abs(keys_[ks]);
        for (std::int64_t j = k + 1; j < k + n; ++j) {
            const bool wrapped = j >= n;
            const auto js = static_cast<std::size_t>(wrapped ? j - n : j);
            const double distance = keys_[js] + (wrapped ? ring_length_ : 0.0) - keys_[ks];
            if (distance > reach) break;
            push_candidate(a, line_[js], distance, step_start, step_end);
        }
    }
}

// Pair (behind, ahead), `gap` apart at time t (<= 0: crossed by rounding, so
// meeting now), both straight from t on: they meet at t + gap / g if they
// close at g >= delta (Eq. (1)'s rule applies there) and that is before
// step_end.
void PassThroughEngine::push_candidate(const Line& behind, const Line& ahead, double gap, double t,
                                       double step_end) {
    const double closing_speed = behind.v - ahead.v;
    if (classify(model_, closing_speed) != CollisionKind::inelastic) return;
    const double meeting = t + std::max(gap, 0.0) / closing_speed;
    if (meeting > step_end) return;
    heap_.push({meeting, behind.id, ahead.id, behind.version, ahead.version});
}

// New candidates of the line at logical index k, just bent at t: it can meet
// lines ahead within (v - v_min)(step_end - t) and behind within
// (v_max - v)(step_end - t). Lines outside the last sorted stretch are in
// their order of some earlier time of this step, which may be off by the
// spread's travel in a step, so the scan looks that much further.
void PassThroughEngine::scan_line_candidates(std::int64_t k, double t, double step_end) {
    const auto n = static_cast<std::int64_t>(line_.size());
    const Line& line = line_[static_cast<std::size_t>(k)];
    const double here = unwrapped_position(k, t);
    const double disorder = (v_max_ - v_min_) * (step_end_ - step_start_);
    const double slack = reach_slack * (std::abs(here) + disorder);
    const double reach_ahead = (line.v - v_min_) * (step_end - t) + disorder + slack;
    for (std::int64_t j = k + 1; j < k + n; ++j) {
        const double distance = unwrapped_position(j, t) - here;
        if (distance > reach_ahead) break;
        push_candidate(line, line_[static_cast<std::size_t>(wrap_index(j))], distance, t, step_end);
    }
    const double reach_behind = (v_max_ - line.v) * (step_end - t) + disorder + slack;
    for (std::int64_t j = k - 1; j > k - n; --j) {
        const double distance = here - unwrapped_position(j, t);
        if (distance > reach_behind) break;
        push_candidate(line_[static_cast<std::size_t>(wrap_index(j))], line, distance, t, step_end);
    }
}

// The inelastic collision of a candidate, at its time t_e.
void PassThroughEngine::bend(const Candidate& candidate, double step_end) {
    const double t = candidate.time;
    const auto n = static_cast<std::int64_t>(line_.size());
    // The stretch between the two lines, the short way round the ring.
    const std::int64_t behind_index = where_[candidate.behind];
    const std::int64_t ahead_index = where_[candidate.ahead];
    const std::int64_t forward = wrap_index(ahead_index - behind_index);
    std::int64_t lo = forward <= n / 2 ? behind_index : ahead_index;
    std::int64_t hi = forward <= n / 2 ? behind_index + forward : ahead_index + (n - forward);
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
    // The one collision rule (collision.hpp, Eq. (1)). The physical left
    // particle (on the catching line) leaves with v_b + eps g, the right one
    // with v_a - eps g; the catching line keeps going right, so it carries the
    // right particle's velocity and each line bends by eps g.
    const PostCollision after = collide(mass_, catching.line.v, mass_, caught.line.v, model_.restitution);
    catching.line.v = after.right_velocity;
    caught.line.v = after.left_velocity;
    // Both leave from one point (the caught line's; one ring length apart if
    // they crossed at the seam), so their order cannot be undone by rounding.
    catching.position = caught.position - (behind_slot < ahead_slot ? ring_length_ : 0.0);
    for (Sorted* s : {&catching, &caught}) {
        s->line.x = s->position - static_cast<double>(s->frame) * ring_length_;
        s->line.clock = t;
        ++s->line.version;
    }
    ++inelastic_;
    write_back(buffer_, lo);
    scan_line_candidates(where_[candidate.behind], t, step_end);
    scan_line_candidates(where_[candidate.ahead], t, step_end);
}

PassThroughEngine::Sorted PassThroughEngine::load(std::int64_t i, double t) const {
    const std::int64_t k = wrap_index(i);
    const auto frame = (i - k) / static_cast<std::int64_t>(line_.size());
    const Line& line = line_[static_cast<std::size_t>(k)];
    return {position_at(line, t) + static_cast<double>(frame) * ring_length_, frame, line};
}

// Stable insertion sort from `begin` on; one swap per crossing. A pair found
// crossed while closing at >= delta is left as it is: its inelastic collision
// is due (see the header).
std::uint64_t PassThroughEngine::insertion_sort(std::vector<Sorted>& buffer, std::size_t begin) const {
    std::uint64_t swaps = 0;
    for (std::size_t i = std::max<std::size_t>(begin, 1); i < buffer.size(); ++i) {
        if (!(buffer[i - 1].position > buffer[i].position)) continue;
        const Sorted item = buffer[i];
        std::size_t j = i;
        while (j > 0 && buffer[j - 1].position > item.position &&
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
    collisions_ += insertion_sort(buffer_, 0);
    if (linear) return;
    const double disorder = (v_max_ - v_min_) * (step_end_ - step_start_);
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
        std::int64_t new_lo = lo;
        for (std::int64_t j = lo - 1; j > hi - n; --j) {
            const double p = unwrapped_position(j, t);
            if (p < smallest - margin) break;
            if (p > smallest) new_lo = j;
        }
        std::int64_t new_hi = hi;
        for (std::int64_t j = hi + 1; j < new_lo + n; ++j) {
            const double p = unwrapped_position(j, t);
            if (p > largest + margin) break;
            if (p < largest) new_hi = j;
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
        collisions_ += insertion_sort(buffer_, 0);
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
        if (!(last.position > first.position + ring_length_)) return;
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
        return behind.position > ahead.position &&
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
    const auto n = static_cast<std::int64_t>(line_.size());
    for (std::size_t m = 0; m < buffer.size(); ++m) {
        const std::int64_t i = lo + static_cast<std::int64_t>(m);
        const std::int64_t k = wrap_index(i);
        const std::int64_t frame = (i - k) / n;
        Line line = buffer[m].line;
        if (buffer[m].frame != frame) line.x += static_cast<double>(buffer[m].frame - frame) * ring_length_;
        line_[static_cast<std::size_t>(k)] = line;
        where_[line.id] = static_cast<std::int32_t>(k);
    }
}

void PassThroughEngine::clusters(ClusterState& out) const {
    out.clear();
    out.time = now_;
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
    out.reals["scalars"] = {now_, step_};
    out.integers["counters"] = {static_cast<std::int64_t>(collisions_), static_cast<std::int64_t>(inelastic_),
                                static_cast<std::int64_t>(steps_)};
    return out;
}

// Versions restart at 0: they only tell candidates of one step apart, and a
// snapshot is taken between steps.
void PassThroughEngine::restore(const EngineSnapshot& snapshot) {
    snapshot_io::expect_kind(snapshot, snapshot_kind, name());
    const std::size_t n = line_.size();
    const auto& x = snapshot_io::array(snapshot.reals, "x", n, snapshot);
    const auto& v = snapshot_io::array(snapshot.reals, "v", n, snapshot);
    const auto& clock = snapshot_io::array(snapshot.reals, "clock", n, snapshot);
    const auto& id = snapshot_io::array(snapshot.integers, "id", n, snapshot);
    const auto& scalars = snapshot_io::array(snapshot.reals, "scalars", 2, snapshot);
    const auto& counters = snapshot_io::array(snapshot.integers, "counters", 3, snapshot);
    std::vector<bool> seen(n, false);
    for (std::size_t k = 0; k < n; ++k) {
        if (id[k] < 0 || static_cast<std::size_t>(id[k]) >= n || seen[static_cast<std::size_t>(id[k])])
            throw InputError("checkpoint: passthrough engine state's line ids are not a permutation");
        seen[static_cast<std::size_t>(id[k])] = true;
        line_[k] = {x[k], v[k], clock[k], static_cast<std::uint32_t>(id[k]), 0};
        where_[static_cast<std::size_t>(id[k])] = static_cast<std::int32_t>(k);
    }
    now_ = scalars[0];
    step_ = scalars[1];
    collisions_ = static_cast<std::uint64_t>(counters[0]);
    inelastic_ = static_cast<std::uint64_t>(counters[1]);
    steps_ = static_cast<std::uint64_t>(counters[2]);
    update_velocity_bounds();
}

}  // namespace shockgas
