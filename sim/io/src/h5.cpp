// SPDX-License-Identifier: GPL-3.0-or-later
#include "shockgas/io/h5.hpp"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <algorithm>
#include <numeric>
#include <regex>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <fmt/format.h>

namespace shockgas::h5 {

namespace {

// HDF5 prints its own error stack by default; we report through exceptions.
// H5dont_atexit: a file whose close failed (disk full while HDF5 wrote its
// metadata) stays half-closed, and HDF5 1.10's own clean-up at exit crashes
// on it (SIGSEGV in H5F__close_cb); every file is closed by its handle
// anyway, so that clean-up is not needed.
struct SilenceHdf5Errors {
    SilenceHdf5Errors() {
        H5dont_atexit();
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    }
};
const SilenceHdf5Errors silence_hdf5_errors;

// Why the last HDF5 call failed, from HDF5's error stack: the system's
// message when a read or write of the file failed (HDF5's file driver records
// "errno = 28, error message = 'No space left on device'"), "checksum
// mismatch" when data or metadata fail their checksum, "truncated file" when
// the file ends before its recorded end; empty otherwise.
std::string failure_cause() {
    struct Found {
        std::string system, checksum, truncated;
    } found;
    H5Ewalk2(
        H5E_DEFAULT, H5E_WALK_DOWNWARD,
        [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
            auto& f = *static_cast<Found*>(data);
            const std::string text = error->desc ? error->desc : "";
            static const std::regex errno_pattern(R"(errno = (\d+))");
            std::smatch match;
            if (f.system.empty() && std::regex_search(text, match, errno_pattern))
                f.system = std::strerror(std::stoi(match[1].str()));
            if (text.find("checksum") != std::string::npos)
                f.checksum = "checksum mismatch";
            if (text.find("truncated file") != std::string::npos) f.truncated = "truncated file";
            return 0;
        },
        &found);
    if (!found.system.empty()) return found.system;
    if (!found.checksum.empty()) return found.checksum;
    return found.truncated;
}

[[noreturn]] void fail(const std::string& what) {
    const std::string cause = failure_cause();
    if (cause.empty()) throw Error(what);
    throw Error(what + ": " + cause, cause);
}

hid_t check(hid_t id, const std::string& what) {
    if (id < 0) fail(what);
    return id;
}

void check_status(herr_t status, const std::string& what) {
    if (status < 0) fail(what);
}

// Refuses, before allocating, a dataset that declares more values than its
// file could hold (a fuzzed file of 2 kB declared 1.7e11 bytes):
// data cannot be larger than the file unless compressed, and 1000x leaves
// room for compressed files written by other tools.
void check_declared_size(hid_t dataset, const std::string& where, const std::vector<hsize_t>& dims,
                         std::size_t element_size) {
    hsize_t file_size = 0;
    {
        const Handle file(H5Iget_file_id(dataset), H5Fclose);
        if (file.valid()) H5Fget_filesize(file.id(), &file_size);
    }
    const hsize_t count = std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
    const hsize_t capacity = (1000 * file_size + (hsize_t{1} << 20)) / std::max<std::size_t>(element_size, 1);
    for (const hsize_t d : dims)
        if (d > capacity || count > capacity)
            throw Error(fmt::format("dataset {} declares {} values, more than a {}-byte file can hold", where, count,
                                    file_size));
}

// No access or modification times in object headers: identical data give
// identical bytes, which is what makes runs comparable bit for bit.
Handle untimed_dataset_properties() {
    Handle plist(check(H5Pcreate(H5P_DATASET_CREATE), "cannot create HDF5 property list"), H5Pclose);
    H5Pset_obj_track_times(plist.id(), false);
    return plist;
}

Handle untimed_group_properties() {
    Handle plist(check(H5Pcreate(H5P_GROUP_CREATE), "cannot create HDF5 property list"), H5Pclose);
    H5Pset_obj_track_times(plist.id(), false);
    return plist;
}

// Elements per chunk, at most: 8 MiB of doubles, well below HDF5's 4 GiB
// chunk limit, and few chunks for the datasets of a large run.
constexpr hsize_t max_chunk_elements = hsize_t{1} << 20;

// Chunked (whole trailing rows, as many leading rows as fit) with the
// Fletcher32 checksum, which HDF5 checks whenever the chunk is read.
Handle checksummed_dataset_properties(const std::vector<hsize_t>& dims) {
    Handle plist = untimed_dataset_properties();
    std::vector<hsize_t> chunk = dims;
    const hsize_t row = std::accumulate(dims.begin() + 1, dims.end(), hsize_t{1}, std::multiplies<>());
    chunk[0] = std::clamp<hsize_t>(max_chunk_elements / std::max<hsize_t>(row, 1), 1, dims[0]);
    check_status(H5Pset_chunk(plist.id(), static_cast<int>(chunk.size()), chunk.data()), "cannot set chunks");
    check_status(H5Pset_fletcher32(plist.id()), "cannot set the Fletcher32 checksum");
    return plist;
}

// No chunk cache while writing: each H5Dwrite then writes its chunks at once
// and reports a failed write itself, rather than at a close whose failure
// would be easy to lose.
Handle uncached_dataset_access() {
    Handle plist(check(H5Pcreate(H5P_DATASET_ACCESS), "cannot create HDF5 property list"), H5Pclose);
    check_status(H5Pset_chunk_cache(plist.id(), 0, 0, 1.0), "cannot set the chunk cache");
    return plist;
}

template <typename T>
void write_dataset(hid_t group, const std::string& where, const std::string& name, const std::vector<T>& data,
                   std::vector<hsize_t> dims, hid_t file_type, hid_t memory_type) {
    if (dims.empty()) dims = {static_cast<hsize_t>(data.size())};
    const hsize_t count = std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
    if (count != data.size())
        throw Error(fmt::format("{}: {} values do not fill the requested shape", where, data.size()));
    Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                       "cannot create dataspace for " + where),
                 H5Sclose);
    // An empty dataset has no data to checksum (and cannot be chunked).
    const Handle plist = count > 0 ? checksummed_dataset_properties(dims) : untimed_dataset_properties();
    const Handle access = uncached_dataset_access();
    Handle dataset(check(H5Dcreate2(group, name.c_str(), file_type, space.id(), H5P_DEFAULT, plist.id(), access.id()),
                         "cannot create dataset " + where),
                   H5Dclose);
    if (count > 0)
        check_status(H5Dwrite(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                     "cannot write dataset " + where);
    check_status(dataset.close_checked(), "cannot write dataset " + where);
}

template <typename T>
std::vector<T> read_dataset(hid_t group, const std::string& where, const std::string& name,
                            std::vector<hsize_t>* dims_out, hid_t memory_type) {
    if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) throw Error(fmt::format("missing dataset {}", where));
    Handle dataset(check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "cannot open dataset " + where), H5Dclose);
    // Only plain numbers are converted: a hostile file can declare an element
    // type of gigabytes (fuzzed files do), for which HDF5 itself would
    // allocate a conversion buffer of that size.
    {
        const Handle type(check(H5Dget_type(dataset.id()), "cannot read type of " + where), H5Tclose);
        const H5T_class_t kind = H5Tget_class(type.id());
        if ((kind != H5T_FLOAT && kind != H5T_INTEGER) || H5Tget_size(type.id()) > 16)
            throw Error(fmt::format("dataset {} is not stored as plain numbers", where));
    }
    Handle space(check(H5Dget_space(dataset.id()), "cannot read shape of " + where), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.id());
    std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
    H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
    const hsize_t count = std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
    check_declared_size(dataset.id(), where, dims, sizeof(T));
    std::vector<T> data(count);
    if (count > 0)
        check_status(H5Dread(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                     fmt::format("cannot read dataset {} as {}", where, sizeof(T) == 8 ? "numbers" : "values"));
    if (dims_out) *dims_out = dims;
    return data;
}

Handle open_attribute(hid_t object, const std::string& where, const std::string& name) {
    if (H5Aexists(object, name.c_str()) <= 0) throw Error(fmt::format("missing attribute {}", where));
    return Handle(check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "cannot open attribute " + where), H5Aclose);
}

// Opens an attribute that must hold exactly one value (H5Aread writes every
// element, so reading an array into one scalar would overrun it).
Handle open_scalar_attribute(hid_t object, const std::string& where, const std::string& name) {
    Handle attribute = open_attribute(object, where, name);
    Handle space(check(H5Aget_space(attribute.id()), "cannot read shape of " + where), H5Sclose);
    if (H5Sget_simple_extent_npoints(space.id()) != 1) throw Error("attribute " + where + " is not a single value");
    return attribute;
}

void replace_attribute(hid_t object, const std::string& name) {
    if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
}

template <typename T>
void write_numeric_attribute(hid_t object, const std::string& where, const std::string& name, const T* values,
                             hsize_t count, hid_t file_type, hid_t memory_type, bool scalar) {
    replace_attribute(object, name);
    Handle space(check(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr),
                       "cannot create attribute space " + where),
                 H5Sclose);
    Handle attribute(check(H5Acreate2(object, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                           "cannot create attribute " + where),
                     H5Aclose);
    check_status(H5Awrite(attribute.id(), memory_type, values), "cannot write attribute " + where);
}

}  // namespace

std::string Group::child_path(const std::string& name) const {
    return path_ + (path_.empty() || path_.back() == '/' ? "" : "/") + name;
}

std::string Group::where(const std::string& name) const {
    return file_.empty() ? child_path(name) : fmt::format("{} in '{}'", child_path(name), file_);
}

bool Group::has(const std::string& name) const { return H5Lexists(id(), name.c_str(), H5P_DEFAULT) > 0; }

Group Group::create_group(const std::string& name) {
    const Handle plist = untimed_group_properties();
    return Group(Handle(check(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, plist.id(), H5P_DEFAULT),
                              "cannot create group " + where(name)),
                        H5Gclose),
                 child_path(name), file_);
}

Group Group::open_group(const std::string& name) const {
    if (!has(name)) throw Error(fmt::format("missing group {}", where(name)));
    return Group(Handle(check(H5Gopen2(id(), name.c_str(), H5P_DEFAULT), "cannot open group " + where(name)),
                        H5Gclose),
                 child_path(name), file_);
}

std::vector<std::string> Group::numbered_children() const {
    std::vector<std::pair<unsigned long long, std::string>> numbered;
    for (const auto& name : children()) {
        // At most 19 digits: std::stoull would throw out_of_range on more.
        if (name.empty() || name.size() > 19 || name.find_first_not_of("0123456789") != std::string::npos)
            throw Error(fmt::format("group {} holds '{}' where numbered groups were expected", where(""), name));
        numbered.emplace_back(std::stoull(name), name);
    }
    std::sort(numbered.begin(), numbered.end());
    std::vector<std::string> names;
    for (auto& entry : numbered) names.push_back(std::move(entry.second));
    return names;
}

std::string numbered_name(std::size_t index, std::size_t count) {
    const std::size_t width = count > 1 ? std::to_string(count - 1).size() : 1;
    return fmt::format("{:0{}}", index, width);
}

bool Group::is_group(const std::string& name) const {
    if (!has(name)) return false;
    const Handle object(H5Oopen(id(), name.c_str(), H5P_DEFAULT), H5Oclose);
    return object.valid() && H5Iget_type(object.id()) == H5I_GROUP;
}

std::vector<std::string> Group::children() const {
    std::vector<std::string> names;
    H5Literate(
        id(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
            static_cast<std::vector<std::string>*>(out)->emplace_back(name);
            return 0;
        },
        &names);
    return names;
}

void Group::write(const std::string& name, const std::vector<double>& data, std::vector<hsize_t> dims) {
    write_dataset(id(), where(name), name, data, std::move(dims), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}

void Group::write(const std::string& name, const std::vector<std::int64_t>& data, std::vector<hsize_t> dims) {
    write_dataset(id(), where(name), name, data, std::move(dims), H5T_STD_I64LE, H5T_NATIVE_INT64);
}

std::vector<double> Group::read_doubles(const std::string& name, std::vector<hsize_t>* dims) const {
    return read_dataset<double>(id(), where(name), name, dims, H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> Group::read_integers(const std::string& name, std::vector<hsize_t>* dims) const {
    return read_dataset<std::int64_t>(id(), where(name), name, dims, H5T_NATIVE_INT64);
}

void Group::set_attribute(const std::string& name, double value) {
    write_numeric_attribute(id(), where(name), name, &value, 1, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, true);
}

void Group::set_attribute(const std::string& name, std::int64_t value) {
    write_numeric_attribute(id(), where(name), name, &value, 1, H5T_STD_I64LE, H5T_NATIVE_INT64, true);
}

void Group::set_attribute(const std::string& name, const std::vector<double>& value) {
    write_numeric_attribute(id(), where(name), name, value.data(), static_cast<hsize_t>(value.size()),
                            H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, false);
}

void Group::set_attribute(const std::string& name, const std::string& value) {
    replace_attribute(id(), name);
    // Variable-length UTF-8 (schema 3): h5py and netCDF readers give str, not
    // bytes; schema 1-2 fixed-length strings are still read (attribute_string).
    Handle type(check(H5Tcopy(H5T_C_S1), "cannot create string type"), H5Tclose);
    H5Tset_size(type.id(), H5T_VARIABLE);
    H5Tset_cset(type.id(), H5T_CSET_UTF8);
    Handle space(check(H5Screate(H5S_SCALAR), "cannot create attribute space"), H5Sclose);
    Handle attribute(check(H5Acreate2(id(), name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
                           "cannot create attribute " + where(name)),
                     H5Aclose);
    const char* text = value.c_str();
    check_status(H5Awrite(attribute.id(), type.id(), &text), "cannot write attribute " + where(name));
}

bool Group::has_attribute(const std::string& name) const { return H5Aexists(id(), name.c_str()) > 0; }

double Group::attribute_double(const std::string& name) const {
    const Handle attribute = open_scalar_attribute(id(), where(name), name);
    double value = 0.0;
    check_status(H5Aread(attribute.id(), H5T_NATIVE_DOUBLE, &value), "attribute " + where(name) + " is not a number");
    return value;
}

std::int64_t Group::attribute_integer(const std::string& name) const {
    const Handle attribute = open_scalar_attribute(id(), where(name), name);
    std::int64_t value = 0;
    check_status(H5Aread(attribute.id(), H5T_NATIVE_INT64, &value), "attribute " + where(name) + " is not an integer");
    return value;
}

std::vector<double> Group::attribute_doubles(const std::string& name) const {
    const Handle attribute = open_attribute(id(), where(name), name);
    Handle space(check(H5Aget_space(attribute.id()), "cannot read shape of " + where(name)), H5Sclose);
    const hssize_t count = H5Sget_simple_extent_npoints(space.id());
    std::vector<double> values(static_cast<std::size_t>(std::max<hssize_t>(count, 0)));
    if (!values.empty())
        check_status(H5Aread(attribute.id(), H5T_NATIVE_DOUBLE, values.data()),
                     "attribute " + where(name) + " is not numeric");
    return values;
}

std::string Group::attribute_string(const std::string& name) const {
    const Handle attribute = open_attribute(id(), where(name), name);
    Handle type(check(H5Aget_type(attribute.id()), "cannot read type of " + where(name)), H5Tclose);
    if (H5Tget_class(type.id()) != H5T_STRING) throw Error("attribute " + where(name) + " is not a string");
    if (H5Tis_variable_str(type.id()) > 0) {
        Handle memory_type(check(H5Tcopy(H5T_C_S1), "cannot create string type"), H5Tclose);
        H5Tset_size(memory_type.id(), H5T_VARIABLE);
        H5Tset_cset(memory_type.id(), H5Tget_cset(type.id()));  // HDF5 converts no character sets
        char* text = nullptr;
        check_status(H5Aread(attribute.id(), memory_type.id(), &text), "cannot read attribute " + where(name));
        std::string value = text ? text : "";
        H5free_memory(text);
        return value;
    }
    const std::size_t size = H5Tget_size(type.id());
    std::string value(size, '\0');
    check_status(H5Aread(attribute.id(), type.id(), value.data()), "cannot read attribute " + where(name));
    value.resize(std::strlen(value.c_str()));
    return value;
}

std::vector<std::string> Group::attribute_names() const {
    std::vector<std::string> names;
    H5Aiterate2(
        id(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
            static_cast<std::vector<std::string>*>(out)->emplace_back(name);
            return 0;
        },
        &names);
    return names;
}

void Group::copy_attributes_from(const Group& other, const std::string& prefix) {
    for (const auto& name : other.attribute_names()) {
        const Handle attribute = open_attribute(other.id(), other.where(name), name);
        Handle type(check(H5Aget_type(attribute.id()), "cannot read type of " + other.where(name)), H5Tclose);
        Handle space(check(H5Aget_space(attribute.id()), "cannot read shape of " + other.where(name)), H5Sclose);
        const H5T_class_t kind = H5Tget_class(type.id());
        const hssize_t count = H5Sget_simple_extent_npoints(space.id());
        if (kind == H5T_STRING) {
            set_attribute(prefix + name, other.attribute_string(name));
        } else if (kind == H5T_INTEGER && count == 1) {
            set_attribute(prefix + name, other.attribute_integer(name));
        } else if (kind == H5T_FLOAT && count == 1 && H5Sget_simple_extent_type(space.id()) == H5S_SCALAR) {
            set_attribute(prefix + name, other.attribute_double(name));
        } else if (kind == H5T_FLOAT || kind == H5T_INTEGER) {
            set_attribute(prefix + name, other.attribute_doubles(name));
        }
    }
}

File File::create(const std::string& path, const std::string& display) {
    Handle plist(check(H5Pcreate(H5P_FILE_CREATE), "cannot create HDF5 property list"), H5Pclose);
    // Timestamps off for the root group as well (see untimed_dataset_properties).
    H5Pset_obj_track_times(plist.id(), false);
    // The HDF5 1.10 file format: its superblock, object headers and chunk
    // indices carry checksums, which HDF5 verifies when it reads them.
    Handle access(check(H5Pcreate(H5P_FILE_ACCESS), "cannot create HDF5 property list"), H5Pclose);
    check_status(H5Pset_libver_bounds(access.id(), H5F_LIBVER_V110, H5F_LIBVER_V110), "cannot select file format");
    // Closing the file closes every group and dataset still open in it. By default HDF5 defers the
    // close until the last of them is closed, and AtomicFile::commit renames the file right after
    // its close: a group still held by the writer (write_atomically's root) would leave a file
    // marked "open for write" under the target's name until the group went, unreadable after a
    // SIGKILL in between (a checkpoint then falls back to its older generation).
    check_status(H5Pset_fclose_degree(access.id(), H5F_CLOSE_STRONG), "cannot set the file close degree");
    const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, plist.id(), access.id());
    if (id < 0) fail(fmt::format("cannot create HDF5 file '{}'", display.empty() ? path : display));
    return File(Handle(id, H5Fclose), path, display.empty() ? path : display);
}

namespace {

// Reads every dataset of a file once, so that HDF5 checks each checksum
// (Fletcher32 on data, the format's own on metadata); throws Error naming
// the first object that fails.
void verify_every_dataset(const Group& root, const std::string& path) {
    struct Walk {
        std::string failed;  // "dataset /x: cause"
    } walk;
    const herr_t status = H5Lvisit(
        root.id(), H5_INDEX_NAME, H5_ITER_INC,
        [](hid_t group, const char* name, const H5L_info_t* info, void* data) -> herr_t {
            auto& w = *static_cast<Walk*>(data);
            if (info->type != H5L_TYPE_HARD) return 0;
            const std::string where = std::string("/") + name;
            const Handle object(H5Oopen(group, name, H5P_DEFAULT), H5Oclose);
            if (!object.valid()) {
                w.failed = "object " + where + ": " + failure_cause();
                return -1;
            }
            if (H5Iget_type(object.id()) != H5I_DATASET) return 0;
            const Handle type(H5Dget_type(object.id()), H5Tclose);
            const Handle space(H5Dget_space(object.id()), H5Sclose);
            if (!type.valid() || !space.valid()) {
                w.failed = "dataset " + where + ": " + failure_cause();
                return -1;
            }
            // Variable-length data live outside the dataset; nothing of ours.
            if (H5Tget_class(type.id()) == H5T_VLEN || H5Tis_variable_str(type.id()) > 0) return 0;
            const int rank = std::max(H5Sget_simple_extent_ndims(space.id()), 0);
            std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
            H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
            const std::size_t element = H5Tget_size(type.id());
            try {
                check_declared_size(object.id(), where, dims, element);
            } catch (const Error& error) {
                w.failed = error.what();
                return -1;
            }
            const hsize_t count = std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
            if (count == 0 || element == 0) return 0;
            std::vector<unsigned char> buffer(count * element);
            if (H5Dread(object.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
                const std::string cause = failure_cause();
                w.failed = "dataset " + where + (cause.empty() ? " cannot be read" : ": " + cause);
                return -1;
            }
            return 0;
        },
        &walk);
    if (!walk.failed.empty()) throw Error(fmt::format("'{}' is damaged: {}", path, walk.failed), "damaged");
    if (status < 0) {
        const std::string cause = failure_cause();
        throw Error(fmt::format("'{}' is damaged: {}", path, cause.empty() ? "its groups cannot be read" : cause),
                    "damaged");
    }
}

}  // namespace

File File::open_read(const std::string& path) {
    if (!std::filesystem::exists(path)) throw Error(fmt::format("file '{}' does not exist", path));
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id < 0) {
        const std::string cause = failure_cause();
        throw Error(cause.empty() ? fmt::format("'{}' is not a readable HDF5 file", path)
                                  : fmt::format("'{}' is not a readable HDF5 file: {}", path, cause),
                    cause.empty() ? "unreadable" : "damaged");
    }
    File file(Handle(id, H5Fclose), path, path);
    try {
        verify_every_dataset(file.root(), path);
    } catch (const Error& error) {
        if (error.cause == "damaged") throw;
        throw Error(fmt::format("'{}' is damaged: {}", path, error.what()), "damaged");
    }
    return file;
}

Group File::root() const {
    return Group(Handle(check(H5Gopen2(handle_.id(), "/", H5P_DEFAULT), "cannot open root of " + display_), H5Gclose),
                 "/", display_);
}

AtomicFile::AtomicFile(std::string target_path)
    : target_(std::move(target_path)), temporary_(target_ + ".tmp." + std::to_string(::getpid())) {
    // Beyond a file-size limit (ulimit -f) the kernel would kill the process
    // with SIGXFSZ; ignored, the write fails with EFBIG and is reported.
    static const bool file_size_signal_ignored = [] {
        std::signal(SIGXFSZ, SIG_IGN);
        return true;
    }();
    (void)file_size_signal_ignored;
    // Errors name the output the user asked for, not the temporary file.
    check_writable(target_);
    try {
        file_ = std::make_unique<File>(File::create(temporary_, target_));
    } catch (const Error&) {
        std::remove(temporary_.c_str());  // a disk full at creation leaves a partial file
        throw;
    }
}

AtomicFile::~AtomicFile() {
    file_.reset();
    if (!committed_) std::remove(temporary_.c_str());
}

bool File::close() {
    if (!handle_.valid()) return true;
    const hid_t id = handle_.id();
    const bool closed = H5Fclose(id) >= 0;
    // A file whose close failed stays half-open; HDF5 is kept from closing it
    // again at exit (see SilenceHdf5Errors) and the process reports the error.
    handle_.forget();
    return closed;
}

namespace {

// Forces a file's bytes (or a directory's entries) to the disk.
void sync_to_disk(const std::string& path, bool directory) {
    const int descriptor = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
    if (descriptor < 0) return;
    const int status = ::fsync(descriptor);
    const int error = errno;
    ::close(descriptor);
    if (status != 0 && !directory)
        throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(error)), std::strerror(error));
}

}  // namespace

void AtomicFile::commit(const std::string& keep_previous_as) {
    if (committed_) return;
    {
        const Group root = file_->root();
        check_status(H5Fflush(root.id(), H5F_SCOPE_GLOBAL), fmt::format("cannot write '{}'", temporary_));
    }
    // Close before the rename so every byte is written; a close that cannot
    // write what HDF5 still holds is a failed write.
    if (!file_->close()) fail(fmt::format("cannot write '{}'", temporary_));
    file_.reset();
    sync_to_disk(temporary_, false);
    namespace fs = std::filesystem;
    std::error_code error;
    if (!keep_previous_as.empty() && fs::exists(target_)) fs::rename(target_, keep_previous_as, error);
    if (!error) fs::rename(temporary_, target_, error);
    if (error) {
        std::remove(temporary_.c_str());
        throw Error(fmt::format("cannot move '{}' to '{}': {}", temporary_, target_, error.message()),
                    error.message());
    }
    const fs::path directory = fs::path(target_).parent_path();
    sync_to_disk(directory.empty() ? "." : directory.string(), true);
    committed_ = true;
}

void rethrow_write_failure(const std::string& target, const Error& error) {
    if (error.cause.empty()) throw Error(fmt::format("cannot write '{}': {}", target, error.what()));
    throw Error(fmt::format("cannot write '{}': {} (temporary file removed)", target, error.cause), error.cause);
}

std::vector<std::string> remove_stale_temporaries(const std::string& target) {
    namespace fs = std::filesystem;
    const fs::path path(target);
    const fs::path directory = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    const std::string prefix = path.filename().string() + ".tmp.";
    std::vector<std::string> removed;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(directory, error)) {
        const std::string name = entry.path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string digits = name.substr(prefix.size());
        if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        const auto pid = static_cast<pid_t>(std::stol(digits));
        // Only a process that no longer exists; ours and any live one's are in use.
        if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
        std::error_code remove_error;
        if (fs::remove(entry.path(), remove_error))
            removed.push_back(path.parent_path().empty() ? name : (directory / name).string());
    }
    return removed;
}

void check_writable(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    fs::path directory = target.parent_path();
    if (directory.empty()) directory = ".";
    if (target.filename().empty()) throw Error(fmt::format("output path '{}' names no file", path));
    if (!fs::is_directory(directory))
        throw Error(fmt::format("cannot write output '{}': directory '{}' does not exist", path, directory.string()));
    if (fs::is_directory(target)) throw Error(fmt::format("cannot write output '{}': it is a directory", path));
    // symlink_status: the link itself, not what it points to.
    const fs::file_status status = fs::symlink_status(target);
    if (fs::is_symlink(status))
        throw Error(fmt::format("cannot write output '{}': it is a symbolic link (give the file it points to)", path));
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw Error(fmt::format("cannot write output '{}': it exists and is not a regular file (a device or a FIFO "
                                "would be replaced)",
                                path));
    // Create (and remove at once) a file beside the output, as its temporary
    // will be (AtomicFile): access(W_OK) answers yes where the write then
    // fails (root on a read-only or pseudo file system, root-squashed NFS,
    // ACLs), and a run without checkpoints would learn it only at its end, its
    // results lost. A name of its own (mkstemp), so that nothing already at
    // the temporary's name is touched.
    std::string probe_name = path + ".probe.XXXXXX";
    const int probe = ::mkstemp(probe_name.data());
    if (probe < 0) throw Error(fmt::format("cannot write output '{}': {}", path, std::strerror(errno)));
    ::close(probe);
    ::unlink(probe_name.c_str());
}

bool Probe::holds(const std::string& name) const {
    return std::find(root_names.begin(), root_names.end(), name) != root_names.end();
}

Probe probe(const std::string& path) {
    namespace fs = std::filesystem;
    Probe result;
    std::error_code error;
    const fs::file_status status = fs::symlink_status(path, error);
    if (error || !fs::exists(status)) return result;
    if (!fs::is_regular_file(status)) {
        result.kind = Probe::Kind::not_regular;
        return result;
    }
    if (fs::file_size(path, error) == 0 && !error) {
        result.kind = Probe::Kind::empty;
        return result;
    }
    const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    const Handle root(file.valid() ? H5Gopen2(file.id(), "/", H5P_DEFAULT) : H5I_INVALID_HID, H5Gclose);
    if (!root.valid()) {
        // The signature HDF5 writes at the start of every file without a user
        // block, as shockgas's are: with it, a file HDF5 cannot open is a
        // damaged HDF5 file; without it, it was never one of ours.
        static constexpr char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
        char head[8] = {};
        std::size_t got = 0;
        if (std::FILE* stream = std::fopen(path.c_str(), "rb")) {
            got = std::fread(head, 1, sizeof head, stream);
            std::fclose(stream);
        }
        result.kind = got == sizeof head && std::memcmp(head, signature, sizeof head) == 0 ? Probe::Kind::damaged
                                                                                          : Probe::Kind::not_hdf5;
        return result;
    }
    result.kind = Probe::Kind::damaged;
    std::vector<std::string> names;
    const herr_t listed = H5Literate(
        root.id(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
            static_cast<std::vector<std::string>*>(out)->emplace_back(name);
            return 0;
        },
        &names);
    if (listed < 0) return result;
    result.kind = Probe::Kind::hdf5;
    result.root_names = std::move(names);
    return result;
}

void check_not_an_input(const std::string& output, const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (!fs::exists(output, error)) return;
    for (const auto& input : inputs) {
        if (input.empty()) continue;
        if (fs::equivalent(output, input, error))
            throw Error(fmt::format("output '{}' is the input '{}': it would be overwritten", output, input));
    }
}

}  // namespace shockgas::h5
