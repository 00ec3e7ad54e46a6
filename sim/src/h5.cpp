#include "shockgas/h5.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>

#include <unistd.h>

#include <fmt/format.h>

namespace shockgas::h5 {

namespace {

// HDF5 prints its own error stack by default; we report through exceptions.
struct SilenceHdf5Errors {
    SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
const SilenceHdf5Errors silence_hdf5_errors;

hid_t check(hid_t id, const std::string& what) {
    if (id < 0) throw Error(what);
    return id;
}

void check_status(herr_t status, const std::string& what) {
    if (status < 0) throw Error(what);
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
    const Handle plist = untimed_dataset_properties();
    Handle dataset(check(H5Dcreate2(group, name.c_str(), file_type, space.id(), H5P_DEFAULT, plist.id(), H5P_DEFAULT),
                         "cannot create dataset " + where),
                   H5Dclose);
    if (count > 0)
        check_status(H5Dwrite(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
                     "cannot write dataset " + where);
}

template <typename T>
std::vector<T> read_dataset(hid_t group, const std::string& where, const std::string& name,
                            std::vector<hsize_t>* dims_out, hid_t memory_type) {
    if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) throw Error(fmt::format("missing dataset {}", where));
    Handle dataset(check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "cannot open dataset " + where), H5Dclose);
    // Only plain numbers are converted: a hostile file can declare an element
    // type of gigabytes (found by fuzzing), for which HDF5 itself would
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
    // A corrupt or hostile file can declare dimensions far beyond its own size
    // (found by fuzzing: 1.7e11 bytes from a 2 kB file). Refuse before
    // allocating: data cannot be larger than the file unless compressed, and
    // 1000x leaves room for compressed files written by other tools.
    hsize_t file_size = 0;
    {
        const Handle file(H5Iget_file_id(dataset.id()), H5Fclose);
        if (file.valid()) H5Fget_filesize(file.id(), &file_size);
    }
    const hsize_t capacity = (1000 * file_size + (hsize_t{1} << 20)) / sizeof(T);
    for (const hsize_t d : dims)
        if (d > capacity || count > capacity)
            throw Error(fmt::format("dataset {} declares {} values, more than a {}-byte file can hold", where, count,
                                    file_size));
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
        if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos)
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
    // Variable-length UTF-8 (schema 2): h5py and netCDF readers give str, not
    // bytes; schema 1's fixed-length strings are still read (attribute_string).
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
    const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, plist.id(), H5P_DEFAULT);
    if (id < 0) throw Error(fmt::format("cannot create HDF5 file '{}'", display.empty() ? path : display));
    return File(Handle(id, H5Fclose), path, display.empty() ? path : display);
}

File File::open_read(const std::string& path) {
    if (!std::filesystem::exists(path)) throw Error(fmt::format("file '{}' does not exist", path));
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id < 0) throw Error(fmt::format("'{}' is not a readable HDF5 file", path));
    return File(Handle(id, H5Fclose), path, path);
}

Group File::root() const {
    return Group(Handle(check(H5Gopen2(handle_.id(), "/", H5P_DEFAULT), "cannot open root of " + display_), H5Gclose),
                 "/", display_);
}

AtomicFile::AtomicFile(std::string target_path)
    : target_(std::move(target_path)), temporary_(target_ + ".tmp." + std::to_string(::getpid())) {
    // Errors name the output the user asked for, not the temporary file.
    check_writable(target_);
    file_ = std::make_unique<File>(File::create(temporary_, target_));
}

AtomicFile::~AtomicFile() {
    file_.reset();
    if (!committed_) std::remove(temporary_.c_str());
}

void AtomicFile::commit() {
    if (committed_) return;
    H5Fflush(file_->root().id(), H5F_SCOPE_GLOBAL);
    file_.reset();  // close before the rename so every byte is on disk
    std::error_code error;
    std::filesystem::rename(temporary_, target_, error);
    if (error) {
        std::remove(temporary_.c_str());
        throw Error(fmt::format("cannot move '{}' to '{}': {}", temporary_, target_, error.message()));
    }
    committed_ = true;
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
    if (::access(directory.c_str(), W_OK) != 0)
        throw Error(fmt::format("cannot write output '{}': {}", path, std::strerror(errno)));
}

}  // namespace shockgas::h5
