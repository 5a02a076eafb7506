#include "io/run_reader.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/particle_fields.hpp"

namespace bsmpm {

namespace {

// The helpers in io/hdf5 name the object but not the file; every error leaving the reader
// names the run file too, and is an InputError: the file is not what a run writes.
template <class F>
auto with_path(const std::string& path, F&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const IoError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind(path, 0) == 0 ? what : path + ": " + what);
  }
}

// Whether another process holds a lock on the file: HDF5 (1.10.7 and later) keeps one on a
// file it writes, so that no reader sees it half-written.
bool locked_by_a_writer(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return locked;
}

// An HDF5 file starts with this signature (when it has no user block, as run files do).
bool has_hdf5_signature(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[8] = {0};
  in.read(head, sizeof head);
  return in && std::string(head, sizeof head) == std::string("\x89HDF\r\n\x1a\n", 8);
}

Vec2 vec2_attribute(hid_t obj, const std::string& name) {
  const std::vector<double> v = h5::get_doubles_attribute(obj, name);
  if (v.size() != 2) throw IoError("attribute '" + name + "' should hold 2 numbers");
  return {v[0], v[1]};
}

std::vector<std::string> split_columns(const std::string& joined) {
  std::vector<std::string> out;
  std::stringstream s(joined);
  for (std::string item; std::getline(s, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

RunReader::RunReader(const std::string& path) : path_(path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, error)) throw InputError(path + ": a directory, not a run file");
  try {
    file_ = h5::open_file(path);
  } catch (const IoError& e) {
    if (!has_hdf5_signature(path)) throw InputError(path + ": not an HDF5 file (bsmpm run writes run.h5)");
    if (locked_by_a_writer(path))
      throw InputError(path + ": a run is still writing it, and HDF5 locks a file it writes: wait for the run to "
                       "end, or set HDF5_USE_FILE_LOCKING=FALSE to read the frames it has flushed");
    throw InputError(std::string(e.what()) +
                     ": the file is damaged (h5ls cannot open it either): a write cut short leaves it so, by a "
                     "crash, or by a full disk on a file system where bsmpm cannot reserve room ahead "
                     "(docs/output-format.md, \"A full disk\")");
  }
  with_path(path_, [&] {
    if (!h5::has_attribute(file_, "format") || h5::get_string_attribute(file_, "format") != "bsmpm-run")
      throw IoError("not a bsmpm run file (no attribute format = \"bsmpm-run\" on '/')");
    const long version = h5::get_long_attribute(file_, "format_version");
    if (version != 1)
      throw IoError("run file format version " + std::to_string(version) + " is not supported (expected 1)");
    title_ = h5::has_attribute(file_, "title") ? h5::get_string_attribute(file_, "title") : "";
    {
      h5::Handle g = h5::open_group(file_, "provenance");
      effective_scene_ = h5::get_string_attribute(g, "effective_scene");
    }
    {
      h5::Handle g = h5::open_group(file_, "reference");
      reference_.length = h5::get_double_attribute(g, "length");
      reference_.density = h5::get_double_attribute(g, "density");
      reference_.gravity = h5::get_double_attribute(g, "gravity");
    }
    {
      h5::Handle g = h5::open_group(file_, "grid");
      grid_.order = static_cast<int>(h5::get_long_attribute(g, "order"));
      grid_.origin = vec2_attribute(g, "origin");
      grid_.cell_size = vec2_attribute(g, "cell_size");
      const Vec2 cells = vec2_attribute(g, "cells");
      grid_.cells = {static_cast<int>(cells.x()), static_cast<int>(cells.y())};
      grid_.extent_max = vec2_attribute(g, "extent_max");
    }
    {
      h5::Handle particles = h5::open_group(file_, "particles");
      particle_body_ = h5::read_uint16(particles, "body");
    }
    {
      h5::Handle g = h5::open_group(file_, "bodies");
      // Groups are named 0, 1, ...; listing order is by name, so look them up by number.
      const std::size_t count = h5::children(g).size();
      for (std::size_t b = 0; b < count; ++b) {
        const std::string name = std::to_string(b);
        if (!h5::exists(g, name)) throw IoError("missing group /bodies/" + name);
        h5::Handle bg = h5::open_group(g, name);
        RunBodyInfo body;
        body.name = h5::get_string_attribute(bg, "name");
        body.type = h5::get_string_attribute(bg, "type");
        body.first = static_cast<std::size_t>(h5::get_long_attribute(bg, "first"));
        body.count = static_cast<std::size_t>(h5::get_long_attribute(bg, "count"));
        body.density = h5::get_double_attribute(bg, "density");
        body.spacing = vec2_attribute(bg, "spacing");
        if (body.first + body.count > particle_body_.size())
          throw IoError("/bodies/" + name + " names particles beyond the " + std::to_string(particle_body_.size()) +
                        " in /particles/body");
        bodies_.push_back(std::move(body));
      }
    }
    for (const BodyId b : particle_body_)
      if (b >= bodies_.size()) throw IoError("/particles/body refers to body " + std::to_string(b) + ", which /bodies lacks");
    {
      h5::Handle g = h5::open_group(file_, "frames");
      for (const std::string& name : h5::children(g)) {
        h5::Handle fg = h5::open_group(g, name);
        RunFrameInfo f;
        f.index = static_cast<int>(frames_.size());
        f.group = name;
        f.time = h5::get_double_attribute(fg, "time");
        f.step = h5::get_long_attribute(fg, "step");
        f.dt = h5::get_double_attribute(fg, "dt");
        frames_.push_back(std::move(f));
      }
    }
  });
}

std::string RunReader::status() const {
  return with_path(path_, [&] { return h5::get_string_attribute(file_, "status"); });
}

const RunFrameInfo& RunReader::frame_info(int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= frames_.size())
    throw IoError(path_ + ": no frame " + std::to_string(index) + " (the run has " + std::to_string(frames_.size()) +
                  " frames)");
  return frames_[static_cast<std::size_t>(index)];
}

std::vector<double> RunReader::read_frame_field(int index, std::string_view name) const {
  const RunFrameInfo& info = frame_info(index);
  const ParticleField& field = particle_field(name);
  const std::size_t expected = static_cast<std::size_t>(field.components) * particle_count();
  return with_path(path_, [&] {
    h5::Handle frames = h5::open_group(file_, "frames");
    h5::Handle g = h5::open_group(frames, info.group);
    std::vector<double> values = h5::read_doubles(g, std::string(name));
    if (values.size() != expected)
      throw IoError("/frames/" + info.group + "/" + std::string(name) + " holds " + std::to_string(values.size()) +
                    " values; expected " + std::to_string(expected));
    return values;
  });
}

std::vector<Vec2> RunReader::read_frame_vectors(int index, std::string_view name) const {
  const std::vector<double> flat = read_frame_field(index, name);
  std::vector<Vec2> out(particle_count());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Vec2(flat[2 * k], flat[2 * k + 1]);
  return out;
}

std::vector<Vec2> RunReader::position(int index) const { return read_frame_vectors(index, "position"); }
std::vector<Vec2> RunReader::velocity(int index) const { return read_frame_vectors(index, "velocity"); }
std::vector<Vec2> RunReader::displacement(int index) const { return read_frame_vectors(index, "displacement"); }
std::vector<double> RunReader::pressure(int index) const { return read_frame_field(index, "pressure"); }
std::vector<double> RunReader::volume(int index) const { return read_frame_field(index, "volume"); }

std::vector<StressComponents> RunReader::stress(int index) const {
  const std::vector<double> flat = read_frame_field(index, "stress");
  std::vector<StressComponents> out(particle_count());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  return out;
}

std::vector<std::string> RunReader::probe_names() const {
  return with_path(path_, [&] {
    h5::Handle g = h5::open_group(file_, "probes");
    return h5::children(g);
  });
}

RunProbeSeries RunReader::probe(const std::string& name) const {
  return with_path(path_, [&] {
    h5::Handle g = h5::open_group(file_, "probes");
    if (!h5::exists(g, name)) throw IoError("no probe '" + name + "' in /probes");
    h5::Handle set(H5Dopen2(g, name.c_str(), H5P_DEFAULT), "opening probe " + name);
    RunProbeSeries series;
    series.name = name;
    series.columns = split_columns(h5::get_string_attribute(set, "columns"));
    if (h5::has_attribute(set, "units")) series.units = split_columns(h5::get_string_attribute(set, "units"));
    series.description = h5::get_string_attribute(set, "description");
    series.values = h5::read_doubles(g, name);
    const auto shape = h5::dataset_shape(g, name);
    series.rows = shape.empty() ? 0 : shape[0];
    if (series.values.size() != series.rows * series.columns.size())
      throw IoError("probe '" + name + "' has " + std::to_string(series.values.size()) + " values for " +
                    std::to_string(series.columns.size()) + " columns");
    return series;
  });
}

}  // namespace bsmpm
