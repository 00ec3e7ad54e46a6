#include "shockgas/analysis/far_tail.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shockgas/h5.hpp"

namespace shockgas::analysis {

FarTail read_far_tail(const std::string& path) {
    const auto file = h5::File::open_read(path);
    const auto root = file.root();
    if (!root.has_attribute("kind") || root.attribute_string("kind") != "far_tail")
        throw InsufficientData(path + " is not a far-tail file (shockgas-tail output)");
    FarTail tail;
    tail.z = root.read_doubles("z");
    tail.log_phi = root.read_doubles("log_phi");
    tail.log_phi_sigma = root.read_doubles("log_phi_sigma");
    tail.time = root.attribute_double("time");
    std::vector<hsize_t> dims;
    const auto leave_one_out = root.read_doubles("log_phi_leave_one_chain_out", &dims);
    if (dims.size() != 2 || dims[1] != tail.z.size()) throw InsufficientData(path + ": leave-one-out has the wrong shape");
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

// Eq. (5) + EB9 at fixed gamma: y = c - a z^gamma - b z, linear in (c, a, b).
MultilinearFit fit_at(const Selection& s, double gamma) {
    std::vector<double> design;
    design.reserve(3 * s.z.size());
    for (double z : s.z) {
        design.push_back(1.0);
        design.push_back(-std::pow(z, gamma));
        design.push_back(-z);
    }
    return weighted_multilinear_fit(design, 3, s.y, s.sigma);
}

constexpr double gamma_min = 1.0, gamma_max = 6.0;  // brackets the Gaussian (2) and the exact (3) widely

}  // namespace

TailExponentFit fit_tail_exponent(const std::vector<double>& z, const std::vector<double>& log_phi,
                                  const std::vector<double>& log_phi_sigma, double z_lo, double z_hi) {
    const Selection s = select(z, log_phi, log_phi_sigma, z_lo, z_hi);
    if (s.z.size() < 6) throw InsufficientData("tail-exponent fit: fewer than 6 usable bins in the window");
    const double gamma = minimise([&](double g) { return fit_at(s, g).chi2; }, gamma_min, gamma_max, 100);
    const MultilinearFit best = fit_at(s, gamma);
    TailExponentFit fit;
    fit.gamma = gamma;
    fit.c = best.parameters[0];
    fit.a = best.parameters[1];
    fit.b = best.parameters[2];
    fit.points = s.z.size();
    fit.chi2_per_dof = best.chi2 / static_cast<double>(s.z.size() - 4);  // c, a, b and gamma
    fit.z_lo = s.z.front();
    fit.z_hi = s.z.back();
    // Delta chi2 = 1 half-width from the curvature of the profiled chi2(gamma).
    const double h = 1e-3 * gamma;
    const double curvature =
        (fit_at(s, gamma + h).chi2 - 2.0 * best.chi2 + fit_at(s, gamma - h).chi2) / (h * h);
    fit.gamma_fit_sigma = curvature > 0.0 ? std::sqrt(2.0 / curvature) : std::numeric_limits<double>::quiet_NaN();
    return fit;
}

double TailExponent::total_sigma() const { return std::hypot(gamma.sigma, window_systematic); }

TailExponent estimate_tail_exponent(const FarTail& tail, double z_lo, double z_hi, double window_shift) {
    TailExponent result;
    result.fit = fit_tail_exponent(tail.z, tail.log_phi, tail.log_phi_sigma, z_lo, z_hi);
    const std::size_t chains = tail.log_phi_leave_one_chain_out.size();
    if (chains < 2) throw InsufficientData("tail exponent: the jackknife needs >= 2 chains");
    // Leave-one-chain-out fits keep the full estimate's weights (sigma).
    result.gamma = jackknife(chains, [&](std::optional<std::size_t> left_out) {
        if (!left_out) return result.fit.gamma;
        return fit_tail_exponent(tail.z, tail.log_phi_leave_one_chain_out[*left_out], tail.log_phi_sigma, z_lo, z_hi)
            .gamma;
    });
    double lowest = result.fit.gamma, highest = result.fit.gamma;
    for (double lo_shift : {-window_shift, 0.0, window_shift})
        for (double hi_shift : {-window_shift, 0.0, window_shift}) {
            try {
                const double g =
                    fit_tail_exponent(tail.z, tail.log_phi, tail.log_phi_sigma, z_lo + lo_shift, z_hi + hi_shift).gamma;
                lowest = std::min(lowest, g);
                highest = std::max(highest, g);
            } catch (const InsufficientData&) {
                // a shifted window beyond the data: not counted
            }
        }
    result.window_systematic = (highest - lowest) / 2.0;
    return result;
}

}  // namespace shockgas::analysis
