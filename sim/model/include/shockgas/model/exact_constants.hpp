// SPDX-License-Identifier: GPL-3.0-or-later
// Exact constants of the paper's initial condition and of its two limits,
// held in one place for the simulator, the analysis and the tests.
#pragma once

namespace shockgas::exact {

// T0: velocities uniform on [-1, 1] have variance 1/3 (the paper's start).
inline constexpr double uniform_initial_temperature = 1.0 / 3.0;

// A of Haff's law T = T0 / (1 + A eps (1 - eps) sqrt(T0) t)^2 (Eq. (2); E3 in
// docs/paper-targets.md): a collision removes eps (1 - eps) g^2, and for the
// uniform start <|g|^3> = 4/5, giving A = 6 sqrt(3) / 5 (docs/haff-and-collapse.md).
inline constexpr double haff_constant_uniform = 6.0 * 1.7320508075688772 / 5.0;

// kappa of the sticky gas's T = kappa t^(-2/3) (Eq. (3)'s middle regime at
// r = 0), the variance of its exact Phi (EB7), computed by
// python/exact_ballistic.py (pinned there to 1e-9 by its test).
inline constexpr double sticky_gas_temperature_prefactor = 0.2128531785;

}  // namespace shockgas::exact
