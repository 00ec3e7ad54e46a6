// SPDX-License-Identifier: GPL-3.0-or-later
// How the simulation programs stop on a signal: SIGINT and SIGTERM raise a
// flag the driver reads, so the run writes what it has computed and a
// checkpoint that --resume continues; SIGHUP (a closed terminal, a dropped ssh
// session) does the same after sending the terminal streams to /dev/null, since
// a hung-up terminal fails every later write (EIO), which would end the run with
// an error before its checkpoint.
#pragma once

#include <atomic>

namespace shockgas::cli {

// The flag the handlers raise.
const std::atomic<bool>& stop_flag();
// Installs the handlers; call once the run is known to start.
void install_stop_handlers();

}  // namespace shockgas::cli
