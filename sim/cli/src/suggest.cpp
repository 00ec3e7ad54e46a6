// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/cli/suggest.hpp"

#include <algorithm>
#include <numeric>

namespace shockgas {

std::size_t edit_distance(const std::string& a, const std::string& b) {
    // One row of the dynamic-programming table at a time.
    std::vector<std::size_t> row(b.size() + 1);
    std::iota(row.begin(), row.end(), std::size_t{0});
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

namespace {
std::string dashes_for_underscores(std::string name) {
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}
}  // namespace

std::string closest_name(const std::string& word, const std::vector<std::string>& known) {
    const std::string target = dashes_for_underscores(word);
    const std::size_t allowed = std::max<std::size_t>(2, word.size() / 3);
    std::string best;
    std::size_t best_distance = allowed + 1;
    for (const auto& name : known) {
        const std::size_t distance = edit_distance(target, dashes_for_underscores(name));
        if (distance < best_distance) {
            best = name;
            best_distance = distance;
        }
    }
    return best;
}

}  // namespace shockgas
