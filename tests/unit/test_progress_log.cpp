// SPDX-License-Identifier: GPL-3.0-or-later
// Progress lines in batch logs (ProgressLog): which of the driver's reports,
// about one a second, become lines. Synthetic reports, no clocks.
#include <cstdint>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "shockgas/cli/progress.hpp"

namespace {

// A run of `seconds` seconds of wall time whose work grows linearly, reported
// once a second and once more at the end; returns the seconds printed.
std::vector<int> printed_seconds(double interval, int seconds) {
    shockgas::ProgressLog log(interval);
    std::vector<int> printed;
    for (int second = 1; second <= seconds; ++second) {
        shockgas::Progress report;
        report.elapsed_seconds = second;
        report.fraction_done = static_cast<double>(second) / seconds;
        if (log.due(report)) printed.push_back(second);
    }
    shockgas::Progress end;  // the driver's last report, after the workers finish
    end.elapsed_seconds = seconds;
    end.fraction_done = 1.0;
    if (log.due(end)) printed.push_back(-1);
    return printed;
}

TEST(ProgressLog, EveryIntervalAndEveryTenthOnceAtTheEnd) {
    // 1000 s: tenths at 100, 200, ... 1000 s; 300-s interval lines at 300 s
    // after the previous line (the 300-s mark is also a tenth).
    EXPECT_EQ(printed_seconds(300.0, 1000), (std::vector<int>{100, 200, 300, 400, 500, 600, 700, 800, 900, 1000}));
    // 10 000 s with a 600-s interval: a line every 600 s between the tenths.
    const auto long_run = printed_seconds(600.0, 10000);
    EXPECT_EQ(long_run.front(), 600);
    EXPECT_EQ(long_run[1], 1000);  // the first tenth
    EXPECT_EQ(long_run[2], 1600);  // 600 s after it
    EXPECT_EQ(long_run.back(), 10000);  // the end, printed once (not again by the final report)
    EXPECT_EQ(long_run.size(), 20u);  // 10 tenths, and one interval line 600 s into each of them
}

TEST(ProgressLog, ZeroIntervalPrintsTenthsOnly) {
    EXPECT_EQ(printed_seconds(0.0, 20), (std::vector<int>{2, 4, 6, 8, 10, 12, 14, 16, 18, 20}));
}

TEST(ProgressLog, ShortRunStillLeavesItsEndInTheLog) {
    // A run that ends before the first report: only the final report, printed.
    EXPECT_EQ(printed_seconds(60.0, 0), (std::vector<int>{-1}));
}

}  // namespace

// --- The estimate of what remains (cli::ProgressEstimator) ---

namespace {

using State = shockgas::RealizationProgress::State;

// A report of an ensemble of `states.size()` realizations to t_max = 1000 in
// which every realization's collisions grow linearly in t (an elastic gas:
// collisions at a constant rate), 1000 per unit time, run two at a time.
shockgas::Progress linear_report(double elapsed, const std::vector<std::pair<State, double>>& states) {
    shockgas::Progress p;
    p.t_max = 1000.0;
    p.elapsed_seconds = elapsed;
    p.realizations = static_cast<std::int64_t>(states.size());
    for (const auto& [state, time] : states) {
        shockgas::RealizationProgress r;
        r.state = state;
        r.time = time;
        r.collisions = static_cast<std::uint64_t>(1000.0 * time);
        p.collisions_this_process += r.collisions;
        p.realizations_done += state == State::finished ? 1 : 0;
        p.realization.push_back(r);
    }
    p.collisions_per_second = static_cast<double>(p.collisions_this_process) / elapsed;
    return p;
}

// The estimate must be within this share of the true remaining time on these
// synthetic runs, whose work is known exactly; the rule it replaced, which took
// the work done as (t / t_max)^(2/3) whatever the gas, was 2.3x short early on
// (ETA 16.6 s where 38 s remained, as a first user saw: "elapsed 2 s, ETA 8 s"
// on a 19-s run).
constexpr double eta_tolerance = 0.10;

TEST(ProgressEstimator, EarlyEtaFollowsTheRunsOwnGrowth) {
    shockgas::cli::ProgressEstimator estimator;
    // Two of four realizations running, reports at 1 s (t = 50) and 2 s (t = 100).
    auto first = linear_report(1.0, {{State::running, 50}, {State::running, 50}, {State::waiting, 0}, {State::waiting, 0}});
    estimator.update(first);
    auto second =
        linear_report(2.0, {{State::running, 100}, {State::running, 100}, {State::waiting, 0}, {State::waiting, 0}});
    estimator.update(second);
    // 4e6 collisions in all, 2e5 done, at 1e5 per second: 38 s remain.
    const double truth = (4e6 - 2e5) / 1e5;
    EXPECT_NEAR(second.eta_seconds, truth, eta_tolerance * truth);
    EXPECT_NEAR(second.fraction_done, 2e5 / 4e6, eta_tolerance * 2e5 / 4e6);
}

TEST(ProgressEstimator, ShowsTheSlowestRunningRealizationsTime) {
    shockgas::cli::ProgressEstimator estimator;
    auto p = linear_report(10.0, {{State::finished, 1000}, {State::running, 300}, {State::running, 500}});
    estimator.update(p);
    EXPECT_EQ(p.shown_time, 300.0);  // not t_max, which the finished one reached
    auto done = linear_report(20.0, {{State::finished, 1000}, {State::finished, 1000}, {State::finished, 1000}});
    estimator.update(done);
    EXPECT_EQ(done.shown_time, 1000.0);
    EXPECT_EQ(done.fraction_done, 1.0);
    EXPECT_EQ(done.eta_seconds, 0.0);
}

TEST(ProgressEstimator, AFinishedRealizationSetsWhatEachCosts) {
    shockgas::cli::ProgressEstimator estimator;
    // One finished (1e6 collisions), one at t = 400 (4e5), one waiting: 1.6e6 remain.
    auto p = linear_report(14.0, {{State::finished, 1000}, {State::running, 400}, {State::waiting, 0}});
    estimator.update(p);
    const double truth = 1.6e6 / p.collisions_per_second;
    EXPECT_NEAR(p.eta_seconds, truth, eta_tolerance * truth);
}

TEST(ProgressEstimator, AStoppedRunIsNotReportedDone) {
    shockgas::cli::ProgressEstimator estimator;
    // A realization stopped by a signal is reported waiting (not finished): no "100% ETA 0 s".
    auto p = linear_report(5.0, {{State::waiting, 300}});
    estimator.update(p);
    EXPECT_LT(p.fraction_done, 1.0);
}

}  // namespace
