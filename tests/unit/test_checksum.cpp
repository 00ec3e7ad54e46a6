// SPDX-License-Identifier: GPL-3.0-or-later
// SHA-256 of init files, against the FIPS 180-4 example vectors.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "shockgas/io/checksum.hpp"
#include "shockgas/model/parameters.hpp"

namespace {

// Expected digests: FIPS 180-4 examples (NIST CSRC "SHA256.pdf", "SHA2_Additional").
TEST(Checksum, Sha256MatchesTheNistExamples) {
    EXPECT_EQ(shockgas::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(shockgas::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    // Two blocks: 56 bytes leave no room for the length in the first.
    EXPECT_EQ(shockgas::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    // One million 'a': many blocks through the streaming path.
    EXPECT_EQ(shockgas::sha256_hex(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Checksum, FileDigestEqualsTheDigestOfItsBytes) {
    const auto path = (std::filesystem::path(testing::TempDir()) / "checksum.bin").string();
    const std::string bytes(3 * (1 << 20) + 17, 'x');  // crosses the 1 MiB read chunks
    std::ofstream(path, std::ios::binary) << bytes;
    EXPECT_EQ(shockgas::file_sha256(path), shockgas::sha256_hex(bytes));
    EXPECT_THROW(shockgas::file_sha256(path + ".absent"), shockgas::InputError);
}

}  // namespace
