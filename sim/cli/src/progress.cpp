#include "shockgas/cli/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <unistd.h>

#include <fmt/format.h>

namespace shockgas {

bool ProgressLog::due(const Progress& p) {
    const int tenth = static_cast<int>(std::floor(10.0 * p.fraction_done));
    const bool time_for_a_line = interval_seconds_ > 0.0 && p.elapsed_seconds - last_line_seconds_ >= interval_seconds_;
    if (!time_for_a_line && tenth <= last_tenth_) return false;
    last_line_seconds_ = p.elapsed_seconds;
    last_tenth_ = std::max(last_tenth_, tenth);
    return true;
}

std::string format_progress(const Progress& p) {
    const std::string eta = p.eta_seconds < 0 ? "--" : fmt::format("{:.0f} s", p.eta_seconds);
    return fmt::format("t = {:.4g}  realizations {}/{}  {:.1f}%  {:.3g} collisions/s  elapsed {:.0f} s  ETA {}",
                       p.latest_time, p.realizations_done, p.realizations, 100.0 * p.fraction_done,
                       p.collisions_per_second, p.elapsed_seconds, eta);
}

namespace cli {

ProgressCallback progress_printer(const std::string& program, double log_interval_seconds) {
    if (isatty(STDERR_FILENO) != 0)
        return [](const Progress& status) {
            fmt::print(stderr, "\r{:<110}", format_progress(status));
            std::fflush(stderr);
        };
    auto log = std::make_shared<ProgressLog>(log_interval_seconds);
    return [log, program](const Progress& status) {
        if (!log->due(status)) return;
        fmt::print(stderr, "{}: progress: {}\n", program, format_progress(status));
        std::fflush(stderr);
    };
}

std::function<void(const std::string&)> rank_note(const std::string& program, int rank, int ranks, bool terminal) {
    return [program, rank, ranks, terminal](const std::string& text) {
        const std::string line =
            ranks > 1 ? fmt::format("{}[rank {}]: {}", program, rank, text) : fmt::format("{}: {}", program, text);
        if (terminal)
            fmt::print(stderr, "\r{:<110}\n", line);
        else
            fmt::print(stderr, "{}\n", line);
    };
}

std::string format_steps_progress(const std::string& program, double fraction_done, double elapsed_seconds) {
    const std::string eta =
        fraction_done > 0.0 ? fmt::format("{:.0f} s", elapsed_seconds * (1.0 - fraction_done) / fraction_done) : "--";
    return fmt::format("{}: progress: {:.1f}% of the steps  elapsed {:.0f} s  ETA {}", program, 100.0 * fraction_done,
                       elapsed_seconds, eta);
}

std::function<void(double, double)> steps_progress_printer(const std::string& program, double log_interval_seconds) {
    const bool terminal = isatty(STDERR_FILENO) != 0;
    auto log = std::make_shared<ProgressLog>(log_interval_seconds);
    return [terminal, log, program](double done, double elapsed) {
        Progress status;
        status.fraction_done = done;
        status.elapsed_seconds = elapsed;
        if (!terminal && !log->due(status)) return;
        const std::string line = format_steps_progress(program, done, elapsed);
        if (terminal)
            fmt::print(stderr, "\r{:<80}", line);
        else
            fmt::print(stderr, "{}\n", line);
        std::fflush(stderr);
    };
}

}  // namespace cli

}  // namespace shockgas
