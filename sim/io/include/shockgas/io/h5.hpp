// SPDX-License-Identifier: GPL-3.0-or-later
// The one HDF5 layer of shockgas: RAII handles around the HDF5 C API, with
// errors turned into exceptions whose message names the file and the object.
// Every reader and writer in sim/ and analysis/ goes through this header.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <hdf5.h>

namespace shockgas::h5 {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
    // The operating system's reason, when HDF5 failed because a read or write
    // of the file failed ("No space left on device", "File too large"), or
    // "checksum mismatch" when stored data fail their checksum; else empty.
    Error(const std::string& what, std::string reason) : std::runtime_error(what), cause(std::move(reason)) {}
    std::string cause;
};

// Owns one hid_t and closes it with the matching H5*close.
class Handle {
public:
    using Closer = herr_t (*)(hid_t);
    Handle() = default;
    Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = H5I_INVALID_HID; }
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            close();
            id_ = other.id_;
            closer_ = other.closer_;
            other.id_ = H5I_INVALID_HID;
        }
        return *this;
    }
    ~Handle() { close(); }
    hid_t id() const { return id_; }
    // Closes now and reports failure (a destructor cannot): closing a dataset
    // or file is when HDF5 writes what it still holds.
    herr_t close_checked() {
        const herr_t status = id_ >= 0 && closer_ != nullptr ? closer_(id_) : 0;
        id_ = H5I_INVALID_HID;
        return status;
    }
    void forget() { id_ = H5I_INVALID_HID; }  // already closed elsewhere
    bool valid() const { return id_ >= 0; }

private:
    void close() {
        if (id_ >= 0 && closer_ != nullptr) closer_(id_);
        id_ = H5I_INVALID_HID;
    }
    hid_t id_ = H5I_INVALID_HID;
    Closer closer_ = nullptr;
};

// A group (the file's root is a group too). Datasets are written whole, with
// no object timestamps, so equal data give byte-identical datasets. Every
// non-empty dataset is chunked and carries HDF5's Fletcher32 checksum, which
// HDF5 verifies on every read; the file format (HDF5 1.10) checksums the
// metadata too, so damaged bytes anywhere are detected rather than read.
class Group {
public:
    // file: the file's name as a user knows it, added to every error message.
    Group(Handle handle, std::string path, std::string file = "")
        : handle_(std::move(handle)), path_(std::move(path)), file_(std::move(file)) {}

    const std::string& path() const { return path_; }
    hid_t id() const { return handle_.id(); }

    bool has(const std::string& name) const;
    Group create_group(const std::string& name);
    Group open_group(const std::string& name) const;
    std::vector<std::string> children() const;
    // Children named by numbers (0, 1, ... or zero-padded 00, 01, ...), in
    // numeric order: schemas 1-2 wrote 0 .. 10 unpadded, schema 3 pads them.
    std::vector<std::string> numbered_children() const;
    bool is_group(const std::string& name) const;

    // Datasets: dims empty means 1-D of data.size(); otherwise product(dims) == data.size().
    void write(const std::string& name, const std::vector<double>& data, std::vector<hsize_t> dims = {});
    void write(const std::string& name, const std::vector<std::int64_t>& data, std::vector<hsize_t> dims = {});
    std::vector<double> read_doubles(const std::string& name, std::vector<hsize_t>* dims = nullptr) const;
    std::vector<std::int64_t> read_integers(const std::string& name, std::vector<hsize_t>* dims = nullptr) const;

    // Attributes on this group.
    void set_attribute(const std::string& name, double value);
    void set_attribute(const std::string& name, std::int64_t value);
    void set_attribute(const std::string& name, const std::string& value);
    void set_attribute(const std::string& name, const char* value) { set_attribute(name, std::string(value)); }
    void set_attribute(const std::string& name, const std::vector<double>& value);
    bool has_attribute(const std::string& name) const;
    double attribute_double(const std::string& name) const;
    std::int64_t attribute_integer(const std::string& name) const;
    std::string attribute_string(const std::string& name) const;
    std::vector<double> attribute_doubles(const std::string& name) const;
    std::vector<std::string> attribute_names() const;
    // Copies every attribute of other onto this group, under prefix + name.
    void copy_attributes_from(const Group& other, const std::string& prefix = "");

private:
    std::string child_path(const std::string& name) const;
    std::string where(const std::string& name) const;  // child_path + " in 'file'", for messages
    Handle handle_;
    std::string path_;
    std::string file_;
};

class File {
public:
    // Truncates. display: the name errors give (AtomicFile: the target, not its temporary).
    static File create(const std::string& path, const std::string& display = "");
    // Throws Error naming the path if unreadable, truncated or damaged: every
    // dataset is read once to check its checksum before the file is trusted.
    static File open_read(const std::string& path);
    Group root() const;
    const std::string& path() const { return path_; }
    // Closes the file, writing what HDF5 still holds; false if that failed.
    bool close();

private:
    File(Handle handle, std::string path, std::string display)
        : handle_(std::move(handle)), path_(std::move(path)), display_(std::move(display)) {}
    Handle handle_;
    std::string path_;
    std::string display_;
};

// Writes to a temporary file TARGET.tmp.<pid> beside the target and renames
// it into place on commit(), so a killed or failed run never leaves a file
// that looks complete. A write that fails (full disk, file-size limit: the
// constructor makes SIGXFSZ ignored so that such a write fails with EFBIG
// rather than killing the process) throws Error with the cause, and the
// temporary file is removed.
class AtomicFile {
public:
    explicit AtomicFile(std::string target_path);
    ~AtomicFile();  // removes the temporary file if commit() was not reached
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    Group root() const { return file_->root(); }
    // Flushes, closes and syncs the temporary file, then renames it onto the
    // target. With keep_previous_as, an existing target is first renamed to
    // that name (the previous generation of a checkpoint).
    void commit(const std::string& keep_previous_as = "");

private:
    std::string target_;
    std::string temporary_;
    std::unique_ptr<File> file_;
    bool committed_ = false;
};

// The name of group `index` of `count` numbered groups: zero-padded to the
// width of count - 1, so that names sort in numeric order anywhere (h5ls,
// h5py's keys(), a notebook) as well as read back here.
std::string numbered_name(std::size_t index, std::size_t count);

// Writes a whole file through AtomicFile; any failure is rethrown as one
// Error naming the target and the cause, after the temporary file is removed.
template <typename Fill>
void write_atomically(const std::string& target, Fill&& fill, const std::string& keep_previous_as = "");

// Removes TARGET.tmp.<pid> files beside target whose process <pid> is gone
// (left by a killed run); returns their names, for a note.
std::vector<std::string> remove_stale_temporaries(const std::string& target);

// Checks that a file can be created at path (its directory exists and is
// writable) before a long run starts; throws Error naming the path otherwise.
// Also refuses a path that exists and is not a regular file (a device such as
// /dev/null, a FIFO) or is a symbolic link: an output is written beside its
// target and renamed over it, which would replace the device or the link.
void check_writable(const std::string& path);

// Throws Error when output names the same file as one of inputs (compared as
// files, so a different spelling or a hard link counts): writing it would
// destroy an input. Inputs that do not exist are skipped.
void check_not_an_input(const std::string& output, const std::vector<std::string>& inputs);

// What is at a path, found by opening it without reading any data
// (File::open_read reads every dataset to verify it, which is the right cost
// for a file about to be used, not for deciding whether a file may be
// replaced or removed).
struct Probe {
    enum class Kind {
        absent,       // nothing at the path
        not_regular,  // a directory, a device, a FIFO or a symbolic link
        empty,        // a regular file of no bytes: it holds nothing to lose, so it may be replaced
        not_hdf5,     // a regular file with bytes that do not start with the HDF5 signature
        damaged,      // the HDF5 signature, but HDF5 cannot open it or list its root (truncated, damaged)
        hdf5,         // an HDF5 file whose root could be listed
    };
    Kind kind = Kind::absent;
    std::vector<std::string> root_names;  // kind hdf5: the names at the file's root
    bool holds(const std::string& name) const;
};
Probe probe(const std::string& path);

[[noreturn]] void rethrow_write_failure(const std::string& target, const Error& error);

template <typename Fill>
void write_atomically(const std::string& target, Fill&& fill, const std::string& keep_previous_as) {
    try {
        AtomicFile file(target);
        auto root = file.root();
        fill(root);
        file.commit(keep_previous_as);
    } catch (const Error& error) {
        rethrow_write_failure(target, error);
    }
}

}  // namespace shockgas::h5
