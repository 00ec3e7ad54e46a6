// SPDX-License-Identifier: GPL-3.0-or-later
// Blocks as files' bytes (shockgas/ranks/ranks.hpp), in both builds.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "shockgas/model/parameters.hpp"  // InputError
#include "shockgas/ranks/ranks.hpp"

namespace shockgas::ranks {

namespace fs = std::filesystem;

TemporaryDirectory::TemporaryDirectory() {
    // Under $TMPDIR (or /tmp): node-local, so no shared file system is needed.
    std::string pattern = (fs::temp_directory_path() / "shockgas-rank-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
        throw InputError(fmt::format("cannot create a temporary directory under '{}'", fs::temp_directory_path().string()));
    path_ = pattern;
}

TemporaryDirectory::~TemporaryDirectory() {
    std::error_code ignored;  // best effort: a leftover temporary directory is not worth failing a finished run
    fs::remove_all(path_, ignored);
}

std::string TemporaryDirectory::file(const std::string& name) const { return (fs::path(path_) / name).string(); }

std::vector<char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("cannot read back '{}'", path));
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw InputError(fmt::format("cannot write '{}' (disk full?)", path));
}

}  // namespace shockgas::ranks
