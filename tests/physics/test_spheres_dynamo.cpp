// SPDX-License-Identifier: GPL-3.0-or-later
// The disk and sphere gas against an independent implementation: DynamO, run
// from the same starts (tests/data/spheres_dynamo_reference.txt says how). The
// trajectories agree to 6 digits for the first 10-20 collisions per particle
// and then part (hard spheres are chaotic: round-off grows), so the
// comparison is of the ensembles: the mean T(t) and collisions per particle of
// 16 realizations, each code's standard error from its own realizations.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "shockgas/analysis/fit.hpp"
#include "shockgas/spheres/ensemble.hpp"

using namespace shockgas;
using namespace shockgas::spheres;

namespace {

struct Sample {
    std::vector<double> temperature, collisions_per_particle;  // one per realization
};
struct Case {
    int dimension = 3;
    std::int64_t particles = 0;
    double phi = 0, restitution = 1, threshold = 0;
    std::map<double, Sample> at;  // by time
};

std::map<std::string, Case> read_reference() {
    std::ifstream in(std::string(SHOCKGAS_TEST_DATA_DIR) + "/spheres_dynamo_reference.txt");
    std::map<std::string, Case> cases;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::string name;
        Case c;
        int realization = 0;
        double t = 0, temperature = 0, collisions = 0;
        fields >> name >> c.dimension >> c.particles >> c.phi >> c.restitution >> c.threshold >> realization >> t >>
            temperature >> collisions;
        Case& stored = cases.try_emplace(name, c).first->second;
        Sample& sample = stored.at[t];
        sample.temperature.push_back(temperature);
        sample.collisions_per_particle.push_back(2.0 * collisions / static_cast<double>(c.particles));
    }
    return cases;
}

// The two means differ by less than 4 combined standard errors: with 42
// compared numbers, 3 would be exceeded by chance in 1 of 6 such comparisons,
// 4 in 1 of 250. A different cooling rate (a restitution applied to the whole
// relative velocity, the threshold on |g| instead of g_n) moves T by 10-50
// standard errors by t = t0.
constexpr double agreement_sigmas = 4.0;

}  // namespace

TEST(SpheresAgainstDynamo, SameEnsembleFromTheSameStarts) {
    const auto cases = read_reference();
    ASSERT_EQ(cases.size(), 5u);
    int compared = 0;
    for (const auto& [name, c] : cases) {
        SphereParameters p;
        p.dimension = c.dimension;
        p.particles = c.particles;
        p.packing_fraction = c.phi;
        p.collision = {c.restitution, c.threshold, Subthreshold::elastic};
        p.seed = 1;
        p.realizations = 16;
        double t_max = 0;
        for (const auto& entry : c.at) {
            if (entry.first > 0) p.sample_times.push_back(entry.first);
            t_max = std::max(t_max, entry.first);
        }
        p.t_max = t_max;
        const SphereResult ours = run_spheres(p);
        for (const auto& [t, reference] : c.at) {
            if (t == 0) continue;
            std::size_t k = 0;
            while (ours.time[k] != t) ++k;
            Sample mine;
            for (int i = 0; i < p.realizations; ++i) {
                mine.temperature.push_back(ours.at(ours.temperature, i, k));
                mine.collisions_per_particle.push_back(ours.at(ours.collisions_per_particle, i, k));
            }
            for (const auto& [label, a, b] : {std::tuple{"T", mine.temperature, reference.temperature},
                                              std::tuple{"collisions per particle", mine.collisions_per_particle,
                                                         reference.collisions_per_particle}}) {
                const analysis::Estimate ours_estimate = analysis::mean_and_standard_error(a);
                const analysis::Estimate their_estimate = analysis::mean_and_standard_error(b);
                const double ours_mean = ours_estimate.value, ours_error = ours_estimate.sigma;
                const double their_mean = their_estimate.value, their_error = their_estimate.sigma;
                const double combined = std::hypot(ours_error, their_error);
                if (c.restitution == 1.0 && std::string(label) == "T") {
                    // Elastic: T = 1 in both, to round-off (10^-14 after 10^5 collisions).
                    EXPECT_NEAR(ours_mean, 1.0, 1e-12);
                    EXPECT_NEAR(their_mean, 1.0, 1e-12);
                    continue;
                }
                std::printf("%s t = %g %s: shockgas %.6g +- %.2g, DynamO %.6g +- %.2g (%.2f sigma)\n", name.c_str(), t,
                            label, ours_mean, ours_error, their_mean, their_error,
                            (ours_mean - their_mean) / combined);
                EXPECT_LT(std::abs(ours_mean - their_mean), agreement_sigmas * combined)
                    << name << " t = " << t << " " << label;
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, 42);  // T and collisions at every time, T of the elastic cases apart
}
