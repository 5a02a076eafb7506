#include "io/hdf5.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "core/error.hpp"
#include "io/output_space.hpp"

namespace bsmpm::h5 {

namespace {

herr_t find_errno(unsigned, const H5E_error2_t* entry, void* out) {
  // The sec2 driver's read, write and truncate errors say "errno = N, error message = ...".
  if (const char* at = entry->desc ? std::strstr(entry->desc, "errno = ") : nullptr)
    *static_cast<int*>(out) = std::atoi(at + 8);
  return 0;
}

herr_t find_innermost(unsigned, const H5E_error2_t* entry, void* out) {
  if (entry->desc) *static_cast<std::string*>(out) = entry->desc;
  return 0;
}

// What the innermost entry of HDF5's error stack says (e.g. "truncated file: eof = ...").
std::string innermost_error() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, find_innermost, &text);
  return text;
}

// The error of the HDF5 call that just failed: an OutOfSpaceError when the file system said
// that there is no room (the write failed half-way, so not clean), else an IoError.
[[noreturn]] void fail(const std::string& what) {
  int error_number = 0;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, find_errno, &error_number);
  std::string message = "HDF5: " + what + " failed";
  if (error_number != 0) message += std::string(": ") + std::strerror(error_number);
  if (is_out_of_space(error_number)) throw OutOfSpaceError(message, false);
  throw IoError(message);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* out) {
  static_cast<std::vector<std::string>*>(out)->push_back(name);
  return 0;
}

template <class T>
void write_typed(hid_t parent, const std::string& name, const T* data, std::size_t rows, std::size_t cols,
                 hid_t file_type, hid_t mem_type) {
  const hsize_t dims[2] = {rows, cols};
  Handle space(H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr), "dataspace for " + name);
  Handle set(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             "creating dataset " + name);
  if (rows * cols > 0) check(H5Dwrite(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing " + name);
}
}  // namespace

Handle::Handle(hid_t id, const std::string& what) : id_(id) {
  if (id < 0) fail(what);
}

Handle::~Handle() {
  if (id_ >= 0) H5Idec_ref(id_);
}

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    if (id_ >= 0) H5Idec_ref(id_);
    id_ = o.id_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void quiet_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

void leave_failed_objects_at_exit() { H5dont_atexit(); }

void flush(hid_t file, const std::string& path) { check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flushing " + path); }

Handle create_file(const std::string& path) {
  quiet_errors();
  return Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "creating " + path);
}

Handle open_file(const std::string& path, bool writable) {
  quiet_errors();
  hid_t id = H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) {
    const std::string detail = innermost_error();
    throw IoError(path + ": cannot open as an HDF5 file" + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
  }
  return Handle(id, "opening " + path);
}

Handle create_group(hid_t parent, const std::string& name) {
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating group " + name);
}

Handle open_group(hid_t parent, const std::string& name) {
  hid_t id = H5Gopen2(parent, name.c_str(), H5P_DEFAULT);
  if (id < 0) throw IoError("HDF5: the file has no group '" + name + "'");
  return Handle(id, "opening group " + name);
}

bool exists(hid_t parent, const std::string& name) { return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0; }

void remove_link(hid_t parent, const std::string& name) {
  check(H5Ldelete(parent, name.c_str(), H5P_DEFAULT), "removing " + name);
}

std::vector<std::string> children(hid_t group) {
  std::vector<std::string> names;
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names), "listing a group");
  return names;
}

namespace {
void replace_attribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) > 0) check(H5Adelete(obj, name.c_str()), "replacing attribute " + name);
}
}  // namespace

void set_attribute(hid_t obj, const std::string& name, double value) {
  replace_attribute(obj, name);
  Handle space(H5Screate(H5S_SCALAR), "dataspace");
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT), "attribute " + name);
  check(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "writing attribute " + name);
}

void set_attribute(hid_t obj, const std::string& name, long value) {
  replace_attribute(obj, name);
  Handle space(H5Screate(H5S_SCALAR), "dataspace");
  const long long v = value;
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT), "attribute " + name);
  check(H5Awrite(attr, H5T_NATIVE_LLONG, &v), "writing attribute " + name);
}

void set_attribute(hid_t obj, const std::string& name, const std::string& value) {
  replace_attribute(obj, name);
  Handle space(H5Screate(H5S_SCALAR), "dataspace");
  Handle type(H5Tcopy(H5T_C_S1), "string type");
  check(H5Tset_size(type, std::max<std::size_t>(1, value.size())), "string size");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "string charset");
  Handle attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), "attribute " + name);
  std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attr, type, padded.data()), "writing attribute " + name);
}

void set_attribute(hid_t obj, const std::string& name, const std::vector<double>& values) {
  replace_attribute(obj, name);
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), "dataspace");
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT), "attribute " + name);
  check(H5Awrite(attr, H5T_NATIVE_DOUBLE, values.data()), "writing attribute " + name);
}

bool has_attribute(hid_t obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

namespace {
Handle open_attribute(hid_t obj, const std::string& name) {
  if (!has_attribute(obj, name)) throw IoError("HDF5: missing attribute '" + name + "'");
  return Handle(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "opening attribute " + name);
}

// A scalar attribute is read into one value: an attribute of several elements (a damaged or
// foreign file) would overflow it, so it is refused.
Handle open_single_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_attribute(obj, name);
  Handle space(H5Aget_space(attr), "attribute space");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n != 1)
    throw IoError("HDF5: attribute '" + name + "' holds " + std::to_string(n) + " values where one was expected");
  return attr;
}
}  // namespace

double get_double_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_single_attribute(obj, name);
  double v = 0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "reading attribute " + name);
  return v;
}

long get_long_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_single_attribute(obj, name);
  long long v = 0;
  check(H5Aread(attr, H5T_NATIVE_LLONG, &v), "reading attribute " + name);
  return static_cast<long>(v);
}

std::string get_string_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_single_attribute(obj, name);
  Handle type(H5Aget_type(attr), "attribute type");
  if (H5Tget_class(type) != H5T_STRING) throw IoError("HDF5: attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type) > 0) {
    char* s = nullptr;
    Handle mem(H5Tcopy(H5T_C_S1), "string type");
    H5Tset_size(mem, H5T_VARIABLE);
    check(H5Aread(attr, mem, &s), "reading attribute " + name);
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }
  const std::size_t n = H5Tget_size(type);
  std::string out(n, '\0');
  check(H5Aread(attr, type, out.data()), "reading attribute " + name);
  out.resize(std::strlen(out.c_str()));
  return out;
}

std::vector<double> get_doubles_attribute(hid_t obj, const std::string& name) {
  Handle attr = open_attribute(obj, name);
  Handle space(H5Aget_space(attr), "attribute space");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> v(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, v.data()), "reading attribute " + name);
  return v;
}

void write_dataset(hid_t parent, const std::string& name, const double* data, std::size_t rows, std::size_t cols) {
  write_typed(parent, name, data, rows, cols, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE);
}
void write_dataset(hid_t parent, const std::string& name, const std::uint16_t* data, std::size_t rows) {
  write_typed(parent, name, data, rows, 1, H5T_STD_U16LE, H5T_NATIVE_UINT16);
}

void write_dataset(hid_t parent, const std::string& name, const std::uint32_t* data, std::size_t rows) {
  write_typed(parent, name, data, rows, 1, H5T_STD_U32LE, H5T_NATIVE_UINT32);
}

std::vector<std::size_t> dataset_shape(hid_t parent, const std::string& name) {
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name);
  Handle space(H5Dget_space(set), "dataset space");
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return std::vector<std::size_t>(dims.begin(), dims.end());
}

std::vector<double> read_doubles(hid_t parent, const std::string& name) {
  if (!exists(parent, name)) throw IoError("HDF5: missing dataset '" + name + "'");
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name);
  Handle space(H5Dget_space(set), "dataset space");
  std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "reading " + name);
  return v;
}

namespace {
template <class T>
std::vector<T> read_integers(hid_t parent, const std::string& name, hid_t mem_type) {
  if (!exists(parent, name)) throw IoError("HDF5: missing dataset '" + name + "'");
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name);
  Handle space(H5Dget_space(set), "dataset space");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0) throw IoError("HDF5: dataset '" + name + "' has no size");
  std::vector<T> v(static_cast<std::size_t>(n));
  if (!v.empty()) check(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "reading " + name);
  return v;
}
}  // namespace

std::vector<std::uint16_t> read_uint16(hid_t parent, const std::string& name) {
  return read_integers<std::uint16_t>(parent, name, H5T_NATIVE_UINT16);
}

std::vector<std::uint32_t> read_uint32(hid_t parent, const std::string& name) {
  return read_integers<std::uint32_t>(parent, name, H5T_NATIVE_UINT32);
}

RowAppender::RowAppender(hid_t parent, const std::string& name, std::size_t cols, std::size_t chunk_rows)
    : cols_(cols), chunk_rows_(chunk_rows), name_(name) {
  const hsize_t dims[2] = {0, cols}, max_dims[2] = {H5S_UNLIMITED, cols}, chunk[2] = {chunk_rows, cols};
  Handle space(H5Screate_simple(2, dims, max_dims), "dataspace for " + name);
  Handle props(H5Pcreate(H5P_DATASET_CREATE), "dataset properties");
  check(H5Pset_chunk(props, 2, chunk), "chunking " + name);
  dataset_ = Handle(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, props, H5P_DEFAULT),
                    "creating dataset " + name);
}

RowAppender RowAppender::reopen(hid_t parent, const std::string& name, std::size_t rows) {
  RowAppender a;
  a.name_ = name;
  a.dataset_ = Handle(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name);
  Handle space(H5Dget_space(a.dataset_), "dataset space");
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space) != 2) throw IoError("HDF5: dataset '" + name + "' is not a table");
  H5Sget_simple_extent_dims(space, dims, nullptr);
  if (rows > dims[0])
    throw IoError("HDF5: dataset '" + name + "' holds " + std::to_string(dims[0]) + " rows, fewer than the " +
                  std::to_string(rows) + " expected");
  a.cols_ = dims[1];
  a.rows_ = rows;
  {
    Handle props(H5Dget_create_plist(a.dataset_), "dataset properties");
    hsize_t chunk[2] = {0, 0};
    if (H5Pget_chunk(props, 2, chunk) == 2) a.chunk_rows_ = chunk[0];
  }
  const hsize_t cut[2] = {rows, dims[1]};
  check(H5Dset_extent(a.dataset_, cut), "cutting " + name);
  return a;
}

std::size_t RowAppender::growth_bound(std::size_t count) const {
  if (count == 0) return 0;
  const std::size_t first = rows_ / chunk_rows_, last = (rows_ + count - 1) / chunk_rows_;
  return (last - first + 1) * chunk_rows_ * cols_ * sizeof(double) + 1024;  // + its B-tree entries
}

void RowAppender::append(const double* rows, std::size_t count) {
  if (count == 0) return;
  const hsize_t new_dims[2] = {rows_ + count, cols_};
  check(H5Dset_extent(dataset_, new_dims), "extending " + name_);
  Handle file_space(H5Dget_space(dataset_), "dataset space");
  const hsize_t start[2] = {rows_, 0}, counts[2] = {count, cols_};
  check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, counts, nullptr), "selecting rows");
  Handle mem_space(H5Screate_simple(2, counts, nullptr), "memory space");
  check(H5Dwrite(dataset_, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, rows), "appending to " + name_);
  rows_ += count;
}

}  // namespace bsmpm::h5
