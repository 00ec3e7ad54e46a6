// SPDX-License-Identifier: GPL-3.0-or-later
// make_validity_map OUT.h5: writes the hand-made validity map of the unit tests
// (tests/validity_map_fixture.hpp) as a results file's /validity_map, through
// write_validity_map, for the cli tests of shockgas-plan and of shockgas-sim's
// warning (tests/cli/validity_tests.cmake).
#include <cstdio>

#include "../validity_map_fixture.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_validity_map OUT.h5\n");
        return 2;
    }
    shockgas::testing::write_map_file(argv[1], shockgas::testing::fixture_map());
    return 0;
}
