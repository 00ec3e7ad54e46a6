// SPDX-License-Identifier: GPL-3.0-or-later
// The event-driven hard-sphere engine (engine.hpp; docs/spheres.md, "The engine").
#include "shockgas/spheres/engine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "calendar_queue.hpp"
#include "shockgas/model/collision.hpp"
#include "shockgas/spheres/parameters.hpp"

namespace shockgas::spheres {

namespace {
constexpr double never = std::numeric_limits<double>::infinity();
constexpr std::int32_t no_particle = -1;
// A start's pairs may overlap by round-off of the coordinates written to a
// file, not more.
constexpr double start_overlap_tolerance = 1e-9;
// Events that advance time by less than this fraction of max(t, 1), this many
// in a row, are a stall (engine.hpp).
constexpr double stall_time_fraction = 1e-12;
constexpr std::uint64_t stall_events_min = 1000000;
}  // namespace

struct HardSphereEngine::Core {
    virtual ~Core() = default;
    virtual bool advance_to(double t, const std::atomic<bool>* stop) = 0;
    virtual void run_collisions(std::uint64_t collisions) = 0;
    virtual SphereState state() const = 0;
    virtual std::vector<double> velocities() const = 0;
    virtual EngineRecord save() const = 0;
    virtual std::size_t memory_bytes() const = 0;
    double now = 0.0;
    EngineStatus status = EngineStatus::running;
    CollisionCounts counts;
};

namespace {

template <int D>
class CellEngine final : public HardSphereEngine::Core {
public:
    CellEngine(const SphereState& start, const CollisionModel& collision, double collapse_speed)
        : model_(collision), collapse_speed_(collapse_speed) {
        const auto n = static_cast<std::size_t>(start.particles());
        box_ = start.box_length;
        half_box_ = 0.5 * box_;
        cells_per_side_ = cells_per_side(box_);
        if (cells_per_side_ < 3)
            throw InputError(fmt::format("a box of side {} holds fewer than 3 cells of one diameter a side; "
                                         "use more particles or a lower packing fraction",
                                         box_));
        cell_width_ = box_ / cells_per_side_;
        std::size_t cell_count = 1;
        for (int k = 0; k < D; ++k) cell_count *= static_cast<std::size_t>(cells_per_side_);
        head_.assign(cell_count, no_particle);
        particles_.resize(n);
        cell_.resize(n);
        previous_.assign(n, no_particle);
        predictions_.resize(n);
        collisions_of_.assign(n, 0);
        now = start.time;
        for (std::size_t i = 0; i < n; ++i) {
            Particle& p = particles_[i];
            p.t = now;
            p.next = no_particle;
            for (int k = 0; k < D; ++k) {
                double x = start.positions[i * D + k];
                if (!std::isfinite(x) || !std::isfinite(start.velocities[i * D + k]))
                    throw InputError(fmt::format("particle {} has a coordinate or velocity that is not finite", i));
                x -= box_ * std::floor(x / box_);
                if (x >= box_) x = 0.0;
                p.x[k] = x;
                p.v[k] = start.velocities[i * D + k];
                cell_[i][k] = std::min(cells_per_side_ - 1, static_cast<int>(x / cell_width_));
            }
            insert(static_cast<std::int32_t>(i));
        }
        check_no_overlap();
        collapse_possible_ = model_.restitution < 1.0 && !(collapse_speed_ <= model_.velocity_threshold);
        queue_.reset(static_cast<std::int32_t>(n));
        for (std::size_t i = 0; i < n; ++i) {
            const auto id = static_cast<std::int32_t>(i);
            predict(id);
            if (event_time(id) != never) queue_.append_unordered(id, event_time(id));
        }
        queue_.heapify();
        stall_start_ = now;
    }

    // Restores an engine from save()'s record (engine.hpp, EngineRecord).
    CellEngine(const EngineRecord& record, const CollisionModel& collision, double collapse_speed)
        : model_(collision), collapse_speed_(collapse_speed) {
        box_ = record.box_length;
        half_box_ = 0.5 * box_;
        cells_per_side_ = cells_per_side(box_);
        cell_width_ = box_ / cells_per_side_;
        std::size_t cell_count = 1;
        for (int k = 0; k < D; ++k) cell_count *= static_cast<std::size_t>(cells_per_side_);
        const std::size_t n = record.reals.size() / reals_per_particle;
        if (cells_per_side_ < 3 || record.reals.size() != n * reals_per_particle + 1 ||
            record.integers.size() != n * integers_per_particle + cell_count + counters)
            throw InputError("the engine record does not fit its box and particle count");
        now = record.time;
        particles_.resize(n);
        predictions_.resize(n);
        collisions_of_.resize(n);
        cell_.resize(n);
        previous_.resize(n);
        const double* real = record.reals.data();
        const std::int64_t* integer = record.integers.data();
        for (std::size_t i = 0; i < n; ++i) {
            Particle& p = particles_[i];
            for (int k = 0; k < D; ++k) p.x[k] = *real++;
            for (int k = 0; k < D; ++k) p.v[k] = *real++;
            p.t = *real++;
            Prediction& e = predictions_[i];
            e.collision_time = *real++;
            e.crossing_time = *real++;
            e.partner = static_cast<std::int32_t>(*integer++);
            e.partner_collisions = static_cast<std::uint32_t>(*integer++);
            e.crossing_axis = static_cast<std::int32_t>(*integer++);
            e.crossing_step = static_cast<std::int32_t>(*integer++);
            collisions_of_[i] = static_cast<std::uint32_t>(*integer++);
            for (int k = 0; k < D; ++k) cell_[i][k] = static_cast<std::int32_t>(*integer++);
            p.next = static_cast<std::int32_t>(*integer++);
            previous_[i] = static_cast<std::int32_t>(*integer++);
        }
        stall_start_ = *real++;
        head_.resize(cell_count);
        for (auto& first : head_) first = static_cast<std::int32_t>(*integer++);
        counts.inelastic = static_cast<std::uint64_t>(*integer++);
        counts.elastic = static_cast<std::uint64_t>(*integer++);
        counts.cell_crossings = static_cast<std::uint64_t>(*integer++);
        counts.stale_events = static_cast<std::uint64_t>(*integer++);
        stall_events_ = static_cast<std::uint64_t>(*integer++);
        status = *integer++ != 0 ? EngineStatus::collapsed : EngineStatus::running;
        collapse_possible_ = model_.restitution < 1.0 && !(collapse_speed_ <= model_.velocity_threshold);
        queue_.reset(static_cast<std::int32_t>(n));
        for (std::size_t i = 0; i < n; ++i) {
            const auto id = static_cast<std::int32_t>(i);
            const double t = event_time(id);
            if (t != never) queue_.append_unordered(id, t);
        }
        queue_.heapify();
    }

    EngineRecord save() const override {
        EngineRecord record;
        record.dimension = D;
        record.box_length = box_;
        record.time = now;
        const std::size_t n = particles_.size();
        record.reals.reserve(n * reals_per_particle + 1);
        record.integers.reserve(n * integers_per_particle + head_.size() + counters);
        for (std::size_t i = 0; i < n; ++i) {
            const Particle& p = particles_[i];
            for (int k = 0; k < D; ++k) record.reals.push_back(p.x[k]);
            for (int k = 0; k < D; ++k) record.reals.push_back(p.v[k]);
            record.reals.push_back(p.t);
            const Prediction& e = predictions_[i];
            record.reals.push_back(e.collision_time);
            record.reals.push_back(e.crossing_time);
            record.integers.push_back(e.partner);
            record.integers.push_back(e.partner_collisions);
            record.integers.push_back(e.crossing_axis);
            record.integers.push_back(e.crossing_step);
            record.integers.push_back(collisions_of_[i]);
            for (int k = 0; k < D; ++k) record.integers.push_back(cell_[i][k]);
            record.integers.push_back(p.next);
            record.integers.push_back(previous_[i]);
        }
        record.reals.push_back(stall_start_);
        for (std::int32_t first : head_) record.integers.push_back(first);
        for (std::uint64_t c : {counts.inelastic, counts.elastic, counts.cell_crossings, counts.stale_events, stall_events_})
            record.integers.push_back(static_cast<std::int64_t>(c));
        record.integers.push_back(status == EngineStatus::collapsed ? 1 : 0);
        return record;
    }

    bool advance_to(double t, const std::atomic<bool>* stop) override {
        // The flag is read every 4096 events: a few milliseconds.
        for (std::uint32_t events = 0; status == EngineStatus::running && queue_.top_time() <= t; ++events) {
            if ((events & 4095u) == 4095u && stop != nullptr && stop->load(std::memory_order_relaxed)) return false;
            next_event();
        }
        if (status != EngineStatus::running) return true;
        now = std::max(now, t);
        for (auto& p : particles_) drift(p, now);
        return true;
    }

    void run_collisions(std::uint64_t collisions) override {
        const std::uint64_t target = counts.collisions() + collisions;
        while (status == EngineStatus::running && counts.collisions() < target && !queue_.empty()) next_event();
    }

    SphereState state() const override {
        SphereState out;
        out.dimension = D;
        out.box_length = box_;
        out.time = now;
        out.positions.resize(particles_.size() * D);
        out.velocities.resize(particles_.size() * D);
        for (std::size_t i = 0; i < particles_.size(); ++i) {
            const Particle& p = particles_[i];
            for (int k = 0; k < D; ++k) {
                double x = p.x[k] + p.v[k] * (now - p.t);
                x -= box_ * std::floor(x / box_);
                if (x >= box_) x = 0.0;
                out.positions[i * D + k] = x;
                out.velocities[i * D + k] = p.v[k];
            }
        }
        return out;
    }

    std::size_t memory_bytes() const override {
        const std::size_t n = particles_.size();
        return n * (sizeof(Particle) + sizeof(Prediction) + sizeof(std::uint32_t) + sizeof(CellCoordinates) +
                    sizeof(std::int32_t) + CalendarQueue::bytes_per_slot + sizeof(std::int32_t)) +
               head_.size() * sizeof(std::int32_t);
    }

    std::vector<double> velocities() const override {
        std::vector<double> out(particles_.size() * D);
        for (std::size_t i = 0; i < particles_.size(); ++i)
            for (int k = 0; k < D; ++k) out[i * D + k] = particles_[i].v[k];
        return out;
    }

private:
    // A particle's position is valid at its own clock t (delayed states).
    // next links the particles of a cell; it shares the particle's cache line
    // (64 bytes in 3D), which is the line a neighbour search reads anyway.
    struct alignas(D == 3 ? 64 : 16) Particle {
        std::array<double, D> x;
        std::array<double, D> v;
        double t;
        std::int32_t next;
    };
    // A particle's next collision (possibly stale: its partner has collided
    // since) and its next cell crossing; its queue key is the earlier.
    struct Prediction {
        double collision_time = never;
        double crossing_time = never;
        std::int32_t partner = no_particle;
        std::uint32_t partner_collisions = 0;  // the partner's count when predicted
        std::int32_t crossing_axis = 0;
        std::int32_t crossing_step = 0;        // +1 or -1
    };
    using CellCoordinates = std::array<std::int32_t, D>;
    static constexpr std::size_t reals_per_particle = 2 * D + 3;
    static constexpr std::size_t integers_per_particle = 7 + D;
    static constexpr std::size_t counters = 6;

    static void drift(Particle& p, double t) {
        const double dt = t - p.t;
        if (dt != 0.0)
            for (int k = 0; k < D; ++k) p.x[k] += p.v[k] * dt;
        p.t = t;
    }

    double event_time(std::int32_t i) const {
        const Prediction& e = predictions_[static_cast<std::size_t>(i)];
        return std::min(e.collision_time, e.crossing_time);
    }

    std::size_t cell_index(const CellCoordinates& c) const {
        std::size_t index = 0;
        for (int k = D - 1; k >= 0; --k) index = index * static_cast<std::size_t>(cells_per_side_) + static_cast<std::size_t>(c[k]);
        return index;
    }
    std::int32_t wrap_cell(std::int32_t c) const {
        return c < 0 ? c + cells_per_side_ : (c >= cells_per_side_ ? c - cells_per_side_ : c);
    }

    void insert(std::int32_t i) {
        const std::size_t c = cell_index(cell_[static_cast<std::size_t>(i)]);
        const std::int32_t first = head_[c];
        particles_[static_cast<std::size_t>(i)].next = first;
        previous_[static_cast<std::size_t>(i)] = no_particle;
        if (first != no_particle) previous_[static_cast<std::size_t>(first)] = i;
        head_[c] = i;
    }
    void remove(std::int32_t i) {
        const auto u = static_cast<std::size_t>(i);
        const std::int32_t before = previous_[u], after = particles_[u].next;
        if (before != no_particle)
            particles_[static_cast<std::size_t>(before)].next = after;
        else
            head_[cell_index(cell_[u])] = after;
        if (after != no_particle) previous_[static_cast<std::size_t>(after)] = before;
    }

    // The separation b - a under the minimum image, a and b at their clocks
    // brought to time `at`, and the relative velocity v_b - v_a.
    void separation(const Particle& a, const Particle& b, std::array<double, D>& dr, std::array<double, D>& dv) const {
        const double dta = now - a.t, dtb = now - b.t;
        for (int k = 0; k < D; ++k) {
            double d = (b.x[k] + b.v[k] * dtb) - (a.x[k] + a.v[k] * dta);
            if (d > half_box_)
                d -= box_;
            else if (d < -half_box_)
                d += box_;
            dr[k] = d;
            dv[k] = b.v[k] - a.v[k];
        }
    }

    // The time at which a (brought to now) and b touch, from
    // |dr + dv s| = 1 with dr.dv < 0: s = (dr^2 - 1) / (-dr.dv + sqrt((dr.dv)^2 - dv^2 (dr^2 - 1))),
    // the smaller root written without cancellation. An approaching pair
    // already closer than 1 by round-off collides at once (the overlap policy).
    // Pairs that cannot touch before `earliest` are passed over as never
    // before the square root: s >= (dr^2 - 1) / (-2 dr.dv), since the root is
    // at most -dr.dv. The time of a pair that can is computed in full, so the
    // result never depends on `earliest`.
    double contact_time(const Particle& a, const Particle& b, double earliest = never) const {
        std::array<double, D> dr, dv;
        separation(a, b, dr, dv);
        double approach = 0.0;
        for (int k = 0; k < D; ++k) approach += dr[k] * dv[k];
        if (approach >= 0.0) return never;
        double dr2 = 0.0, dv2 = 0.0;
        for (int k = 0; k < D; ++k) {
            dr2 += dr[k] * dr[k];
            dv2 += dv[k] * dv[k];
        }
        const double excess = dr2 - 1.0;
        if (excess <= 0.0) return now;
        if (excess > (earliest - now) * (-2.0 * approach)) return never;
        const double discriminant = approach * approach - dv2 * excess;
        if (discriminant <= 0.0) return never;
        return now + excess / (std::sqrt(discriminant) - approach);
    }

    // Looks for i's earliest collision among the particles of one cell; keeps
    // the earlier of it and what `e` holds.
    void scan_cell(std::int32_t i, const Particle& a, std::size_t cell, Prediction& e) const {
        for (std::int32_t j = head_[cell]; j != no_particle; j = particles_[static_cast<std::size_t>(j)].next) {
            if (j == i) continue;
            const double t = contact_time(a, particles_[static_cast<std::size_t>(j)], e.collision_time);
            if (t < e.collision_time) {
                e.collision_time = t;
                e.partner = j;
            }
        }
    }

    void predict_crossing(std::int32_t i) {
        const auto u = static_cast<std::size_t>(i);
        const Particle& a = particles_[u];
        Prediction& e = predictions_[u];
        e.crossing_time = never;
        const double dta = now - a.t;
        for (int k = 0; k < D; ++k) {
            const double v = a.v[k];
            if (v == 0.0) continue;
            const double x = a.x[k] + v * dta;
            const std::int32_t step = v > 0.0 ? 1 : -1;
            const double wall = (cell_[u][k] + (step > 0 ? 1 : 0)) * cell_width_;
            const double t = now + std::max(0.0, (wall - x) / v);
            if (t < e.crossing_time) {
                e.crossing_time = t;
                e.crossing_axis = k;
                e.crossing_step = step;
            }
        }
    }

    // i's next collision among the 3^d cells around it, and its next crossing.
    void predict(std::int32_t i) {
        const auto u = static_cast<std::size_t>(i);
        Prediction& e = predictions_[u];
        e.collision_time = never;
        e.partner = no_particle;
        const Particle& a = particles_[u];
        const CellCoordinates& c = cell_[u];
        CellCoordinates neighbour;
        if constexpr (D == 2) {
            for (int dy = -1; dy <= 1; ++dy) {
                neighbour[1] = wrap_cell(c[1] + dy);
                for (int dx = -1; dx <= 1; ++dx) {
                    neighbour[0] = wrap_cell(c[0] + dx);
                    scan_cell(i, a, cell_index(neighbour), e);
                }
            }
        } else {
            for (int dz = -1; dz <= 1; ++dz) {
                neighbour[2] = wrap_cell(c[2] + dz);
                for (int dy = -1; dy <= 1; ++dy) {
                    neighbour[1] = wrap_cell(c[1] + dy);
                    for (int dx = -1; dx <= 1; ++dx) {
                        neighbour[0] = wrap_cell(c[0] + dx);
                        scan_cell(i, a, cell_index(neighbour), e);
                    }
                }
            }
        }
        if (e.partner != no_particle) e.partner_collisions = collisions_of_[static_cast<std::size_t>(e.partner)];
        predict_crossing(i);
    }

    // After i entered a cell: only the layer of cells that has newly come
    // within reach can hold an earlier partner; the collision predicted
    // before stays (if stale, it is predicted again when its time comes:
    // every collision of i with a particle that has moved since was predicted
    // by that particle).
    void predict_after_crossing(std::int32_t i, int axis, std::int32_t step) {
        const auto u = static_cast<std::size_t>(i);
        Prediction& e = predictions_[u];
        const std::int32_t old_partner = e.partner;
        const Particle& a = particles_[u];
        const CellCoordinates& c = cell_[u];
        CellCoordinates neighbour;
        neighbour[axis] = wrap_cell(c[axis] + step);
        const int other1 = axis == 0 ? 1 : 0;
        if constexpr (D == 2) {
            for (int d1 = -1; d1 <= 1; ++d1) {
                neighbour[other1] = wrap_cell(c[other1] + d1);
                scan_cell(i, a, cell_index(neighbour), e);
            }
        } else {
            const int other2 = axis == 2 ? 1 : 2;
            for (int d2 = -1; d2 <= 1; ++d2) {
                neighbour[other2] = wrap_cell(c[other2] + d2);
                for (int d1 = -1; d1 <= 1; ++d1) {
                    neighbour[other1] = wrap_cell(c[other1] + d1);
                    scan_cell(i, a, cell_index(neighbour), e);
                }
            }
        }
        if (e.partner != old_partner) e.partner_collisions = collisions_of_[static_cast<std::size_t>(e.partner)];
        predict_crossing(i);
    }

    void next_event() {
        const std::int32_t i = queue_.top_slot();
        const auto u = static_cast<std::size_t>(i);
        const double t = queue_.top_time();
        queue_.popped();
        watch_for_stall(t);
        now = t;
        Prediction& e = predictions_[u];
        if (e.crossing_time < e.collision_time) {
            cross(i, e.crossing_axis, e.crossing_step);
        } else if (collisions_of_[static_cast<std::size_t>(e.partner)] != e.partner_collisions) {
            ++counts.stale_events;
            drift(particles_[u], now);
            predict(i);
            queue_.schedule(i, event_time(i));
        } else {
            collide_pair(i, e.partner);
        }
    }

    void cross(std::int32_t i, int axis, std::int32_t step) {
        const auto u = static_cast<std::size_t>(i);
        Particle& p = particles_[u];
        drift(p, now);
        remove(i);
        std::int32_t& c = cell_[u][axis];
        c += step;
        if (c == cells_per_side_) {
            c = 0;
            p.x[axis] -= box_;
        } else if (c < 0) {
            c = cells_per_side_ - 1;
            p.x[axis] += box_;
        }
        insert(i);
        ++counts.cell_crossings;
        predict_after_crossing(i, axis, step);
        queue_.schedule(i, event_time(i));
    }

    // The paper's rule on the normal relative velocity g_n = (v_i - v_j).n,
    // n the unit vector from i to j: restitution r when g_n >= delta, elastic
    // below (classify, collision.hpp). The normal kick per unit mass is the
    // velocity the rule gives a resting partner, collide(1, g_n, 1, 0, r):
    // (1 + r) g_n / 2, so v_i -= J n, v_j += J n; tangential velocities kept.
    void collide_pair(std::int32_t i, std::int32_t j) {
        Particle& a = particles_[static_cast<std::size_t>(i)];
        Particle& b = particles_[static_cast<std::size_t>(j)];
        drift(a, now);
        drift(b, now);
        std::array<double, D> dr, dv;
        separation(a, b, dr, dv);
        double dr2 = 0.0;
        for (int k = 0; k < D; ++k) dr2 += dr[k] * dr[k];
        const double inverse_distance = 1.0 / std::sqrt(dr2);
        double normal_speed = 0.0;
        for (int k = 0; k < D; ++k) normal_speed -= dv[k] * dr[k];
        normal_speed *= inverse_distance;
        if (normal_speed > 0.0) {
            const CollisionKind kind = classify(model_, normal_speed);
            if (kind == CollisionKind::inelastic && collapse_possible_ && normal_speed < collapse_speed_) {
                status = EngineStatus::collapsed;
                return;
            }
            const double restitution = kind == CollisionKind::inelastic ? model_.restitution : 1.0;
            const double kick = collide(1.0, normal_speed, 1.0, 0.0, restitution).right_velocity * inverse_distance;
            for (int k = 0; k < D; ++k) {
                a.v[k] -= kick * dr[k];
                b.v[k] += kick * dr[k];
            }
            if (kind == CollisionKind::inelastic && restitution < 1.0)
                ++counts.inelastic;
            else
                ++counts.elastic;
            ++collisions_of_[static_cast<std::size_t>(i)];
            ++collisions_of_[static_cast<std::size_t>(j)];
        }
        predict(i);
        predict(j);
        queue_.schedule(i, event_time(i));
        queue_.schedule(j, event_time(j));
    }

    void watch_for_stall(double t) {
        if (t - stall_start_ > stall_time_fraction * std::max(1.0, std::abs(t))) {
            stall_start_ = t;
            stall_events_ = 0;
            return;
        }
        if (++stall_events_ <= stall_events_min + 10 * particles_.size()) return;
        if (collapse_possible_) {
            status = EngineStatus::collapsed;
            return;
        }
        throw NumericalFailure(fmt::format("{} events in a row advanced time by less than {} of t = {}: events crowd "
                                           "at one instant beyond what double precision resolves",
                                           stall_events_, stall_time_fraction, t));
    }

    void check_no_overlap() const {
        const double closest = (1.0 - start_overlap_tolerance) * (1.0 - start_overlap_tolerance);
        for (std::size_t i = 0; i < particles_.size(); ++i) {
            const CellCoordinates& c = cell_[i];
            CellCoordinates neighbour;
            const int span = D == 2 ? 9 : 27;
            for (int code = 0; code < span; ++code) {
                int rest = code;
                for (int k = 0; k < D; ++k) {
                    neighbour[k] = wrap_cell(c[k] + rest % 3 - 1);
                    rest /= 3;
                }
                for (std::int32_t j = head_[cell_index(neighbour)]; j != no_particle; j = particles_[static_cast<std::size_t>(j)].next) {
                    if (static_cast<std::size_t>(j) <= i) continue;
                    std::array<double, D> dr, dv;
                    separation(particles_[i], particles_[static_cast<std::size_t>(j)], dr, dv);
                    double dr2 = 0.0;
                    for (int k = 0; k < D; ++k) dr2 += dr[k] * dr[k];
                    if (dr2 < closest)
                        throw InputError(fmt::format("particles {} and {} of the start overlap: their centres are {} "
                                                     "apart, less than one diameter",
                                                     i, j, std::sqrt(dr2)));
                }
            }
        }
    }

    CollisionModel model_;
    double collapse_speed_;
    bool collapse_possible_ = false;
    double box_ = 0.0, half_box_ = 0.0, cell_width_ = 0.0;
    std::int32_t cells_per_side_ = 0;
    std::vector<Particle> particles_;
    std::vector<Prediction> predictions_;
    std::vector<std::uint32_t> collisions_of_;
    std::vector<CellCoordinates> cell_;
    std::vector<std::int32_t> head_, previous_;
    CalendarQueue queue_;
    double stall_start_ = 0.0;
    std::uint64_t stall_events_ = 0;
};

}  // namespace

HardSphereEngine::HardSphereEngine(const SphereState& start, const CollisionModel& collision, double collapse_speed) {
    if (start.dimension != 2 && start.dimension != 3)
        throw InputError(fmt::format("dimension {} is not 2 or 3", start.dimension));
    if (start.positions.size() != start.velocities.size() || start.velocities.size() % static_cast<std::size_t>(start.dimension) != 0)
        throw InputError("the start's positions and velocities do not hold d numbers for each particle");
    if (start.dimension == 2)
        core_ = std::make_unique<CellEngine<2>>(start, collision, collapse_speed);
    else
        core_ = std::make_unique<CellEngine<3>>(start, collision, collapse_speed);
}
HardSphereEngine::HardSphereEngine(const EngineRecord& record, const CollisionModel& collision, double collapse_speed) {
    if (record.dimension == 2)
        core_ = std::make_unique<CellEngine<2>>(record, collision, collapse_speed);
    else if (record.dimension == 3)
        core_ = std::make_unique<CellEngine<3>>(record, collision, collapse_speed);
    else
        throw InputError(fmt::format("the engine record's dimension {} is not 2 or 3", record.dimension));
}
EngineRecord HardSphereEngine::save() const { return core_->save(); }
std::size_t HardSphereEngine::memory_bytes() const { return core_->memory_bytes(); }
HardSphereEngine::~HardSphereEngine() = default;
HardSphereEngine::HardSphereEngine(HardSphereEngine&&) noexcept = default;
HardSphereEngine& HardSphereEngine::operator=(HardSphereEngine&&) noexcept = default;

bool HardSphereEngine::advance_to(double t, const std::atomic<bool>* stop) { return core_->advance_to(t, stop); }
void HardSphereEngine::run_collisions(std::uint64_t collisions) { core_->run_collisions(collisions); }
double HardSphereEngine::time() const { return core_->now; }
EngineStatus HardSphereEngine::status() const { return core_->status; }
const CollisionCounts& HardSphereEngine::counts() const { return core_->counts; }
SphereState HardSphereEngine::state() const { return core_->state(); }
std::vector<double> HardSphereEngine::velocities() const { return core_->velocities(); }

}  // namespace shockgas::spheres
