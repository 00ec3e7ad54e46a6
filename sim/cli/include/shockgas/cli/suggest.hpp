// SPDX-License-Identifier: GPL-3.0-or-later
// "Did you mean ...?": the nearest known name to a misspelt one, for the
// command-line and config-file messages of every shockgas program.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace shockgas {

// Levenshtein distance: the fewest single-character insertions, deletions and
// substitutions that turn a into b.
std::size_t edit_distance(const std::string& a, const std::string& b);

// The name in `known` nearest to `word`, if it is near enough to be a typo:
// at most max(2, |word| / 3) edits away (a transposition is two edits); ""
// otherwise. '-' and '_' count as the same letter, so an HDF5 attribute name
// (t_max) finds its option (t-max). Ties go to the first in `known`.
std::string closest_name(const std::string& word, const std::vector<std::string>& known);

}  // namespace shockgas
