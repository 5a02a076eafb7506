// Thin RAII layer over HDF5's C API: owned identifiers and the few attribute and dataset
// helpers the run file needs. Every failure throws IoError naming the object.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bsmpm::h5 {

// Owns an HDF5 identifier; closes it with H5Oclose/H5Fclose/... through H5Idec_ref.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id, const std::string& what);
  ~Handle();
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

// Silences HDF5's own error printing; errors surface as exceptions instead (an
// OutOfSpaceError when the file system had no room for a write).
void quiet_errors();

// A program calls this first, before any other HDF5 call: HDF5 then leaves its clean-up at
// exit to the operating system. HDF5 1.10 keeps the identifier of an object whose close
// failed (a file whose last write found the disk full) with the object half torn down; its
// clean-up at exit closes it again and crashes (SIGSEGV in H5_term_library). Everything the
// program opens is closed by its Handle before exit; only such a failed object is left.
void leave_failed_objects_at_exit();

// H5Fflush of the whole file; throws naming `path`.
void flush(hid_t file, const std::string& path);

Handle create_file(const std::string& path);
Handle open_file(const std::string& path, bool writable = false);
Handle create_group(hid_t parent, const std::string& name);
Handle open_group(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& name);
void remove_link(hid_t parent, const std::string& name);  // a group or dataset (space is not reclaimed)
std::vector<std::string> children(hid_t group);  // link names, in name order

void set_attribute(hid_t obj, const std::string& name, double value);
void set_attribute(hid_t obj, const std::string& name, long value);
void set_attribute(hid_t obj, const std::string& name, const std::string& value);
void set_attribute(hid_t obj, const std::string& name, const std::vector<double>& values);
bool has_attribute(hid_t obj, const std::string& name);
double get_double_attribute(hid_t obj, const std::string& name);
long get_long_attribute(hid_t obj, const std::string& name);
std::string get_string_attribute(hid_t obj, const std::string& name);
std::vector<double> get_doubles_attribute(hid_t obj, const std::string& name);

// Row-major datasets of `rows` x `cols` (cols = 1 writes a 1-D dataset).
void write_dataset(hid_t parent, const std::string& name, const double* data, std::size_t rows, std::size_t cols);
void write_dataset(hid_t parent, const std::string& name, const std::uint16_t* data, std::size_t rows);
void write_dataset(hid_t parent, const std::string& name, const std::uint32_t* data, std::size_t rows);
std::vector<std::size_t> dataset_shape(hid_t parent, const std::string& name);
std::vector<double> read_doubles(hid_t parent, const std::string& name);  // any numeric type
std::vector<std::uint16_t> read_uint16(hid_t parent, const std::string& name);
std::vector<std::uint32_t> read_uint32(hid_t parent, const std::string& name);

// A 2-D double dataset that grows by rows (chunked, unlimited first dimension).
class RowAppender {
 public:
  RowAppender() = default;
  // `chunk_rows`: rows per chunk, the unit in which the file grows (a whole chunk is
  // allocated at the first write into it).
  RowAppender(hid_t parent, const std::string& name, std::size_t cols, std::size_t chunk_rows = 1024);
  // The existing dataset `name`, cut to its first `rows` rows (a resumed run continues there).
  static RowAppender reopen(hid_t parent, const std::string& name, std::size_t rows);
  void append(const double* rows, std::size_t count);
  std::size_t rows() const { return rows_; }
  std::size_t cols() const { return cols_; }
  // Bytes the file may grow by when `count` more rows are appended (the chunks they start).
  std::size_t growth_bound(std::size_t count) const;

 private:
  Handle dataset_;
  std::size_t cols_ = 0, rows_ = 0, chunk_rows_ = 1024;
  std::string name_;
};

}  // namespace bsmpm::h5
