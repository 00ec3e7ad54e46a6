// SPDX-License-Identifier: GPL-3.0-or-later
// SHA-256 of a file (FIPS 180-4, computed by OpenSSL), so an output can prove which --init file
// made it: the path alone does not (files are edited, moved, regenerated).
#pragma once

#include <string>

namespace shockgas {

// Lower-case hex digest of the bytes; sha256_hex("abc") = "ba7816bf...".
std::string sha256_hex(const std::string& bytes);
// The digest of a whole file; throws InputError naming the file if unreadable.
std::string file_sha256(const std::string& path);

}  // namespace shockgas
