#include "io/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.hpp"
#include "core/version.hpp"
#include "io/hdf5.hpp"
#include "io/output_space.hpp"
#include "io/particle_datasets.hpp"

namespace bsmpm {

namespace {

constexpr long kFormatVersion = 1;

void set_count_list(hid_t obj, const std::string& name, const std::vector<std::uint64_t>& values) {
  h5::set_attribute(obj, name, std::vector<double>(values.begin(), values.end()));  // exact below 2^53
}

std::vector<std::uint64_t> get_count_list(hid_t obj, const std::string& name) {
  std::vector<std::uint64_t> out;
  for (const double v : h5::get_doubles_attribute(obj, name)) {
    if (!(v >= 0.0 && v < 9.0e15)) throw IoError("attribute '" + name + "' holds an invalid count");
    out.push_back(static_cast<std::uint64_t>(v));
  }
  return out;
}

void write_work(hid_t g, const std::string& prefix, const ConstraintWork& w) {
  h5::set_attribute(g, prefix + "walls", w.walls);
  h5::set_attribute(g, prefix + "clamps", w.clamps);
  h5::set_attribute(g, prefix + "contact", w.contact);
  h5::set_attribute(g, prefix + "rigid_contact", w.rigid_contact);
}

ConstraintWork read_work(hid_t g, const std::string& prefix) {
  ConstraintWork w;
  w.walls = h5::get_double_attribute(g, prefix + "walls");
  w.clamps = h5::get_double_attribute(g, prefix + "clamps");
  w.contact = h5::get_double_attribute(g, prefix + "contact");
  w.rigid_contact = h5::get_double_attribute(g, prefix + "rigid_contact");
  return w;
}

// The state fields of the table, in slot order, exactly as stored (float64, uint16, uint32).
void write_particles(hid_t group, const Particles& ps) {
  std::vector<double> buffer;
  for (const ParticleField& field : particle_fields())
    if (field.has(kCheckpointState)) write_particle_dataset(group, field, ps, nullptr, buffer);
}

Particles read_particles(hid_t group, std::size_t n) {
  Particles ps;
  for (std::size_t p = 0; p < n; ++p) ps.push_back(Vec2::Zero(), 0.0, 0.0, 0);
  for (const ParticleField& field : particle_fields()) {
    if (!field.has(kCheckpointState)) continue;
    const std::string name(field.name);
    if (!h5::exists(group, name)) throw IoError("the checkpoint lacks the particle field '" + name + "'");
    const std::vector<double> values = read_particle_dataset(group, field);
    const std::size_t c = static_cast<std::size_t>(field.components);
    if (values.size() != n * c)
      throw IoError("the checkpoint's particle field '" + name + "' holds " + std::to_string(values.size()) +
                    " values; expected " + std::to_string(n * c));
    for (std::size_t p = 0; p < n; ++p) field.set(ps, p, &values[c * p]);
  }
  return ps;
}

// An upper bound of the checkpoint's size: the state fields, the probes' rows and the
// effects' state (its raw data, exactly), the scene's text and the attributes and object headers (h5stat: 14.4 KiB of
// metadata for the Lobovsky tank's checkpoint with its 3.6 KiB of scene text).
std::uint64_t checkpoint_bytes(const CheckpointScene& scene, const Simulation& sim) {
  std::uint64_t bytes = 24 * 1024 + scene.text.size() + scene.command_line.size();
  for (const std::string& o : scene.overrides) bytes += o.size() + 256;
  for (const ParticleField& field : particle_fields())
    if (field.has(kCheckpointState)) bytes += sim.particles().size() * field_value_bytes(field);
  for (const auto& probe : sim.probes()) bytes += probe->data().size() * sizeof(double) + 1024;
  bytes += sim.counters().effect_state.size() * sizeof(double);  // the effects' own state (a pressure field)
  return bytes;
}

// Data and metadata on the disk before the rename makes the file the checkpoint.
void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw IoError(path + ": cannot open to sync");
  const int status = ::fsync(fd), error_number = errno;
  ::close(fd);
  if (status == 0) return;
  const std::string message = path + ": sync failed: " + std::strerror(error_number);
  if (is_out_of_space(error_number)) throw OutOfSpaceError(message, false);
  throw IoError(message);
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointScene& scene, const Simulation& sim,
                      const RunLoopState& loop, const RunWriterState& writer, double wall_seconds) {
  const std::string tmp = path + ".tmp";
  FileRoom room;  // outlives the file: HDF5 writes into it until the file is closed
  try {
    {
      h5::Handle f = h5::create_file(tmp);
      room = FileRoom(tmp, path);
      room.keep(checkpoint_bytes(scene, sim), "the checkpoint");
      h5::set_attribute(f, "format", std::string("bsmpm-checkpoint"));
      h5::set_attribute(f, "format_version", kFormatVersion);
      h5::set_attribute(f, "program_version", std::string(kVersion));
      h5::set_attribute(f, "git_revision", std::string(kGitRevision));
      {
        h5::Handle g = h5::create_group(f, "scene");
        h5::set_attribute(g, "path", scene.path);
        h5::set_attribute(g, "text", scene.text);
        h5::set_attribute(g, "command_line", scene.command_line);
        h5::set_attribute(g, "overrides", static_cast<long>(scene.overrides.size()));
        for (std::size_t k = 0; k < scene.overrides.size(); ++k)
          h5::set_attribute(g, "override_" + std::to_string(k), scene.overrides[k]);
      }
      {
        h5::Handle g = h5::create_group(f, "step");
        const StepCounters c = sim.counters();
        h5::set_attribute(g, "time", c.time);
        h5::set_attribute(g, "step", c.step);
        h5::set_attribute(g, "max_signal_speed", c.max_signal_speed);
        h5::set_attribute(g, "clamped_positions", c.stats.clamped_positions);
        write_work(g, "work_", c.stats.work);
        h5::set_attribute(g, "pressure_solves", c.stats.pressure.solves);
        h5::set_attribute(g, "pressure_iterations", c.stats.pressure.iterations);
        h5::set_attribute(g, "pressure_max_iterations", static_cast<long>(c.stats.pressure.max_iterations));
        h5::set_attribute(g, "pressure_max_residual", c.stats.pressure.max_residual);
        if (!c.effect_state.empty())
          h5::write_dataset(g, "effect_state", c.effect_state.data(), c.effect_state.size(), 1);
      }
      {
        h5::Handle g = h5::create_group(f, "run_loop");
        h5::set_attribute(g, "next_frame", loop.next_frame);
        h5::set_attribute(g, "steps", loop.steps);
        h5::set_attribute(g, "min_dt", loop.min_dt);
        h5::set_attribute(g, "max_dt", loop.max_dt);
        h5::set_attribute(g, "last_dt", loop.last_dt);
        h5::set_attribute(g, "wall_seconds", wall_seconds);
      }
      {
        h5::Handle g = h5::create_group(f, "writer");
        h5::set_attribute(g, "frames", writer.frames);
        set_count_list(g, "probe_rows", writer.probe_rows);
        set_count_list(g, "csv_bytes", writer.csv_bytes);
        h5::set_attribute(g, "conservation_rows", static_cast<long>(writer.conservation_rows));
      }
      {
        h5::Handle g = h5::create_group(f, "probes");
        const auto& probes = sim.probes();
        h5::set_attribute(g, "count", static_cast<long>(probes.size()));
        for (std::size_t k = 0; k < probes.size(); ++k) {
          const ProbeState s = probes[k]->state();
          const std::string name = std::to_string(k);
          h5::write_dataset(g, name, s.data.data(), s.data.size(), 1);
          h5::Handle set(H5Dopen2(g, name.c_str(), H5P_DEFAULT), "opening probe state " + name);
          h5::set_attribute(set, "next_time", s.next_time);
          h5::set_attribute(set, "name", probes[k]->name());
        }
      }
      {
        h5::Handle g = h5::create_group(f, "particles");
        h5::set_attribute(g, "count", static_cast<long>(sim.particles().size()));
        write_particles(g, sim.particles());
      }
      h5::flush(f, tmp);
    }
    room.release();
    sync_file(tmp);
    std::filesystem::rename(tmp, path);
  } catch (const std::exception& e) {
    // No half checkpoint is left: the last whole one, if any, stays the one to resume from.
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    const std::string what = e.what();
    const auto* full = dynamic_cast<const OutOfSpaceError*>(&e);
    if (what.rfind(path, 0) == 0) throw;
    if (full) throw OutOfSpaceError(path + ": " + what, full->clean());
    throw IoError(path + ": " + what);
  }
}

Checkpoint read_checkpoint(const std::string& path) {
  if (!std::filesystem::exists(path)) throw IoError(path + ": no such file");
  h5::Handle f = h5::open_file(path);
  try {
    if (!h5::has_attribute(f, "format") || h5::get_string_attribute(f, "format") != "bsmpm-checkpoint")
      throw IoError("not a bsmpm checkpoint (no attribute format = \"bsmpm-checkpoint\" on '/')");
    if (h5::get_long_attribute(f, "format_version") != kFormatVersion)
      throw IoError("checkpoint format version " + std::to_string(h5::get_long_attribute(f, "format_version")) +
                    " is not supported (expected " + std::to_string(kFormatVersion) + ")");
    Checkpoint c;
    c.program_version = h5::get_string_attribute(f, "program_version");
    c.git_revision = h5::get_string_attribute(f, "git_revision");
    {
      h5::Handle g = h5::open_group(f, "scene");
      c.scene.path = h5::get_string_attribute(g, "path");
      c.scene.text = h5::get_string_attribute(g, "text");
      c.scene.command_line = h5::get_string_attribute(g, "command_line");
      const long n = h5::get_long_attribute(g, "overrides");
      for (long k = 0; k < n; ++k) c.scene.overrides.push_back(h5::get_string_attribute(g, "override_" + std::to_string(k)));
    }
    {
      h5::Handle g = h5::open_group(f, "step");
      c.counters.time = h5::get_double_attribute(g, "time");
      c.counters.step = h5::get_long_attribute(g, "step");
      c.counters.max_signal_speed = h5::get_double_attribute(g, "max_signal_speed");
      c.counters.stats.clamped_positions = h5::get_long_attribute(g, "clamped_positions");
      c.counters.stats.work = read_work(g, "work_");
      if (h5::has_attribute(g, "pressure_solves")) {  // written since the incompressible fluid
        c.counters.stats.pressure.solves = h5::get_long_attribute(g, "pressure_solves");
        c.counters.stats.pressure.iterations = h5::get_long_attribute(g, "pressure_iterations");
        c.counters.stats.pressure.max_iterations = static_cast<int>(h5::get_long_attribute(g, "pressure_max_iterations"));
        c.counters.stats.pressure.max_residual = h5::get_double_attribute(g, "pressure_max_residual");
      }
      if (H5Lexists(g, "effect_state", H5P_DEFAULT) > 0) c.counters.effect_state = h5::read_doubles(g, "effect_state");
    }
    {
      h5::Handle g = h5::open_group(f, "run_loop");
      c.loop.started = true;
      c.loop.next_frame = h5::get_long_attribute(g, "next_frame");
      c.loop.steps = h5::get_long_attribute(g, "steps");
      c.loop.min_dt = h5::get_double_attribute(g, "min_dt");
      c.loop.max_dt = h5::get_double_attribute(g, "max_dt");
      c.loop.last_dt = h5::get_double_attribute(g, "last_dt");
      c.wall_seconds = h5::get_double_attribute(g, "wall_seconds");
    }
    {
      h5::Handle g = h5::open_group(f, "writer");
      c.writer.frames = h5::get_long_attribute(g, "frames");
      c.writer.probe_rows = get_count_list(g, "probe_rows");
      c.writer.csv_bytes = get_count_list(g, "csv_bytes");
      c.writer.conservation_rows = static_cast<std::uint64_t>(h5::get_long_attribute(g, "conservation_rows"));
    }
    {
      h5::Handle g = h5::open_group(f, "probes");
      const long n = h5::get_long_attribute(g, "count");
      for (long k = 0; k < n; ++k) {
        const std::string name = std::to_string(k);
        ProbeState s;
        s.data = h5::read_doubles(g, name);
        h5::Handle set(H5Dopen2(g, name.c_str(), H5P_DEFAULT), "opening probe state " + name);
        s.next_time = h5::get_double_attribute(set, "next_time");
        c.probes.push_back(std::move(s));
      }
    }
    {
      h5::Handle g = h5::open_group(f, "particles");
      const long n = h5::get_long_attribute(g, "count");
      if (n < 0 || n > std::numeric_limits<std::uint32_t>::max()) throw IoError("invalid particle count");
      c.particles = read_particles(g, static_cast<std::size_t>(n));
    }
    return c;
  } catch (const IoError& e) {
    const std::string what = e.what();
    if (what.rfind(path, 0) == 0) throw;
    throw IoError(path + ": " + what);
  }
}

}  // namespace bsmpm
