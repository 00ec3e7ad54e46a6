// SPDX-License-Identifier: GPL-3.0-or-later
// Kinetic theory of the hard-disk and hard-sphere gas (diameter, mass and
// Boltzmann's constant 1): the numbers the engine is checked against and the
// cooling law the figures are drawn against (docs/spheres.md, "Validation").
#pragma once

#include <cmath>
#include <numbers>

#include "shockgas/spheres/parameters.hpp"

namespace shockgas::spheres {

// The equilibrium pair correlation at contact: Henderson, Mol. Phys. 30, 971
// (1975) for disks, g = (1 - 7 phi/16) / (1 - phi)^2; Carnahan & Starling,
// J. Chem. Phys. 51, 635 (1969) for spheres, g = (1 - phi/2) / (1 - phi)^3.
inline double contact_value(int dimension, double phi) {
    return dimension == 2 ? (1.0 - 7.0 * phi / 16.0) / ((1.0 - phi) * (1.0 - phi))
                          : (1.0 - phi / 2.0) / ((1.0 - phi) * (1.0 - phi) * (1.0 - phi));
}

// Enskog's collision frequency per particle at temperature T:
// omega = (2 pi^((d-1)/2) / Gamma(d/2)) n g(1) sqrt(T), that is
// 2 sqrt(pi) n g sqrt(T) for disks and 4 sqrt(pi) n g sqrt(T) for spheres
// (Chapman & Cowling, ch. 16), with n = phi / v_d.
inline double enskog_frequency(int dimension, double phi, double temperature) {
    const double n = phi / sphere_volume(dimension);
    const double prefactor = (dimension == 2 ? 2.0 : 4.0) * std::sqrt(std::numbers::pi);
    return prefactor * n * contact_value(dimension, phi) * std::sqrt(temperature);
}

// Haff's law T(t) = T0 / (1 + t/t0)^2 (Haff, J. Fluid Mech. 134, 401 (1983)):
// each collision takes (1 - r^2) g_n^2 / 4 of kinetic energy, and <g_n^2> over
// collisions is 4 T, so dT/dt = -(1 - r^2) omega(T) T / d, whence
// t0 = 2 d / ((1 - r^2) omega(T0)).
inline double haff_time(int dimension, double phi, double restitution, double initial_temperature = 1.0) {
    return 2.0 * dimension /
           ((1.0 - restitution * restitution) * enskog_frequency(dimension, phi, initial_temperature));
}
inline double haff_temperature(double t, double t0, double initial_temperature = 1.0) {
    return initial_temperature / ((1.0 + t / t0) * (1.0 + t / t0));
}

}  // namespace shockgas::spheres
