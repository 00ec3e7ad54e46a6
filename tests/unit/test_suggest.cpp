// SPDX-License-Identifier: GPL-3.0-or-later
// "Did you mean ...?" for misspelt options and config keys.
#include <gtest/gtest.h>

#include "shockgas/cli/suggest.hpp"

namespace {

const std::vector<std::string> options{"particles", "restitution", "threshold", "t-max", "seed", "subthreshold"};

TEST(Suggest, EditDistanceCountsSingleCharacterEdits) {
    EXPECT_EQ(shockgas::edit_distance("kitten", "sitting"), 3u);  // the textbook example
    EXPECT_EQ(shockgas::edit_distance("", "abc"), 3u);
    EXPECT_EQ(shockgas::edit_distance("seed", "seed"), 0u);
    EXPECT_EQ(shockgas::edit_distance("restituion", "restitution"), 1u);
}

TEST(Suggest, NearestOptionForTyposNothingForStrangers) {
    EXPECT_EQ(shockgas::closest_name("restituion", options), "restitution");
    EXPECT_EQ(shockgas::closest_name("threshhold", options), "threshold");
    EXPECT_EQ(shockgas::closest_name("partciles", options), "particles");  // a transposition: 2 edits
    EXPECT_EQ(shockgas::closest_name("t_max", options), "t-max");          // the HDF5 attribute name
    EXPECT_EQ(shockgas::closest_name("colour", options), "");              // no option is near
}

}  // namespace
