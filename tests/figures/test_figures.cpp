// SPDX-License-Identifier: GPL-3.0-or-later
// The quick-fidelity figures, through the real pipeline: every figure exists as
// PNG and PDF, and the fitted numbers each figure reports agree with theory.
// The FIXTURES_SETUP test figures.build ran `cmake --build --target figures`.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "shockgas/io/h5.hpp"

namespace {

namespace fs = std::filesystem;
const std::string figure_dir = SHOCKGAS_FIGURE_DIR;      // build/figures/quick
const std::string pipeline_dir = SHOCKGAS_PIPELINE_DIR;  // build/paper_targets/quick

double attribute(const std::string& file, const std::string& group, const std::string& name) {
    const auto h5 = shockgas::h5::File::open_read(pipeline_dir + "/" + file);
    return h5.root().open_group(group).attribute_double(name);
}

// Statistical error (jackknife over realizations) and the window-choice
// systematic in quadrature, as analysis/README.md explains; k = 3 of them.
constexpr double k_sigma = 3.0;

TEST(Figures, EveryFigureHasPngAndPdf) {
    for (const char* name : {"fig1", "fig2", "fig3", "fig4", "fig4_sticky", "fig5", "fig_collapse", "fig_crossovers", "fig_haff",
                             "fig_tradeoff", "fig_tail", "fig_validity", "fig_spheres", "fig_2d", "fig_2d_clusters", "fig_3d",
                             "fig_3d_clusters"})
        for (const char* extension : {".png", ".pdf"}) {
            const fs::path path = fs::path(figure_dir) / (std::string(name) + extension);
            ASSERT_TRUE(fs::exists(path)) << path;
            // A gnuplot canvas with axes and curves is tens of kB; an empty
            // or failed plot is a few hundred bytes.
            EXPECT_GT(fs::file_size(path), 10000u) << path;
        }
}

void expect_two_thirds(const std::string& run) {
    const std::string file = "fig1/" + run + ".decay.h5";
    const double exponent = attribute(file, "decay", "exponent");
    // The window systematic is missing (NaN) where the fit window holds only one
    // one-decade window (r = 0.9's [894, 10^4] at quick fidelity): then the
    // statistical error alone.
    const double window = attribute(file, "decay", "exponent_window_systematic");
    const double sigma = std::hypot(attribute(file, "decay", "exponent_sigma"), std::isnan(window) ? 0.0 : window);
    // Eq. (3): T ~ t^(-2/3) for every r < 1; the paper fits 0.67, 0.67, 0.66.
    EXPECT_NEAR(exponent, 2.0 / 3.0, k_sigma * sigma) << run << ": " << exponent << " +- " << sigma;
}

TEST(Figures, Fig1StickyGasDecaysAsTwoThirds) { expect_two_thirds("r0"); }
TEST(Figures, Fig1ModeratelyInelasticDecaysAsTwoThirds) { expect_two_thirds("r0.5"); }
TEST(Figures, Fig1WeaklyInelasticDecaysAsTwoThirds) { expect_two_thirds("r0.9"); }

TEST(Figures, Fig1PureInelasticRunsStopAtCollapse) {
    for (const char* run : {"pure_r0.5", "pure_r0.9", "pure_r0.99"}) {
        const auto h5 = shockgas::h5::File::open_read(pipeline_dir + "/fig1/" + run + ".h5");
        EXPECT_EQ(h5.root().attribute_string("status"), "collapsed") << run;
    }
}

// t_stick ~ eps^(-3/2) is the paper's matching of eps^-2 t^-2 with t^(-2/3) (Eq. 3). With the
// paper's elastic sub-threshold collisions (the quick tier's setting) the measured exponent over
// eps = 0.05 ... 0.00625 is steeper than that: the paper tier (N = 1e6, 10 realizations, delta = 1e-2,
// seeds 6090 ... 6098; docs/measurements.md, "The paper tier") gives -1.560 +- 0.003, while sticky sub-threshold
// collisions give -3/2 (AnalysisPhysics.StickTimeScalesAsEpsToMinusThreeHalves). The quick tier
// (N = 2e4: other initial conditions) must reproduce the paper tier within k sigma, the two errors
// in quadrature, and stay within the allowance below of the paper's -3/2.
constexpr double paper_tier_stick_exponent = -1.560, paper_tier_stick_exponent_sigma = 0.003;
// T(t_stick) ~ eps (Eq. 3) from the same paper-tier runs: 1.056 +- 0.005.
constexpr double paper_tier_stick_temperature_exponent = 1.056,
                 paper_tier_stick_temperature_exponent_sigma = 0.005;
// The paper tier's distance from -3/2 (0.060 +- 0.003, not understood; README, "What still falls
// short") plus three of the quick tier's sigma (0.015): a larger distance is a different law.
constexpr double stick_exponent_allowance_from_three_halves = 0.1;

TEST(Figures, StickTimeExponentIsThePaperTiersNearMinusThreeHalves) {
    const std::string file = "fig_crossovers/crossovers.h5";
    const double stick = attribute(file, "scaling_in_eps", "t_stick_exponent");
    const double stick_sigma = attribute(file, "scaling_in_eps", "t_stick_exponent_sigma");
    const double sigma = std::hypot(stick_sigma, paper_tier_stick_exponent_sigma);
    EXPECT_NEAR(stick, paper_tier_stick_exponent, k_sigma * sigma) << stick << " +- " << stick_sigma;
    EXPECT_NEAR(stick, -1.5, stick_exponent_allowance_from_three_halves) << stick << " +- " << stick_sigma;
    const double temperature = attribute(file, "scaling_in_eps", "temperature_at_stick_exponent");
    const double temperature_sigma = attribute(file, "scaling_in_eps", "temperature_at_stick_exponent_sigma");
    EXPECT_NEAR(temperature, paper_tier_stick_temperature_exponent,
                k_sigma * std::hypot(temperature_sigma, paper_tier_stick_temperature_exponent_sigma))
        << temperature << " +- " << temperature_sigma;
}

// Haff's law for this rule (docs/haff-and-collapse.md): T = T0 / (1 + A eps (1 - eps)
// sqrt(T0) t)^2 with A = 6 sqrt(3)/5, so T = T0/2 at
//   t_dissip = (sqrt 2 - 1) / (A sqrt(T0) eps (1 - eps)) = 0.3452 / (eps (1 - eps)):
// the paper's t_dissip ~ 1/eps, with its constant and the (1 - eps) of Eq. (1).
// Tolerance: the lattice start delays the first collisions, so the effective A
// at t ~ 8 is 1.99, 4.3% below A (docs/haff-and-collapse.md, Haff table); every t_dissip here is
// >= 7.5, so it can be late by at most that much.
constexpr double haff_dissipation_time_tolerance = 0.045;

TEST(Figures, DissipationTimeIsHaffsWithTheDerivedConstant) {
    const double predicted = (std::sqrt(2.0) - 1.0) / (6.0 * std::sqrt(3.0) / 5.0 * std::sqrt(1.0 / 3.0));
    const auto h5 = shockgas::h5::File::open_read(pipeline_dir + "/fig_crossovers/crossovers.h5");
    int checked = 0;
    for (int k = 0;; ++k) {
        const std::string group = "crossover" + std::to_string(k);
        if (!h5.root().has(group)) break;
        const double eps = h5.root().open_group(group).attribute_double("inelasticity");
        const double t_dissip = h5.root().open_group(group).attribute_double("t_dissip");
        EXPECT_NEAR(t_dissip * eps * (1 - eps), predicted, haff_dissipation_time_tolerance * predicted)
            << "eps = " << eps;
        ++checked;
    }
    EXPECT_GE(checked, 3);
}

TEST(Figures, VelocityDistributionsCollapseWithOneThird) {
    const double beta = attribute("fig4/scaling.h5", "collapse", "beta");
    const double beta_sigma = attribute("fig4/scaling.h5", "collapse", "beta_sigma");
    // Eq. (4): P(v,t) = t^(1/3) Phi(v t^(1/3)).
    EXPECT_NEAR(beta, 1.0 / 3.0, k_sigma * beta_sigma) << beta << " +- " << beta_sigma;
}

TEST(Figures, StickySubthresholdDistributionsCollapseWithOneThird) {
    const double beta = attribute("fig4_sticky/scaling.h5", "collapse", "beta");
    const double beta_sigma = attribute("fig4_sticky/scaling.h5", "collapse", "beta_sigma");
    // Eq. (4) again, with clusters merging below delta instead of colliding elastically.
    EXPECT_NEAR(beta, 1.0 / 3.0, k_sigma * beta_sigma) << beta << " +- " << beta_sigma;
}

// The paper's two sub-threshold mechanisms give one Phi, not only one T(t) (its
// Fig. 2): the kurtosis of each r > 0 histogram, elastic (fig4) against sticky
// (fig4_sticky), the same times and seeds. Both files hold r = 0's three times
// first (histograms 0-2), then r = 0.5's and r = 0.9's. The two sigmas (group
// jackknife over realizations) are added in quadrature although the sticky
// runs' first realizations start where the elastic ones do, which correlates
// them positively: the allowance is larger than the difference's own sigma.
TEST(Figures, ElasticAndStickySubthresholdGiveOneKurtosis) {
    int compared = 0;
    for (int h = 3; h < 9; ++h) {
        const std::string group = "histogram" + std::to_string(h);
        const double elastic = attribute("fig4/scaling.h5", group, "kurtosis");
        const double sticky = attribute("fig4_sticky/scaling.h5", group, "kurtosis");
        const double sigma = std::hypot(attribute("fig4/scaling.h5", group, "kurtosis_sigma"),
                                        attribute("fig4_sticky/scaling.h5", group, "kurtosis_sigma"));
        EXPECT_EQ(attribute("fig4/scaling.h5", group, "time"), attribute("fig4_sticky/scaling.h5", group, "time"))
            << group;
        EXPECT_NEAR(elastic, sticky, k_sigma * sigma) << group << ": elastic " << elastic << ", sticky " << sticky;
        ++compared;
    }
    EXPECT_EQ(compared, 6);
}

TEST(Figures, ShockSegmentsHaveSlopeOneOverT) {
    // Eq. (7): between shocks v = (x - q)/t; for particles of density rho in a
    // segment the slope is (1 - rho)/t (analysis/README.md, "Shocks").
    const double slope = attribute("fig5/shocks.h5", "shocks0", "density_corrected_slope_times_t");
    const double sigma = attribute("fig5/shocks.h5", "shocks0", "density_corrected_slope_times_t_sigma");
    EXPECT_NEAR(slope, 1.0, k_sigma * sigma) << slope << " +- " << sigma;
}

// fig_collapse (docs/haff-and-collapse.md, "Collapse against eps and N"): the
// quick tier's eps sweep (N = 40/eps, 8-16 realizations, seeds independent of
// the paper tier's) against the paper tier's measurement (docs/measurements.md,
// "Haff and collapse"; eps = 0.25 ... 5e-4, 8-64 realizations).
double collapse_form(const std::string& quantity, const std::string& form, const std::string& name) {
    return attribute("fig_collapse/vs_eps.h5", quantity + "_forms/" + form, name);
}
// Paper tier: t_collapse = C eps^-3/2 (ln 1/eps)^y and m = C eps^x.
constexpr double paper_tier_log_exponent = 0.936, paper_tier_log_exponent_sigma = 0.038;
constexpr double paper_tier_mass_exponent = -0.981, paper_tier_mass_exponent_sigma = 0.011;
// A difference of information criteria above 10 is decisive (Kass & Raftery,
// J. Am. Stat. Assoc. 90, 773 (1995)); the excluded forms sit far beyond it
// (quick tier: dAIC > 300 for the time, > 30 for the mass).
constexpr double decisive_delta_aic = 10.0;

TEST(Figures, CollapseTimeIsEpsToMinusThreeHalvesTimesALog) {
    // The data prefer eps^-3/2 (ln 1/eps)^y to a free power and exclude the
    // paper's eps^-3/2 alone and McNamara-Young's [ln(1/2eps)/(2eps)]^3/2.
    EXPECT_EQ(collapse_form("time", "log_corrected", "delta_aic"), 0.0);
    EXPECT_GT(collapse_form("time", "paper", "delta_aic"), decisive_delta_aic);
    EXPECT_GT(collapse_form("time", "mcnamara_young", "delta_aic"), decisive_delta_aic);
    // y agrees with the paper tier within k sigma, the two tiers' (PDG-scaled)
    // errors in quadrature: independent seeds, the same sizes N = 40/eps.
    const double y = collapse_form("time", "log_corrected", "exponent");
    const double sigma = std::hypot(collapse_form("time", "log_corrected", "exponent_sigma_scaled"),
                                    paper_tier_log_exponent_sigma);
    EXPECT_NEAR(y, paper_tier_log_exponent, k_sigma * sigma) << y << " +- " << sigma;
}

TEST(Figures, CollapsingClusterMassIsNearOneOverEpsAndLocal) {
    const double x = collapse_form("mass", "power", "exponent");
    const double sigma =
        std::hypot(collapse_form("mass", "power", "exponent_sigma_scaled"), paper_tier_mass_exponent_sigma);
    EXPECT_NEAR(x, paper_tier_mass_exponent, k_sigma * sigma) << x << " +- " << sigma;
    // McNamara-Young's minimal cluster grows as ln(1/2eps)/(2eps), faster than the masses do.
    EXPECT_GT(collapse_form("mass", "mcnamara_young", "delta_aic"), decisive_delta_aic);
    // A collapse is local: its cluster's mass does not depend on the ring's size N.
    const double slope = attribute("fig_collapse/vs_N.h5", "first_collapse", "cluster_mass_exponent");
    const double slope_sigma = attribute("fig_collapse/vs_N.h5", "first_collapse", "cluster_mass_exponent_sigma");
    EXPECT_NEAR(slope, 0.0, k_sigma * slope_sigma) << slope << " +- " << slope_sigma;
}

TEST(Figures, FirstCollapseIsTheGumbelMinimumOfManyRegions) {
    // Where N/m >= 50 the mean first-collapse time falls as -tau ln N, and the
    // spread is pi tau / sqrt 6 at every N (a minimum over N/m regions whose
    // collapse hazard rises exponentially). Tolerance: k sigma of the two in
    // quadrature, the measured one's times 1.5 because the sigma of a sample
    // standard deviation is computed for Gaussian data and the Gumbel law's
    // excess kurtosis 2.4 makes it 1.5 times larger
    // (tests/unit/test_analysis_collapse.cpp). At quick fidelity this resolves
    // the spread to about 30%: it tells a Gumbel minimum from, say, a spread
    // that shrinks with N, not pi/sqrt 6 from 1.
    const std::string file = "fig_collapse/vs_N.h5";
    const double tau = attribute(file, "first_collapse", "gumbel_tau");
    const double tau_sigma = attribute(file, "first_collapse", "gumbel_tau_sigma");
    EXPECT_GT(tau, k_sigma * tau_sigma) << "the first collapse comes earlier on a larger ring";
    const double predicted = attribute(file, "first_collapse", "gumbel_predicted_spread");
    const double measured = attribute(file, "first_collapse", "gumbel_measured_spread");
    const double sigma = std::hypot(attribute(file, "first_collapse", "gumbel_predicted_spread_sigma"),
                                    1.5 * attribute(file, "first_collapse", "gumbel_measured_spread_sigma"));
    EXPECT_NEAR(measured, predicted, k_sigma * sigma) << measured << " vs " << predicted << " +- " << sigma;
}

}  // namespace
