// SPDX-License-Identifier: GPL-3.0-or-later
// Observables of one cluster state: the temperature, kinetic energy and the
// mass-weighted velocity histogram. Sums are compensated (Neumaier), so the
// values do not depend on N's size beyond rounding of the final result.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "shockgas/model/state.hpp"

namespace shockgas {

struct Moments {
    double total_mass = 0.0;
    double mean_velocity = 0.0;   // V = sum m v / M, in the lab
    double temperature = 0.0;     // T = sum m (v - V)^2 / M  (= sum m v^2/M - V^2)
    double kinetic_energy = 0.0;  // sum m v^2 / (2 M) in the lab: per unit mass, i.e. per particle for unit masses
    // V less the frame velocity the velocities were given in (ClusterState::
    // frame_velocity): the mean of the velocities as given, to subtract from them.
    double frame_mean_velocity = 0.0;
};

// T = sum_i m_i v_i^2 / M - (sum_i m_i v_i / M)^2 with M = sum_i m_i (the
// mass-weighted temperature of the paper, cluster velocities weighted by
// mass), computed in two passes as sum m (v - V)^2 / M for stability.
// Velocities in the lab, or relative to frame_velocity (the lab velocity of
// cluster i is frame_velocity + velocity[i]): T is computed from the given
// velocities alone (it is Galilean invariant), the mean and the kinetic
// energy in the lab.
Moments velocity_moments(const std::vector<double>& velocity, const std::vector<double>& mass,
                         double frame_velocity = 0.0);
// The same for a cluster state, in its own frame.
inline Moments velocity_moments(const ClusterState& state) {
    return velocity_moments(state.velocity, state.mass, state.frame_velocity);
}

// Bin edges for the histogram at time t: uniform in z = (v - V) t^(1/3) over
// [-range, range], i.e. v - V in [-range, range] t^(-1/3). The t^(1/3) is only
// a choice of binning that keeps the distribution resolved as it narrows; the
// edges are stored in velocity units, and the counts are raw.
std::vector<double> histogram_edges(double time, int bins, double range);

// Adds the mass of each cluster to the bin of (v - V). counts has bins + 2
// entries: [0] underflow, [1..bins] the bins, [bins + 1] overflow. V is
// taken in the state's frame (Moments::frame_mean_velocity), so v - V is
// formed from the velocities as the engine holds them.
void accumulate_histogram(const ClusterState& state, double frame_mean_velocity, const std::vector<double>& edges,
                          std::vector<double>& counts);

// Compensated summation (Neumaier 1974): accurate to O(ulp) independent of n.
class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        if (std::abs(sum_) >= std::abs(x))
            compensation_ += (sum_ - t) + x;
        else
            compensation_ += (x - t) + sum_;
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

private:
    double sum_ = 0.0;
    double compensation_ = 0.0;
};

}  // namespace shockgas
