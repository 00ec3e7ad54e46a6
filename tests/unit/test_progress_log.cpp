// Progress lines in batch logs (ProgressLog): which of the driver's reports,
// about one a second, become lines. Synthetic reports, no clocks.
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
