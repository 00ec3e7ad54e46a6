// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/text_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "shockgas/io/h5.hpp"
#include "shockgas/model/parameters.hpp"

namespace shockgas {

namespace {

InputError text_file_error(const std::string& kind, const std::string& path, const std::string& why) {
    return InputError(fmt::format("cannot write {}{}: {}", kind, path.empty() ? "standard output" : "'" + path + "'",
                                  why));
}

// The process's own standard output or error when path is the same file
// (/dev/stdout, /proc/self/fd/1, or the file a shell redirected it to), else
// null. Writing such a path through its own stream keeps the shell's
// redirection whole: opening it anew with "w" truncated a `>> log` to nothing,
// and a second open file description would write at its own offset, over
// what the program prints.
std::FILE* standard_stream_at(const std::string& path) {
    struct stat target {};
    if (::stat(path.c_str(), &target) != 0) return nullptr;
    for (const auto& [descriptor, stream] : {std::pair{STDOUT_FILENO, stdout}, std::pair{STDERR_FILENO, stderr}}) {
        struct stat open_file {};
        if (::fstat(descriptor, &open_file) == 0 && open_file.st_dev == target.st_dev &&
            open_file.st_ino == target.st_ino)
            return stream;
    }
    return nullptr;
}

}  // namespace

std::string replaced_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::path hop = path;
    // A chain of links is followed by hand, so that a link through the kernel's
    // own names (/dev/stdout -> /proc/self/fd/1 -> the file the shell opened)
    // is written through: renaming over that file would detach the shell's
    // redirection (and lose what `>>` kept).
    for (int hops = 0; hops < 40; ++hops) {
        const fs::file_status status = fs::symlink_status(hop, error);
        if (!fs::exists(status)) return hops == 0 ? path : std::string();  // new, or a link to nothing
        if (fs::is_regular_file(status)) return hop.string();
        if (!fs::is_symlink(status)) return {};  // a device, a FIFO, a directory
        const std::string absolute = fs::absolute(hop, error).lexically_normal().string();
        if (absolute.rfind("/dev/", 0) == 0 || absolute.rfind("/proc/", 0) == 0) return {};
        const fs::path link = fs::read_symlink(hop, error);
        if (error) return {};
        hop = link.is_absolute() ? link : hop.parent_path() / link;
    }
    return {};  // a loop of links: written through, where opening reports it
}

bool writes_through(const std::string& path) { return replaced_file(path).empty(); }

void check_text_writable(const std::string& path, const std::string& kind) {
    namespace fs = std::filesystem;
    std::error_code error;
    const std::string replaced = replaced_file(path);
    if (!replaced.empty()) {
        h5::check_writable(replaced);  // a new or regular file, written beside and renamed
        return;
    }
    const fs::file_status target = fs::status(path, error);  // what a link points to
    if (!fs::exists(target)) throw text_file_error(kind, path, "it is a symbolic link to nothing");
    if (fs::is_directory(target)) throw text_file_error(kind, path, "it is a directory");
    if (::access(path.c_str(), W_OK) != 0) throw text_file_error(kind, path, std::strerror(errno));
}

TextFile::TextFile(const std::string& path, std::string kind) : target_(path), kind_(std::move(kind)) {
    if (target_.empty()) {
        stream_ = stdout;
        borrowed_ = true;
        return;
    }
    // Beyond a file-size limit (ulimit -f) the kernel would kill the process
    // with SIGXFSZ; ignored, the write fails with EFBIG and is reported (as
    // h5::AtomicFile does).
    std::signal(SIGXFSZ, SIG_IGN);
    replaced_ = replaced_file(target_);
    if (!replaced_.empty()) {
        temporary_ = replaced_ + ".tmp." + std::to_string(::getpid());
        stream_ = std::fopen(temporary_.c_str(), "w");
    } else if ((stream_ = standard_stream_at(target_)) != nullptr) {
        borrowed_ = true;
    } else {
        // Appended, never truncated: through /dev/fd/N or /proc a regular file
        // may be reached that holds what others wrote (a shell's `3>> log`);
        // a device or FIFO is the same either way.
        stream_ = std::fopen(target_.c_str(), "a");
    }
    if (stream_ == nullptr) fail(errno);
}

TextFile::~TextFile() {
    if (stream_ != nullptr && !borrowed_) std::fclose(stream_);
    if (!committed_ && !temporary_.empty()) std::remove(temporary_.c_str());
}

void TextFile::fail(int error) {
    // The message names the file the user asked for; the temporary one goes.
    if (stream_ != nullptr && !borrowed_) std::fclose(stream_);
    stream_ = nullptr;
    if (!temporary_.empty()) std::remove(temporary_.c_str());
    // stdio need not set errno on a short write; an unknown cause is an I/O error.
    throw text_file_error(kind_, target_, std::strerror(error != 0 ? error : EIO));
}

void TextFile::write(std::string_view text) {
    if (stream_ == nullptr) throw std::logic_error("TextFile: write after close: " + target_);
    errno = 0;
    if (std::fwrite(text.data(), 1, text.size(), stream_) != text.size()) fail(errno);
}

void TextFile::close() {
    if (stream_ == nullptr) return;
    errno = 0;
    if (std::fflush(stream_) != 0 || std::ferror(stream_) != 0) fail(errno);
    // A regular file's bytes reach the disk before it is renamed into place;
    // devices and FIFOs have nothing to sync (fsync fails on them).
    if (!temporary_.empty() && ::fsync(::fileno(stream_)) != 0) fail(errno);
    if (borrowed_) return;
    std::FILE* stream = stream_;
    stream_ = nullptr;
    errno = 0;
    if (std::fclose(stream) != 0) fail(errno);
}

void TextFile::commit() {
    if (committed_) return;
    close();
    if (!temporary_.empty() && std::rename(temporary_.c_str(), replaced_.c_str()) != 0) fail(errno);
    committed_ = true;
}

}  // namespace shockgas
