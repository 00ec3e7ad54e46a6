// How the programs show the driver's progress reports: one line for a
// terminal, and which reports a batch job's log gets.
#pragma once

#include <functional>
#include <string>

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

// How a program (e.g. "shockgas-sim") shows the driver's reports on stderr: on
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
