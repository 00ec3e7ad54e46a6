// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/cli/signals.hpp"

#include <csignal>

#include <fcntl.h>
#include <unistd.h>

namespace {

std::atomic<bool> stop_requested{false};

// Which of stdout and stderr were terminals when the run began (isatty is not
// safe inside a signal handler).
bool stdout_terminal = false;
bool stderr_terminal = false;

extern "C" void on_interrupt(int) { stop_requested.store(true); }

// open and dup2 are async-signal-safe.
extern "C" void on_hangup(int) {
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
        if (stdout_terminal) dup2(null, STDOUT_FILENO);
        if (stderr_terminal) dup2(null, STDERR_FILENO);
        close(null);
    }
    stop_requested.store(true);
}

}  // namespace

namespace shockgas::cli {

const std::atomic<bool>& stop_flag() { return stop_requested; }

void install_stop_handlers() {
    stdout_terminal = isatty(STDOUT_FILENO) != 0;
    stderr_terminal = isatty(STDERR_FILENO) != 0;
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    std::signal(SIGHUP, on_hangup);
}

}  // namespace shockgas::cli
