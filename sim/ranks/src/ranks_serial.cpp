// SPDX-License-Identifier: GPL-3.0-or-later
// The one-rank implementation of shockgas/ranks/ranks.hpp, compiled when
// SHOCKGAS_MPI is off: every collective step is this process's alone.
#include "shockgas/ranks/ranks.hpp"

namespace shockgas::ranks {

Session::Session(int& /*argc*/, char**& /*argv*/) {}
Session::~Session() = default;
void Session::agree_ready() { phase_ = Phase::running; }
bool Session::any(bool flag) { return flag; }
bool Session::root_says(bool word) { return word; }
std::optional<std::vector<Block>> Session::gather_at_root(Block mine) {
    std::vector<Block> blocks;
    blocks.push_back(std::move(mine));
    return blocks;
}
int Session::cores_available() { return 0; }

}  // namespace shockgas::ranks
