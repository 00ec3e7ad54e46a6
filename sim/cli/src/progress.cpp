// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/cli/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

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
                       p.shown_time, p.realizations_done, p.realizations, 100.0 * p.fraction_done,
                       p.collisions_per_second, p.elapsed_seconds, eta);
}

namespace cli {

namespace {
// A realization's growth exponent a of c(t) ~ t^a is read between the time it
// has reached and the last report at or before this fraction of it: far enough
// back that a second's jitter does not decide it.
constexpr double history_reach = 0.5;
// The exponent is held to this range: the collision count of every setting
// grows no faster than linearly in t once its first collisions are done (an
// elastic gas: constant rate; clustering gases: slower), and a short history
// at the very start can read anything.
constexpr double slowest_growth = 0.2, fastest_growth = 1.0;
}  // namespace

double ProgressEstimator::expected_total(std::size_t k, const RealizationProgress& r, double t_max) const {
    const auto now = static_cast<double>(r.collisions);
    if (r.time <= 0.0 || r.time >= t_max || now <= 0.0) return now;
    double growth = fastest_growth;
    const std::vector<Sample>& seen = history_[k];
    for (auto it = seen.rbegin(); it != seen.rend(); ++it)
        if (it->time <= history_reach * r.time) {
            if (it->time > 0.0 && it->collisions > 0.0)
                growth = std::clamp(std::log(now / it->collisions) / std::log(r.time / it->time), slowest_growth,
                                    fastest_growth);
            break;
        }
    return now * std::pow(t_max / r.time, growth);
}

void ProgressEstimator::update(Progress& p) {
    using State = RealizationProgress::State;
    history_.resize(p.realization.size());
    double finished_total = 0.0, running_done = 0.0, running_extrapolated = 0.0;
    std::int64_t finished = 0, waiting = 0;
    std::vector<std::pair<double, double>> running;  // (collisions so far, extrapolated total) of each running one
    double slowest = p.t_max;
    for (std::size_t k = 0; k < p.realization.size(); ++k) {
        const RealizationProgress& r = p.realization[k];
        const auto collisions = static_cast<double>(r.collisions);
        if (r.state == State::finished) {
            finished_total += collisions;
            ++finished;
        } else if (r.state == State::running) {
            const double total = expected_total(k, r, p.t_max);
            running.emplace_back(collisions, total);
            running_done += collisions;
            running_extrapolated += total;
            slowest = running.size() == 1 ? r.time : std::min(slowest, r.time);
            if (history_[k].empty() || r.time > history_[k].back().time) history_[k].push_back({r.time, collisions});
        } else {
            ++waiting;
        }
    }
    p.shown_time = slowest;
    // What one realization costs: measured once one has finished, else the running ones' extrapolations.
    const double per_realization = finished > 0        ? finished_total / static_cast<double>(finished)
                                   : !running.empty() ? running_extrapolated / static_cast<double>(running.size())
                                                      : 0.0;
    double remaining = static_cast<double>(waiting) * per_realization;
    for (const auto& [done_so_far, extrapolated] : running) {
        const double expected = finished > 0 ? std::max(per_realization, done_so_far) : extrapolated;
        remaining += std::max(0.0, expected - done_so_far);
    }
    const double done = finished_total + running_done;
    const bool all_done = waiting == 0 && running.empty();
    p.fraction_done = done + remaining > 0.0 ? done / (done + remaining) : (all_done ? 1.0 : 0.0);
    p.eta_seconds = p.collisions_per_second > 0.0 && per_realization > 0.0 ? remaining / p.collisions_per_second
                    : all_done                                             ? 0.0
                                                                           : -1.0;
}

ProgressCallback progress_printer(const std::string& program, double log_interval_seconds) {
    auto estimator = std::make_shared<ProgressEstimator>();
    if (isatty(STDERR_FILENO) != 0)
        return [estimator](const Progress& report) {
            Progress status = report;
            estimator->update(status);
            fmt::print(stderr, "\r{:<110}", format_progress(status));
            std::fflush(stderr);
        };
    auto log = std::make_shared<ProgressLog>(log_interval_seconds);
    return [estimator, log, program](const Progress& report) {
        Progress status = report;
        estimator->update(status);
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
