// SPDX-License-Identifier: GPL-3.0-or-later
// Counts on the command line in scientific notation (cli::whole_number_digits):
// exact whole numbers become their digits, computed from the text; fractions
// are refused by name; anything else is left to the option's own checks.
#include <string>

#include <gtest/gtest.h>

#include "shockgas/cli/cli.hpp"

namespace {

std::string digits(const std::string& text, std::string* error = nullptr) {
    std::string message;
    const std::string out = shockgas::cli::whole_number_digits(text, message);
    if (error != nullptr) *error = message;
    return out;
}

TEST(WholeNumbers, ScientificNotationGivesTheExactDigits) {
    EXPECT_EQ(digits("1e5"), "100000");
    EXPECT_EQ(digits("2e0"), "2");
    EXPECT_EQ(digits("1.2e3"), "1200");
    EXPECT_EQ(digits("8E+1"), "80");
    EXPECT_EQ(digits("4.0"), "4");
    EXPECT_EQ(digits("2500e-2"), "25");
    EXPECT_EQ(digits("-3e2"), "-300");
    // Beyond double precision: 2^63 - 1 written with an exponent stays exact.
    EXPECT_EQ(digits("922337203685477580.7e1"), "9223372036854775807");
}

TEST(WholeNumbers, PlainIntegersAndNonNumbersPassUnchanged) {
    std::string error;
    for (const char* text : {"100000", "-5", "007", "abc", "12abc", "1e", "e5", ""}) {
        EXPECT_EQ(digits(text, &error), text) << text;
        EXPECT_EQ(error, "") << text;
    }
}

TEST(WholeNumbers, FractionsAreRefusedByName) {
    std::string error;
    digits("1.5e0", &error);
    EXPECT_EQ(error, "must be a whole number, not '1.5e0'");
    digits("2.25e1", &error);
    EXPECT_EQ(error, "must be a whole number, not '2.25e1'");
    digits("1e40", &error);
    EXPECT_EQ(error, "must be a whole number in range, not '1e40'");
}

}  // namespace
