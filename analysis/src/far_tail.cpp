// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/analysis/far_tail.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/io/output.hpp"

namespace shockgas::analysis {

FarTail read_far_tail(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    if (!is_far_tail_file(root))
        throw h5::Error("not a far-tail file (shockgas-tail output has the root attribute kind = far_tail) in '" +
                        path + "'");
    FarTail tail;
    tail.z = root.read_doubles("z");
    tail.log_phi = root.read_doubles("log_phi");
    tail.log_phi_sigma = root.read_doubles("log_phi_sigma");
    tail.time = root.attribute_double("time");
    std::vector<hsize_t> dims;
    const auto leave_one_out = root.read_doubles("log_phi_leave_one_chain_out", &dims);
    // Every table is one value per z bin. A damaged or hand-made file with a
    // short table would be read past its end (a gamma that looks measured):
    // refused, with the dataset and the file named.
    auto damaged = [&](const std::string& what) { return h5::Error(fmt::format("{} in '{}'", what, path)); };
    for (const auto& [name, table] : {std::pair<const char*, const std::vector<double>*>{"log_phi", &tail.log_phi},
                                      {"log_phi_sigma", &tail.log_phi_sigma}})
        if (table->size() != tail.z.size())
            throw damaged(fmt::format("/{} holds {} values but /z holds {}: one per z bin expected", name,
                                      table->size(), tail.z.size()));
    if (dims.size() != 2 || dims[1] != tail.z.size())
        throw damaged(fmt::format("/log_phi_leave_one_chain_out is not chains x z bins (z holds {} bins)",
                                  tail.z.size()));
    if (!std::all_of(tail.z.begin(), tail.z.end(), [](double z) { return std::isfinite(z); }) ||
        std::adjacent_find(tail.z.begin(), tail.z.end(), std::greater_equal<>()) != tail.z.end())
        throw damaged("/z is not finite and increasing");
    if (std::none_of(tail.log_phi.begin(), tail.log_phi.end(), [](double v) { return std::isfinite(v); }))
        throw damaged("/log_phi holds no finite value: the sampler measured no bin");
    for (hsize_t c = 0; c < dims[0]; ++c)
        tail.log_phi_leave_one_chain_out.emplace_back(leave_one_out.begin() + static_cast<std::ptrdiff_t>(c * dims[1]),
                                                      leave_one_out.begin() + static_cast<std::ptrdiff_t>((c + 1) * dims[1]));
    return tail;
}

namespace {

struct Selection {
    std::vector<double> z, y, sigma;  // y = ln Phi + 2 ln z
};

Selection select(const std::vector<double>& z, const std::vector<double>& log_phi,
                 const std::vector<double>& log_phi_sigma, double z_lo, double z_hi) {
    Selection s;
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (z[i] < z_lo || z[i] > z_hi || !std::isfinite(log_phi[i]) || !std::isfinite(log_phi_sigma[i]) ||
            !(log_phi_sigma[i] > 0.0))
            continue;
        s.z.push_back(z[i]);
        s.y.push_back(log_phi[i] + 2.0 * std::log(z[i]));
        s.sigma.push_back(log_phi_sigma[i]);
    }
    return s;
}

struct FitAtGamma {
    double c = 0.0, a = 0.0, b = 0.0, chi2 = 0.0;
};

// Eq. (6) + EB9 at fixed gamma: y = c - a z^gamma - b z, linear in (c, a, b),
// or in (c, a) when b is given (a straight line in z^gamma).
FitAtGamma fit_at(const Selection& s, double gamma, std::optional<double> linear_coefficient) {
    if (linear_coefficient) {
        std::vector<double> x(s.z.size()), y(s.z.size());
        for (std::size_t i = 0; i < s.z.size(); ++i) {
            x[i] = std::pow(s.z[i], gamma);
            y[i] = s.y[i] + *linear_coefficient * s.z[i];
        }
        const LinearFit line = weighted_linear_fit(x, y, s.sigma);
        return {line.intercept, -line.slope, *linear_coefficient, line.chi2};
    }
    std::vector<double> design;
    design.reserve(3 * s.z.size());
    for (double z : s.z) {
        design.push_back(1.0);
        design.push_back(-std::pow(z, gamma));
        design.push_back(-z);
    }
    const MultilinearFit fit = weighted_multilinear_fit(design, 3, s.y, s.sigma);
    return {fit.parameters[0], fit.parameters[1], fit.parameters[2], fit.chi2};
}

constexpr double gamma_min = 1.0, gamma_max = 6.0;  // brackets the Gaussian (2) and the exact (3) widely

// sigma(ln Phi) pooled (root mean square) over the bins within
// +-sigma_pool_bins. The chains' jackknife gives each bin's sigma from only
// 4-6 values (3-5 degrees of freedom), and weighing bins by the inverse
// squares of such estimates makes gamma scatter twice as much as pooled weights
// do and its jackknife sigma four times too small (synthetic tails with
// sampler-like errors, 4 chains; test TailExponent.JackknifeCoverageWithFourChains;
// the numbers: docs/measurements.md, "Measurements behind constants in the code").
// sigma changes slowly with z against a bin's 0.02, so pooling over +-0.1 in z
// costs little bias. A bin without a sigma (one chain reached it) stays
// without: it is not fitted.
constexpr int sigma_pool_bins = 5;
std::vector<double> pooled_sigma(const std::vector<double>& sigma) {
    const auto usable = [&](std::size_t i) { return std::isfinite(sigma[i]) && sigma[i] > 0.0; };
    std::vector<double> pooled(sigma.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < sigma.size(); ++i) {
        if (!usable(i)) continue;
        const std::size_t first = i >= sigma_pool_bins ? i - sigma_pool_bins : 0;
        const std::size_t last = std::min(sigma.size() - 1, i + sigma_pool_bins);
        double sum = 0.0;
        std::size_t count = 0;
        for (std::size_t j = first; j <= last; ++j)
            if (usable(j)) {
                sum += sigma[j] * sigma[j];
                ++count;
            }
        pooled[i] = std::sqrt(sum / static_cast<double>(count));
    }
    return pooled;
}

// The leave-one-chain-out replica's own sigma(ln Phi), bin by bin: the
// delete-one spread of the other chains' leave-one-out tables. Each of those
// differs from the next by the difference of two chains the replica keeps, so
// the spread is the replica's jackknife sigma up to a factor common to every
// bin (exactly so where ln Phi is the chains' mean), which leaves gamma's
// minimum where it is. NaN where any of them is. Needs >= 3 chains.
std::vector<double> replica_sigma(const FarTail& tail, std::size_t left_out) {
    const auto& tables = tail.log_phi_leave_one_chain_out;
    const double kept = static_cast<double>(tables.size() - 1);
    std::vector<double> sigma(tail.z.size());
    for (std::size_t i = 0; i < tail.z.size(); ++i) {
        double mean = 0.0;
        for (std::size_t c = 0; c < tables.size(); ++c)
            if (c != left_out) mean += tables[c][i] / kept;
        double squares = 0.0;
        for (std::size_t c = 0; c < tables.size(); ++c)
            if (c != left_out) squares += (tables[c][i] - mean) * (tables[c][i] - mean);
        sigma[i] = std::sqrt((kept - 1.0) / kept * squares);  // NaN propagates
    }
    return pooled_sigma(sigma);
}

// The requested window [z_lo, z_hi] against the bins fitted: an end that lies
// more than a bin spacing beyond the nearest fitted bin was cut by the data (the
// tail ends, or its bins there are unusable). Empty when the window was not cut.
std::string clipped_window_note(const std::vector<double>& z, double z_lo, double z_hi, const TailExponentFit& fit) {
    auto spacing_at = [&](double at) {
        const auto k = static_cast<std::size_t>(std::lower_bound(z.begin(), z.end(), at) - z.begin());
        if (k + 1 < z.size()) return z[k + 1] - z[k];
        return k > 0 && k < z.size() ? z[k] - z[k - 1] : 0.0;
    };
    const bool low = z_lo < fit.z_lo - spacing_at(fit.z_lo) * (1.0 + 1e-9);
    const bool high = z_hi > fit.z_hi + spacing_at(fit.z_hi) * (1.0 + 1e-9);
    if (!low && !high) return "";
    return fmt::format("the window [{:g}, {:g}] was clipped to the data: usable bins {}, fitted over z in [{:.3g}, "
                       "{:.3g}]",
                       z_lo, z_hi, low && high ? "cover less on both ends" : high ? "end before z_hi" : "start after z_lo",
                       fit.z_lo, fit.z_hi);
}

}  // namespace

TailExponentFit fit_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi,
                                  const std::vector<double>& log_phi_sigma, double z_lo, double z_hi,
                                  std::optional<double> linear_coefficient) {
    const Selection s = select(z, log_phi, log_phi_sigma, z_lo, z_hi);
    if (s.z.size() < 6) throw InsufficientData("tail-exponent fit: fewer than 6 usable bins in the window");
    const SearchMinimum search =
        minimise([&](double g) { return fit_at(s, g, linear_coefficient).chi2; }, gamma_min, gamma_max, 100);
    const double gamma = search.argmin;
    const FitAtGamma best = fit_at(s, gamma, linear_coefficient);
    TailExponentFit fit;
    fit.search = search;
    fit.gamma = gamma;
    fit.c = best.c;
    fit.a = best.a;
    fit.b = best.b;
    fit.points = s.z.size();
    const std::size_t fitted = linear_coefficient ? 3 : 4;  // c, a, (b,) gamma
    fit.chi2_per_dof = best.chi2 / static_cast<double>(s.z.size() - fitted);
    fit.z_lo = s.z.front();
    fit.z_hi = s.z.back();
    if (search.at_bound) {
        // The range, not the data, stopped the search: no gamma, no width.
        fit.gamma = std::numeric_limits<double>::quiet_NaN();
        fit.gamma_note = search.bound_note();
        fit.gamma_fit_sigma = std::numeric_limits<double>::quiet_NaN();
        fit.gamma_fit_sigma_note = "gamma " + search.bound_note();
        return fit;
    }
    // Delta chi2 = 1 half-width from the curvature of the profiled chi2(gamma).
    const double h = 1e-3 * gamma;
    const double curvature =
        (fit_at(s, gamma + h, linear_coefficient).chi2 - 2.0 * best.chi2 + fit_at(s, gamma - h, linear_coefficient).chi2) /
        (h * h);
    fit.gamma_fit_sigma = curvature > 0.0 ? std::sqrt(2.0 / curvature) : std::numeric_limits<double>::quiet_NaN();
    if (!(curvature > 0.0)) fit.gamma_fit_sigma_note = "chi2(gamma) is not curved upwards at its minimum";
    return fit;
}

double local_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi, double z0,
                           double half_width) {
    std::vector<double> log_z, log_excess;
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (std::abs(z[i] - z0) > half_width || !(z[i] > 0.0) || !std::isfinite(log_phi[i])) continue;
        const double excess = -(log_phi[i] + 2.0 * std::log(z[i]) - std::log(exact_tail_prefactor));
        if (!(excess > 0.0)) return std::numeric_limits<double>::quiet_NaN();
        log_z.push_back(std::log(z[i]));
        log_excess.push_back(std::log(excess));
    }
    if (log_z.size() < 3) return std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> unit(log_z.size(), 1.0);
    return weighted_linear_fit(log_z, log_excess, unit, ErrorModel::scale_by_residuals).slope;
}

double TailExponent::total_sigma() const { return std::hypot(gamma.sigma, window_systematic.value); }

TailExponent estimate_tail_exponent(const FarTail& tail, double z_lo, double z_hi, double window_shift,
                                    std::optional<double> linear_coefficient) {
    TailExponent result;
    const std::vector<double> sigma = pooled_sigma(tail.log_phi_sigma);
    result.fit = fit_tail_exponent(tail.z, tail.log_phi, sigma, z_lo, z_hi, linear_coefficient);
    const std::size_t chains = tail.log_phi_leave_one_chain_out.size();
    result.window_note = clipped_window_note(tail.z, z_lo, z_hi, result.fit);
    if (chains < 3) {
        // gamma is the fit's; its jackknife sigma is n/a, as the histogram tail's with R <= 2, also
        // for fewer than 2 chains (shockgas-tail refuses them; a hand-made file): the fit made, the
        // command goes on.
        const char* const why =
            chains == 2 ? "two chains: each jackknife replica keeps one, which has no spread to weigh the bins by; "
                          "run 3 or more chains"
            : chains == 1 ? "one chain: the jackknife has nothing to leave out; run 3 or more chains"
                          : "no leave-one-chain-out table: no jackknife; run 3 or more chains";
        result.gamma = {result.fit.gamma, std::numeric_limits<double>::quiet_NaN(),
                        !result.fit.gamma_note.empty() ? result.fit.gamma_note : why};
    } else {
        // Each leave-one-chain-out fit weighs the bins by its own chains' spread
        // (replica_sigma), as the decay and histogram-tail replicas do: with the
        // full estimate's weights, sigma left out the weights' own scatter.
        result.gamma = bounded_jackknife(chains, [&](std::optional<std::size_t> left_out) {
            if (!left_out) return result.fit.search;
            return fit_tail_exponent(tail.z, tail.log_phi_leave_one_chain_out[*left_out],
                                     replica_sigma(tail, *left_out), z_lo, z_hi, linear_coefficient)
                .search;
        });
    }
    if (!result.fit.gamma_note.empty()) {
        result.window_systematic = Measured::missing("gamma " + result.fit.gamma_note);
        return result;
    }
    double lowest = result.fit.gamma, highest = result.fit.gamma;
    std::size_t shifted = 0;  // windows other than the given one that could be fitted
    std::string shifted_at_bound;  // the first shifted window whose gamma is at a search bound
    for (double lo_shift : {-window_shift, 0.0, window_shift})
        for (double hi_shift : {-window_shift, 0.0, window_shift}) {
            if (lo_shift == 0.0 && hi_shift == 0.0) continue;  // the given window: result.fit
            try {
                const TailExponentFit moved = fit_tail_exponent(tail.z, tail.log_phi, sigma,
                                                                z_lo + lo_shift, z_hi + hi_shift, linear_coefficient);
                if (!moved.gamma_note.empty()) {
                    if (shifted_at_bound.empty())
                        shifted_at_bound = fmt::format("gamma over the moved window [{:g}, {:g}] is {}",
                                                       z_lo + lo_shift, z_hi + hi_shift, moved.gamma_note);
                    continue;
                }
                lowest = std::min(lowest, moved.gamma);
                highest = std::max(highest, moved.gamma);
                ++shifted;
            } catch (const InsufficientData&) {
                // a shifted window beyond the data: not counted
            }
        }
    // The spread of the given window alone is not 0 but unknown; nor is a
    // spread that includes a window whose gamma only the search range bounds.
    if (!shifted_at_bound.empty())
        result.window_systematic = Measured::missing(shifted_at_bound);
    else
        result.window_systematic =
            shifted > 0 ? Measured{(highest - lowest) / 2.0, ""}
                        : Measured::missing(window_shift > 0.0
                                                ? fmt::format("no window with its ends moved by +-{:g} holds 6 usable "
                                                              "bins",
                                                              window_shift)
                                                : std::string("window shift 0: no other window to compare with"));
    return result;
}

}  // namespace shockgas::analysis
