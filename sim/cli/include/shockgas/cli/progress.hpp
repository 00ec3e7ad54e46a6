// SPDX-License-Identifier: GPL-3.0-or-later
// How the programs show the driver's progress reports: one line for a
// terminal, and which reports a batch job's log gets.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "shockgas/run/progress.hpp"

namespace shockgas {

// One line of progress for a terminal: time, rate, ETA.
std::string format_progress(const Progress& progress);

// When a log (stderr not a terminal: a batch job's log file) gets a progress
// line: every interval_seconds of wall time, at each tenth of the work done,
// and once at the end, so a log shows a live job without filling up. The
// driver reports about once a second; due() picks the reports to print.
class ProgressLog {
public:
    explicit ProgressLog(double interval_seconds) : interval_seconds_(interval_seconds) {}
    bool due(const Progress& progress);

private:
    double interval_seconds_;
    double last_line_seconds_ = 0.0;
    int last_tenth_ = 0;
};

namespace cli {

// Estimates a run's progress from the driver's facts (Progress::realization):
// fills fraction_done, shown_time and eta_seconds. The work is counted in
// collisions, whose cost is what the engines' speed is: what remains is each
// running realization's expected total less what it has done, and a full
// realization for each waiting one, at the rate collisions are being computed
// now. A realization's expected total is the mean total of those finished;
// before any has finished, each running one's collisions are extrapolated to
// t_max along its own c(t) ~ t^a, with a measured between the time it has
// reached and half of it (a = 1, collisions at a constant rate, until it has
// history). Stateful: keep one estimator for a run and give it every report.
class ProgressEstimator {
public:
    void update(Progress& progress);

private:
    struct Sample {
        double time = 0.0;
        double collisions = 0.0;
    };
    std::vector<std::vector<Sample>> history_;  // per realization, times increasing
    double expected_total(std::size_t k, const RealizationProgress& r, double t_max) const;
};

// How a program (e.g. "shockgas-sim") shows the driver's reports on stderr,
// estimated by a ProgressEstimator of its own: on
// a terminal one line, rewritten in place; in a log (stderr not a terminal: a
// batch job's file) "<program>: progress: ..." lines when ProgressLog says one
// is due (every log_interval_seconds, at each tenth done, and at the end).
ProgressCallback progress_printer(const std::string& program, double log_interval_seconds);

// A one-line note on stderr, "<program>: <text>", or "<program>[rank k]: <text>"
// in a job of several ranks; on a terminal it overwrites the progress line
// instead of following it.
std::function<void(const std::string&)> rank_note(const std::string& program, int rank, int ranks, bool terminal);

// Progress of work that reports only the share of its steps done and the wall
// seconds since it began (shockgas-tail's chains): "<program>: progress: 12.5%
// of the steps  elapsed 40 s  ETA 280 s", the ETA "--" before any step is done.
std::string format_steps_progress(const std::string& program, double fraction_done, double elapsed_seconds);

// Shows such reports on stderr as progress_printer shows the driver's: on a
// terminal one line, rewritten in place; in a log a line when ProgressLog says
// one is due.
std::function<void(double fraction_done, double elapsed_seconds)> steps_progress_printer(const std::string& program,
                                                                                         double log_interval_seconds);

}  // namespace cli

}  // namespace shockgas
