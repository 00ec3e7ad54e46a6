// SPDX-License-Identifier: GPL-3.0-or-later
// Burgers equation on a ring: inviscid (Legendre transform / convex minorant)
// and viscous (Hopf-Cole, cell-by-cell closed form, log-sum-exp). See burgers.hpp.
#include "shockgas/analysis/burgers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "shockgas/model/parameters.hpp"

namespace shockgas::burgers {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double sqrt_pi = 1.77245385090551602730;

// Cells whose smallest G lies more than this many units of 2 nu above the
// global minimum weigh less than e^-60 ~ 1e-26 each: dropped (even 10^8 of
// them change v by < 1e-18 relative).
constexpr double viscous_cutoff = 60.0;

// erfcx(z) = exp(z^2) erfc(z) for z >= 0. Below 25, erfc has full relative
// precision (erfc(25) ~ 1e-273 is still a normal double) and exp(z^2) costs
// z^2 ulp (~1e-13); above, the asymptotic series
// erfcx(z) = (1/(z sqrt pi)) sum_k (-1)^k (2k-1)!! / (2 z^2)^k, whose terms
// after k = 6 are < 1e-15 at z = 25.
double erfcx(double z) {
    if (z < 25.0) return std::exp(z * z) * std::erfc(z);
    const double inverse_two_z2 = 1.0 / (2.0 * z * z);
    double term = 1.0, sum = 1.0;
    for (int k = 1; k <= 7; ++k) {
        term *= -(2.0 * k - 1.0) * inverse_two_z2;
        sum += term;
    }
    return sum / (z * sqrt_pi);
}

// 10-point Gauss-Legendre nodes and weights on [-1, 1], by Newton's method on
// P_10 (exact to rounding; integrates e^{-(z^2 - A^2)} over an interval where
// the exponent changes by < 1/2 to machine precision).
struct GaussLegendre {
    static constexpr int order = 10;
    std::array<double, order> node{}, weight{};
    GaussLegendre() {
        for (int i = 0; i < order; ++i) {
            double x = std::cos(pi * (i + 0.75) / (order + 0.5));
            double derivative = 0.0;
            for (int iteration = 0; iteration < 100; ++iteration) {
                double p0 = 1.0, p1 = x;
                for (int n = 2; n <= order; ++n) {
                    const double p2 = ((2.0 * n - 1.0) * x * p1 - (n - 1.0) * p0) / n;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = order * (x * p1 - p0) / (x * x - 1.0);
                const double step = p1 / derivative;
                x -= step;
                if (std::abs(step) < 1e-16) break;
            }
            node[i] = x;
            weight[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
        }
    }
};
const GaussLegendre gauss_legendre;

// int_A^B e^{-z^2} dz = e^{-z0^2} f, z0 the point of [A, B] nearest 0.
// Returns (z0^2, f) so that logs never see an underflowed e^{-z0^2}.
struct ScaledGaussian {
    double z0_squared;
    double f;
};
ScaledGaussian gaussian_integral(double a, double b) {
    if (b <= 0.0) return gaussian_integral(-b, -a);  // symmetric integrand
    if (a < 0.0) return {0.0, 0.5 * sqrt_pi * (std::erf(b) - std::erf(a))};  // straddles 0: no cancellation
    const double rise = (b - a) * (b + a);  // B^2 - A^2
    if (rise < 0.5) {
        // Narrow interval: the erfcx difference would cancel; integrate directly.
        const double half = 0.5 * (b - a), mid = 0.5 * (b + a);
        double sum = 0.0;
        for (int i = 0; i < GaussLegendre::order; ++i) {
            const double z = mid + half * gauss_legendre.node[i];
            sum += gauss_legendre.weight[i] * std::exp(-(z - a) * (z + a));
        }
        return {a * a, half * sum};
    }
    return {a * a, 0.5 * sqrt_pi * (erfcx(a) - std::exp(-rise) * erfcx(b))};
}

std::int64_t floor_to_int(double x) { return static_cast<std::int64_t>(std::floor(x)); }

}  // namespace

std::int64_t first_off_lattice(const InitialCondition& initial) {
    const std::int64_t n = initial.size();
    const double length = initial.ring_length;
    const double spacing = length / static_cast<double>(n);
    for (std::int64_t i = 0; i < n; ++i) {
        const double expected = initial.position[0] + static_cast<double>(i) * spacing;
        if (std::abs(initial.position[i] - expected) > lattice_tolerance * length) return i;
    }
    return -1;
}

Grid grid_from_particles(const InitialCondition& initial, std::int64_t cells) {
    const std::int64_t n = initial.size();
    if (n < 1 || cells < 1) throw std::invalid_argument("burgers: no particles or no cells");
    const double length = initial.ring_length;
    const double spacing = length / static_cast<double>(n);
    // The Lagrangian picture needs the particles' own cells: equal spacing and masses.
    if (const std::int64_t off = first_off_lattice(initial); off >= 0)
        throw InputError("burgers: particles are not equally spaced (particle " + std::to_string(off) +
                         " is off the lattice x_0 + i L/N): the Burgers profile is built on the lattice of the "
                         "particles' start");
    for (std::int64_t i = 0; i < n; ++i)
        if (!initial.mass.empty() && initial.mass[i] != initial.mass[0])
            throw InputError("burgers: particles have unequal masses");
    Grid grid;
    grid.ring_length = length;
    grid.origin = initial.position[0] - 0.5 * spacing;  // particle i's cell is centred on x_i
    grid.velocity.resize(static_cast<std::size_t>(cells));
    if (cells % n == 0) {
        const std::int64_t per_particle = cells / n;
        for (std::int64_t c = 0; c < cells; ++c) grid.velocity[c] = initial.velocity[c / per_particle];
    } else if (n % cells == 0) {
        // Coarse grid: momentum per cell conserved (mean of the particles in it).
        const std::int64_t per_cell = n / cells;
        for (std::int64_t c = 0; c < cells; ++c) {
            double sum = 0.0;
            for (std::int64_t i = c * per_cell; i < (c + 1) * per_cell; ++i) sum += initial.velocity[i];
            grid.velocity[c] = sum / static_cast<double>(per_cell);
        }
    } else {
        throw InputError("burgers: cells (" + std::to_string(cells) + ") must be a multiple or a divisor of N (" +
                            std::to_string(n) + ")");
    }
    return grid;
}

std::vector<double> sample_points(double ring_length, std::int64_t points) {
    std::vector<double> x(static_cast<std::size_t>(points));
    for (std::int64_t j = 0; j < points; ++j) x[j] = ring_length * static_cast<double>(j) / static_cast<double>(points);
    return x;
}

Solver::Solver(Grid grid) : grid_(std::move(grid)) {
    const std::size_t m = grid_.velocity.size();
    if (m < 2 || !(grid_.ring_length > 0.0)) throw std::invalid_argument("burgers: need >= 2 cells and L > 0");
    // Neumaier-free plain mean is enough: V only enters through the Galilean shift.
    mean_velocity_ = std::accumulate(grid_.velocity.begin(), grid_.velocity.end(), 0.0) / static_cast<double>(m);
    const double h = grid_.cell_width();
    phi_.assign(m + 1, 0.0);
    for (std::size_t c = 0; c < m; ++c) phi_[c + 1] = phi_[c] + (grid_.velocity[c] - mean_velocity_) * h;
    // Zero mean makes Phi0 periodic; remove the rounding residue linearly.
    const double residue = phi_[m];
    for (std::size_t c = 0; c <= m; ++c) phi_[c] -= residue * static_cast<double>(c) / static_cast<double>(m);
    phi_min_ = *std::min_element(phi_.begin(), phi_.end());
    phi_max_ = *std::max_element(phi_.begin(), phi_.end());
}

double Solver::edge(std::int64_t c) const { return grid_.origin + static_cast<double>(c) * grid_.cell_width(); }

double Solver::cell_velocity(std::int64_t c) const {
    const auto m = static_cast<std::int64_t>(grid_.velocity.size());
    return grid_.velocity[((c % m) + m) % m] - mean_velocity_;
}

double Solver::phi_at_edge(std::int64_t c) const {
    const auto m = static_cast<std::int64_t>(grid_.velocity.size());
    return phi_[((c % m) + m) % m];
}

double Solver::reach(double t, double extra) const {
    // The minimiser q* has G_x(q*) <= G_x(x), so (x - q*)^2 / (2t) <= max Phi0 - min Phi0.
    return std::sqrt(2.0 * t * (phi_max_ - phi_min_ + extra)) + 2.0 * grid_.cell_width();
}

double Solver::face_slope(std::int64_t a, std::int64_t b, double t) const {
    // (Y_b - Y_a)/(q_b - q_a) for Y(q) = q^2/2 + t Phi0(q), from local differences only:
    // Y itself ~ L^2/2 would lose the digits that place a one-cell face.
    return 0.5 * (edge(a) + edge(b)) +
           t * (phi_at_edge(b) - phi_at_edge(a)) / (static_cast<double>(b - a) * grid_.cell_width());
}

std::vector<std::int64_t> Solver::lower_hull(double t) const {
    // Lower convex hull (monotone chain) of the nodes (q_c, Y_c) over the copies of the ring
    // that can hold a minimiser of G_x for x in the central copy. Eq. (7) via Hopf-Lax:
    // argmin_q G_x(q) = argmin_q Y(q) - x q, the hull vertex whose faces bracket slope x.
    const double h = grid_.cell_width(), r = reach(t, 0.0);
    const std::int64_t first = floor_to_int(-r / h) - 1;
    const std::int64_t last = static_cast<std::int64_t>(grid_.velocity.size()) + floor_to_int(r / h) + 2;
    std::vector<std::int64_t> hull;
    hull.reserve(static_cast<std::size_t>(last - first + 1));
    for (std::int64_t c = first; c <= last; ++c) {
        while (hull.size() >= 2 && face_slope(hull[hull.size() - 2], hull.back(), t) >= face_slope(hull.back(), c, t))
            hull.pop_back();
        hull.push_back(c);
    }
    return hull;
}

std::vector<double> Solver::inviscid(const std::vector<double>& x, double t) const {
    if (!(t > 0.0)) throw std::invalid_argument("burgers: t must be > 0");
    const double length = grid_.ring_length;
    // Galilean frame moving with V: w(x', t), x' = x - V t wrapped into [origin, origin + L).
    std::vector<double> local(x.size());
    for (std::size_t j = 0; j < x.size(); ++j) {
        double u = std::fmod(x[j] - mean_velocity_ * t - grid_.origin, length);
        if (u < 0.0) u += length;
        local[j] = grid_.origin + u;
    }
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return local[a] < local[b]; });

    const auto hull = lower_hull(t);
    auto slope = [&](std::int64_t a, std::int64_t b) { return face_slope(a, b, t); };
    std::vector<double> v(x.size());
    std::size_t k = 0;  // hull vertex; the minimiser moves right as x grows
    for (std::size_t j : order) {
        const double xj = local[j];
        while (k + 1 < hull.size() && slope(hull[k], hull[k + 1]) < xj) ++k;
        const std::int64_t vertex = hull[k];
        double q = edge(vertex);
        double best = (xj - q) * (xj - q) / (2.0 * t) + phi_at_edge(vertex);
        // Inside the cells next to the vertex G is a parabola; its interior minimum
        // q = x - t v_c (a particle's own cell, moving at v_c) beats the node when it lies in the cell.
        for (std::int64_t c : {vertex - 1, vertex}) {
            const double vc = cell_velocity(c), q_in = xj - t * vc;
            if (q_in <= edge(c) || q_in >= edge(c + 1)) continue;
            const double g = (xj - q_in) * (xj - q_in) / (2.0 * t) + phi_at_edge(c) + vc * (q_in - edge(c));
            if (g < best) {
                best = g;
                q = q_in;
            }
        }
        v[j] = mean_velocity_ + (xj - q) / t;  // Eq. (7): v = (x - q)/t
    }
    return v;
}

std::vector<Shock> Solver::shocks(double t, double min_mass) const {
    if (!(t > 0.0)) throw std::invalid_argument("burgers: t must be > 0");
    const double length = grid_.ring_length, h = grid_.cell_width();
    const auto m = static_cast<std::int64_t>(grid_.velocity.size());
    const auto hull = lower_hull(t);
    auto slope = [&](std::int64_t a, std::int64_t b) { return face_slope(a, b, t); };
    std::vector<Shock> out;
    for (std::size_t k = 0; k + 1 < hull.size(); ++k) {
        const std::int64_t a = hull[k], b = hull[k + 1];
        if (a < 0 || a >= m || b - a < 2) continue;  // one copy of each; a single cell is not a shock
        Shock s;
        s.q_left = edge(a);
        s.q_right = edge(b);
        if (s.mass() < min_mass) continue;
        // The face's slope is the shock position (Legendre transform: both ends map to it).
        double position = std::fmod(slope(a, b) + mean_velocity_ * t, length);
        if (position < 0.0) position += length;
        s.position = position;
        // Rankine-Hugoniot: (v_- + v_+)/2 = ((x - q_a) + (x - q_b))/(2t) = mean v0 over the face.
        s.velocity = mean_velocity_ + (phi_at_edge(b) - phi_at_edge(a)) / (static_cast<double>(b - a) * h);
        out.push_back(s);
    }
    std::sort(out.begin(), out.end(), [](const Shock& a, const Shock& b) { return a.position < b.position; });
    return out;
}

double Solver::temperature(double t) const {
    const auto hull = lower_hull(t);
    const auto m = static_cast<std::int64_t>(grid_.velocity.size());
    const double h = grid_.cell_width();
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < hull.size(); ++k) {
        const std::int64_t a = hull[k], b = hull[k + 1];
        if (a < 0 || a >= m) continue;
        const double mass = static_cast<double>(b - a) * h;
        const double velocity = (phi_at_edge(b) - phi_at_edge(a)) / mass;  // relative to V
        sum += mass * velocity * velocity;
    }
    return sum / grid_.ring_length;
}

std::vector<double> Solver::viscous(const std::vector<double>& x, double t, double nu) const {
    if (!(t > 0.0) || !(nu > 0.0)) throw std::invalid_argument("burgers: t and nu must be > 0");
    const double length = grid_.ring_length, h = grid_.cell_width();
    const double s = 2.0 * std::sqrt(nu * t);  // heat-kernel width: exp(-(x-y)^2/(4 nu t)) = exp(-((x-y)/s)^2)
    const double r = reach(t, 2.0 * nu * viscous_cutoff);
    std::vector<double> v(x.size());
    std::vector<double> log_weight, cell_mean;
    for (std::size_t j = 0; j < x.size(); ++j) {
        double u = std::fmod(x[j] - mean_velocity_ * t - grid_.origin, length);
        if (u < 0.0) u += length;
        const double xj = grid_.origin + u;
        const std::int64_t c_lo = floor_to_int((xj - r - grid_.origin) / h) - 1;
        const std::int64_t c_hi = floor_to_int((xj + r - grid_.origin) / h) + 1;
        // Per cell c, v0 = v_c: G_x(q) = (q - q_hat)^2/(2t) + const with q_hat = x - t v_c, so
        //   int_cell e^{-G/(2nu)} dq = e^{-G(q0)/(2nu)} s f,   f from gaussian_integral(A, B),
        //   A, B = (cell edges - q_hat)/s, q0 the cell point nearest q_hat;
        //   and the weighted mean of (x - q)/t = v_c + (q_hat - q)/t over the cell is
        //   v_c + (s/(2t)) (e^{-B^2} - e^{-A^2}) / (e^{-z0^2} f).
        log_weight.clear();
        cell_mean.clear();
        double largest = -std::numeric_limits<double>::infinity();
        for (std::int64_t c = c_lo; c <= c_hi; ++c) {
            const double vc = cell_velocity(c), left = edge(c);
            const double q_hat = xj - t * vc;
            const double q0 = std::clamp(q_hat, left, left + h);
            const double g0 = (xj - q0) * (xj - q0) / (2.0 * t) + phi_at_edge(c) + vc * (q0 - left);
            const double a = (left - q_hat) / s, b = (left + h - q_hat) / s;
            const ScaledGaussian integral = gaussian_integral(a, b);
            const double lw = -g0 / (2.0 * nu) + std::log(s * integral.f);
            const double ratio = (std::exp(integral.z0_squared - b * b) - std::exp(integral.z0_squared - a * a)) / integral.f;
            // The mean of (x - q)/t over a cell lies between its values at the edges.
            const double mean = std::clamp(vc + s / (2.0 * t) * ratio, (xj - left - h) / t, (xj - left) / t);
            log_weight.push_back(lw);
            cell_mean.push_back(mean);
            largest = std::max(largest, lw);
        }
        // v = -2 nu d ln u/dx as a ratio of log-sum-exps: sum e^{lw - max} mean / sum e^{lw - max}.
        double numerator = 0.0, denominator = 0.0;
        for (std::size_t i = 0; i < log_weight.size(); ++i) {
            const double shifted = log_weight[i] - largest;
            if (shifted < -viscous_cutoff) continue;
            const double w = std::exp(shifted);
            numerator += w * cell_mean[i];
            denominator += w;
        }
        v[j] = mean_velocity_ + numerator / denominator;
    }
    return v;
}

}  // namespace shockgas::burgers
