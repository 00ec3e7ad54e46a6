// SPDX-License-Identifier: GPL-3.0-or-later
// One text output (a gnuplot data file, a dump, a profile), written so that a
// failure never leaves a file that looks complete: a new or regular file is
// written as PATH.tmp.<pid> beside it and renamed onto PATH by commit(), and
// removed if commit() is not reached (an error, a full disk). A symbolic link
// to a regular file is treated so at the file it points to (the link stays a
// link). A path that exists and is not a regular file (a device such as
// /dev/null or /dev/full, a FIFO, /dev/stdout or any link through /dev or
// /proc) is written through directly and never renamed over, since that would
// replace the device, or detach a shell's redirection. Such a path is
// appended to, never truncated, and one that is the process's own standard
// output or error (/dev/stdout under `>> log`) is written through that stream;
// an empty path is standard output. Every write, the flush and the close are
// checked; a failure throws InputError "cannot write <kind>'PATH': <reason>".
// The HDF5 outputs have their own atomic writer (h5::AtomicFile).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace shockgas {

class TextFile {
public:
    // kind: how messages name the file, e.g. "data file " gives "cannot write
    // data file 'x.dat': ...". Opening does not check the path beforehand:
    // check_text_writable does, for programs that refuse before any work.
    explicit TextFile(const std::string& path, std::string kind = "");
    ~TextFile();
    TextFile(const TextFile&) = delete;
    TextFile& operator=(const TextFile&) = delete;

    std::FILE* stream() const { return stream_; }
    void write(std::string_view text);
    // Writes out what is buffered (a full disk often shows only here), syncs a
    // temporary file and closes it, keeping it until commit(). Standard output
    // (or error) is flushed and checked, not closed.
    void close();
    // close(), then renames the temporary file onto the target.
    void commit();
    // Closes and removes the temporary file and throws the InputError naming
    // the target and strerror(error) (an I/O error when error is 0).
    [[noreturn]] void fail(int error);

private:
    std::string target_;
    std::string kind_;
    std::string replaced_;   // the regular file commit() replaces (a link's target); empty: written through
    std::string temporary_;  // empty: written in place (standard output, a device)
    std::FILE* stream_ = nullptr;
    bool borrowed_ = false;  // stdout or stderr (the path is that file): flushed, never closed
    bool committed_ = false;
};

// The regular file that a TextFile at path writes beside and renames onto:
// path itself when it is new or a regular file, the end of a chain of symbolic
// links that ends at a regular file without passing through /dev or /proc;
// empty when path is written through (a device, a FIFO, /dev/stdout, a link to
// nothing or such a target).
std::string replaced_file(const std::string& path);

// Whether TextFile writes path through (replaced_file(path) is empty).
bool writes_through(const std::string& path);

// Throws (h5::Error or InputError, naming the path) unless a TextFile can be
// written at path: as h5::check_writable for a regular or new file, and for a
// target written through, that it exists, is no directory and may be written.
void check_text_writable(const std::string& path, const std::string& kind = "");

}  // namespace shockgas
