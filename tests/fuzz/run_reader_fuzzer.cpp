// Fuzzes the run reader (RunReader) on damaged run files. A byte-level mutation of an HDF5
// file mostly finds the HDF5 library's own parser (not bsmpm's, and not instrumented here);
// instead the input is a list of edits applied through the HDF5 API to a small valid run
// (tests/fuzz/seed_run.h5): objects removed, attributes removed or replaced by values of
// another type or range, datasets replaced by others of any shape and type. The reader must
// then read everything (metadata, every field of every frame, every probe) or throw a
// bsmpm::Error; nothing else may escape, crash, hang or trip a sanitizer.
#include <hdf5.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/hdf5.hpp"
#include "io/run_reader.hpp"

namespace {

namespace fs = std::filesystem;

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  template <class T>
  T value() {
    T v{};
    unsigned char bytes[sizeof(T)] = {};
    for (auto& b : bytes) b = byte();
    std::memcpy(&v, bytes, sizeof(T));
    return v;
  }
  std::string text(std::size_t max) {
    std::string s;
    for (std::size_t n = byte() % (max + 1); n > 0 && !empty(); --n) s.push_back(static_cast<char>(byte()));
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

// Every object below the root, by path ("/frames/000001/x", ...).
std::vector<std::string> objects(hid_t file) {
  std::vector<std::string> out;
  H5Ovisit(
      file, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t*, void* op) -> herr_t {
        if (std::strcmp(name, ".") != 0) static_cast<std::vector<std::string>*>(op)->push_back(std::string("/") + name);
        return 0;
      },
      &out);
  return out;
}

std::vector<std::string> attributes(hid_t obj) {
  std::vector<std::string> out;
  hsize_t at = 0;
  H5Aiterate2(
      obj, H5_INDEX_NAME, H5_ITER_INC, &at,
      [](hid_t, const char* name, const H5A_info_t*, void* op) -> herr_t {
        static_cast<std::vector<std::string>*>(op)->push_back(name);
        return 0;
      },
      &out);
  return out;
}

// One edit, as the next bytes of the input say.
void edit(hid_t file, Input& in) {
  const std::vector<std::string> all = objects(file);
  const std::uint8_t op = in.byte() % 8;
  const std::string path = all.empty() ? "/" : all[in.value<std::uint16_t>() % all.size()];
  if (op == 0) {
    if (path != "/") bsmpm::h5::remove_link(file, path);
    return;
  }
  bsmpm::h5::Handle obj(H5Oopen(file, path.c_str(), H5P_DEFAULT), "opening " + path);
  if (op <= 4) {  // an attribute: removed, or replaced by a double, a long, a string, a list
    const std::vector<std::string> names = attributes(obj);
    std::string name = names.empty() ? in.text(8) : names[in.byte() % names.size()];
    if (name.empty()) name.push_back('a');  // not `= "a"`: GCC 12's false -Wrestrict (its bug 105329)
    if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
    switch (op) {
      case 1: break;
      case 2: bsmpm::h5::set_attribute(obj, name, in.value<double>()); break;
      case 3: bsmpm::h5::set_attribute(obj, name, static_cast<long>(in.value<std::int32_t>())); break;
      default: {
        if (in.byte() % 2) {
          bsmpm::h5::set_attribute(obj, name, in.text(24));
        } else {
          std::vector<double> v(in.byte() % 6);
          for (auto& x : v) x = in.value<double>();
          bsmpm::h5::set_attribute(obj, name, v);
        }
      }
    }
    return;
  }
  // A dataset replaced by another (or, at a group, a new one in it): any shape, any type.
  std::string name;
  hid_t parent = file;
  bsmpm::h5::Handle group;
  if (H5Iget_type(obj) == H5I_DATASET || path == "/") {
    name = path;
    if (path == "/") name = std::string(1, '/').append(in.text(8));  // not "/" + ...: GCC 12's false -Wrestrict (its bug 105329)
    if (path != "/") bsmpm::h5::remove_link(file, path);
  } else {
    group = bsmpm::h5::open_group(file, path);
    parent = group;
    name = in.text(8);
  }
  if (name.empty() || name.back() == '/' || bsmpm::h5::exists(parent, name)) return;
  const std::size_t rows = in.byte() % 40, cols = 1 + in.byte() % 4;
  if (op == 5) {
    std::vector<double> v(rows * cols);
    for (auto& x : v) x = in.byte() % 4 == 0 ? in.value<double>() : static_cast<double>(in.byte()) / 16.0;
    bsmpm::h5::write_dataset(parent, name, v.data(), rows, cols);
  } else if (op == 6) {
    std::vector<std::uint32_t> v(rows);
    for (auto& x : v) x = in.byte() % 2 ? in.value<std::uint32_t>() : in.byte() % 4;
    bsmpm::h5::write_dataset(parent, name, v.data(), rows);
  } else {
    std::vector<std::uint16_t> v(rows);
    for (auto& x : v) x = in.byte() % 4;
    bsmpm::h5::write_dataset(parent, name, v.data(), rows);
  }
}

void read_everything(const std::string& path) {
  const bsmpm::RunReader run(path);
  (void)run.status();
  for (std::size_t i = 0; i < run.frames().size(); ++i) {
    const int f = static_cast<int>(i);
    (void)run.position(f);
    (void)run.velocity(f);
    (void)run.displacement(f);
    (void)run.pressure(f);
    (void)run.volume(f);
    (void)run.stress(f);
  }
  for (const std::string& name : run.probe_names()) (void)run.probe(name);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string seed = BSMPM_FUZZ_SEED_RUN;
  static const std::string path = (fs::temp_directory_path() / ("bsmpm_fuzz_run_" + std::to_string(getpid()) + ".h5")).string();
  fs::copy_file(seed, path, fs::copy_options::overwrite_existing);
  Input in(data, size);
  try {
    bsmpm::h5::Handle file = bsmpm::h5::open_file(path, true);
    for (int edits = 0; !in.empty() && edits < 16; ++edits) edit(file, in);
  } catch (const bsmpm::Error&) {
    // an edit HDF5 refused: read what was made of the file so far
  }
  try {
    read_everything(path);
  } catch (const bsmpm::Error&) {
  }
  return 0;
}
