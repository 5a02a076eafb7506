#include "io/run_writer.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/version.hpp"
#include "diagnostics/conservation.hpp"
#include "io/particle_datasets.hpp"

namespace bsmpm {

namespace {

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char s[32];
  std::strftime(s, sizeof s, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return s;
}

void write_body_attributes(hid_t g, const Body& b) {
  h5::set_attribute(g, "name", b.name);
  h5::set_attribute(g, "type", std::string(kind_name(b.material)));
  h5::set_attribute(g, "first", static_cast<long>(b.begin));
  h5::set_attribute(g, "count", static_cast<long>(b.size()));
  h5::set_attribute(g, "spacing", std::vector<double>{b.spacing.x(), b.spacing.y()});
  h5::set_attribute(g, "density", density_of(b.material));
  for (const MaterialAttribute& a : std::visit([](const auto& m) { return m.attributes(); }, b.material))
    std::visit([&](const auto& value) { h5::set_attribute(g, a.name.c_str(), value); }, a.value);
}

// What the room kept for the next writes adds to the particle fields and probe rows (measured
// with h5stat and the CSV files: a frame's group with its 3 attributes and 6 datasets holds
// about 4 KiB of metadata; status, steps and clamped_positions about 1 KiB).
constexpr std::uint64_t kFrameMetadataBytes = 16 * 1024;
constexpr std::uint64_t kFinishBytes = 16 * 1024;
constexpr std::uint64_t kCsvCharsPerValue = 18;  // "%.9g" and its comma; %.17g needs 25
constexpr std::uint64_t kCsvTrailerBytes = 1024;  // the comment line of a run that stopped
// Conservation rows come one a frame: small chunks, so that a short run's file is not mostly
// an empty chunk (1024 rows of 14 columns would be 112 KiB).
constexpr std::size_t kConservationChunkRows = 64;

// Bytes of one particle's values of every field with `use`, as stored.
std::uint64_t particle_bytes(unsigned use) {
  std::uint64_t bytes = 0;
  for (const ParticleField& f : particle_fields())
    if (f.use & use) bytes += field_value_bytes(f);
  return bytes;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t c = 0; c < items.size(); ++c) out += (c ? "," : "") + items[c];
  return out;
}

// The CSV header: each column's name and unit, "t [s]", a number without unit bare ("T*"):
// the name is what precedes " [" (docs/output-format.md).
std::vector<std::string> labelled(const std::vector<std::string>& columns, const std::vector<std::string>& units) {
  std::vector<std::string> out;
  for (std::size_t c = 0; c < columns.size(); ++c)
    out.push_back(units[c] == "1" ? columns[c] : columns[c] + " [" + units[c] + "]");
  return out;
}

// The field's dataset under `group`: one row per particle, in id order (the order of every
// frame); `buffer` is scratch space.
void write_particle_field(hid_t group, const ParticleField& field, const Simulation& sim, std::vector<double>& buffer) {
  write_particle_dataset(group, field, sim.particles(), &sim.index_of_id(), buffer);
}

}  // namespace

RunWriter::RunWriter(const std::string& directory, const RunProvenance& prov, const Simulation& sim)
    : directory_(directory), h5_path_(directory + "/run.h5"), xdmf_path_(directory + "/run.xdmf"),
      gravity_(prov.gravity) {
  file_ = h5::create_file(h5_path_);
  h5_room_ = FileRoom(h5_path_);
  particle_count_ = sim.particles().size();
  frame_bytes_ = particle_count_ * particle_bytes(kInFrames);
  h5_room_.keep(particle_count_ * particle_bytes(kInRunHeader) + 2 * prov.scene_text.size() +
                    prov.effective_scene.size() + 64 * 1024,
                "the run's header");
  h5::set_attribute(file_, "format", std::string("bsmpm-run"));
  h5::set_attribute(file_, "format_version", 1L);
  h5::set_attribute(file_, "program_version", std::string(kVersion));
  h5::set_attribute(file_, "git_revision", std::string(kGitRevision));
  h5::set_attribute(file_, "title", prov.title);
  h5::set_attribute(file_, "status", std::string("running"));
  h5::set_attribute(file_, "end_time", prov.end_time);
  {
    h5::Handle g = h5::create_group(file_, "provenance");
    h5::set_attribute(g, "scene_path", prov.scene_path);
    h5::set_attribute(g, "scene_text", prov.scene_text);
    h5::set_attribute(g, "effective_scene", prov.effective_scene);
    h5::set_attribute(g, "command_line", prov.command_line);
    h5::set_attribute(g, "threads", static_cast<long>(prov.threads));
    h5::set_attribute(g, "started_utc", utc_now());
  }
  {
    h5::Handle g = h5::create_group(file_, "reference");
    h5::set_attribute(g, "length", prov.reference.length);
    h5::set_attribute(g, "density", prov.reference.density);
    h5::set_attribute(g, "gravity", prov.reference.gravity);
  }
  {
    const GridInfo gi = sim.grid_info();
    h5::Handle g = h5::create_group(file_, "grid");
    h5::set_attribute(g, "order", static_cast<long>(gi.order));
    h5::set_attribute(g, "origin", std::vector<double>{gi.origin.x(), gi.origin.y()});
    h5::set_attribute(g, "cell_size", std::vector<double>{gi.cell_size.x(), gi.cell_size.y()});
    h5::set_attribute(g, "cells", std::vector<double>{double(gi.cells_x), double(gi.cells_y)});
    const Vec2 hi = gi.extent_max();
    h5::set_attribute(g, "extent_max", std::vector<double>{hi.x(), hi.y()});
  }
  {
    h5::Handle g = h5::create_group(file_, "bodies");
    const auto& bodies = sim.bodies();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      h5::Handle bg = h5::create_group(g, std::to_string(b));
      write_body_attributes(bg, bodies[b]);
    }
  }
  {
    h5::Handle g = h5::create_group(file_, "particles");
    std::vector<double> buffer;
    for (const ParticleField& field : particle_fields())
      if (field.has(kInRunHeader)) write_particle_field(g, field, sim, buffer);
  }
  frames_ = h5::create_group(file_, "frames");
  {
    h5::Handle g = h5::create_group(file_, "probes");
    for (const auto& probe : sim.probes()) {
      const auto cols = probe->columns();
      probe_sets_.emplace_back(g, probe->name(), cols.size());
      h5::Handle set(H5Dopen2(g, probe->name().c_str(), H5P_DEFAULT), "probe dataset");
      const auto units = probe->units();
      h5::set_attribute(set, "columns", joined(cols));
      h5::set_attribute(set, "units", joined(units));
      h5::set_attribute(set, "description", probe->describe());
      probe_csv_.push_back(
          create_csv(directory_ + "/" + probe->name() + ".csv", probe->describe(), labelled(cols, units)));
      probe_rows_done_.push_back(0);
    }
  }
  {
    const auto& cols = conservation_columns();
    conservation_set_ = h5::RowAppender(file_, "conservation", cols.size(), kConservationChunkRows);
    h5::Handle set(H5Dopen2(file_, "conservation", H5P_DEFAULT), "conservation dataset");
    h5::set_attribute(set, "columns", joined(cols));
    h5::set_attribute(set, "units", joined(conservation_units()));
    conservation_csv_ = create_csv(directory_ + "/conservation.csv",
                                   "mass, momentum, energy and work of the deformable bodies per frame "
                                   "(docs/output-format.md)",
                                   labelled(cols, conservation_units()));
  }
  rows_covered_.assign(probe_rows_done_.size(), 0);
  h5::flush(file_, h5_path_);
}

std::vector<RunWriter::Csv*> RunWriter::all_csv() {
  std::vector<Csv*> out;
  for (Csv& csv : probe_csv_) out.push_back(&csv);
  out.push_back(&conservation_csv_);
  return out;
}

void RunWriter::Csv::write(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), file.get()) != text.size() || std::fflush(file.get()) != 0) {
    const int error_number = errno;
    const std::string message = path + ": writing failed: " + std::strerror(error_number);
    if (is_out_of_space(error_number)) throw OutOfSpaceError(message, false);
    throw IoError(message);
  }
}

// A CSV with a comment line and a header row.
RunWriter::Csv RunWriter::create_csv(const std::string& path, const std::string& comment,
                                     const std::vector<std::string>& columns) {
  Csv csv{path, std::unique_ptr<std::FILE, CloseFile>(std::fopen(path.c_str(), "w")), FileRoom()};
  if (!csv.file) throw IoError(path + ": cannot create: " + std::strerror(errno));
  csv.room = FileRoom(path);
  csv.room.keep(comment.size() + 64 * columns.size() + kCsvTrailerBytes, "its header");
  csv.write("# " + comment + "\n" + joined(columns) + "\n");
  return csv;
}

namespace {

// The file cut to `bytes` and opened for appending.
std::FILE* reopen_cut(const std::string& path, std::uint64_t bytes) {
  std::error_code error;
  if (std::filesystem::file_size(path, error) < bytes || error)
    throw IoError(path + ": shorter than at the checkpoint (" + std::to_string(bytes) + " bytes)");
  std::filesystem::resize_file(path, bytes);
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) throw IoError(path + ": cannot open for appending");
  return f;
}

// "/frames/NNNNNN" names: the frame index they hold, or -1.
long frame_index(const std::string& name) {
  if (name.size() != 6 || name.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(name);
}

}  // namespace

RunWriter::RunWriter(const std::string& directory, const RunWriterState& at, Vec2 gravity, const Simulation& sim)
    : directory_(directory), h5_path_(directory + "/run.h5"), xdmf_path_(directory + "/run.xdmf"), gravity_(gravity) {
  file_ = h5::open_file(h5_path_, true);
  frames_ = h5::open_group(file_, "frames");
  particle_count_ = sim.particles().size();
  frame_bytes_ = particle_count_ * particle_bytes(kInFrames);
  // Frames after the checkpoint go; those before it stay, in order.
  for (const std::string& name : h5::children(frames_)) {
    const long index = frame_index(name);
    if (index < 0 || index >= at.frames) {
      h5::remove_link(frames_, name);
      continue;
    }
    h5::Handle g = h5::open_group(frames_, name);
    frame_names_.push_back(name);
    frame_times_.push_back(h5::get_double_attribute(g, "time"));
    last_frame_step_ = h5::get_long_attribute(g, "step");
  }
  if (static_cast<long>(frame_names_.size()) != at.frames)
    throw IoError(h5_path_ + ": holds " + std::to_string(frame_names_.size()) + " of the " + std::to_string(at.frames) +
                  " frames written before the checkpoint");
  const auto& probes = sim.probes();
  if (at.probe_rows.size() != probes.size() || at.csv_bytes.size() != probes.size() + 1)
    throw IoError(h5_path_ + ": the checkpoint does not match the scene's probes");
  h5::Handle g = h5::open_group(file_, "probes");
  for (std::size_t k = 0; k < probes.size(); ++k) {
    probe_sets_.push_back(h5::RowAppender::reopen(g, probes[k]->name(), at.probe_rows[k]));
    const std::string path = directory_ + "/" + probes[k]->name() + ".csv";
    probe_csv_.push_back(Csv{path, std::unique_ptr<std::FILE, CloseFile>(reopen_cut(path, at.csv_bytes[k])), FileRoom(path)});
    probe_rows_done_.push_back(at.probe_rows[k]);
  }
  rows_covered_.assign(probe_rows_done_.size(), 0);
  conservation_set_ = h5::RowAppender::reopen(file_, "conservation", at.conservation_rows);
  const std::string path = directory_ + "/conservation.csv";
  conservation_csv_ = Csv{path, std::unique_ptr<std::FILE, CloseFile>(reopen_cut(path, at.csv_bytes.back())), FileRoom(path)};
  h5_room_ = FileRoom(h5_path_);
  h5_room_.keep(kFinishBytes, "marking the run running again");
  h5::set_attribute(file_, "status", std::string("running"));
  h5::set_attribute(file_, "frames_written", static_cast<long>(frames_written()));
  h5::flush(file_, h5_path_);
  write_xdmf();
}

RunWriterState RunWriter::state(const Simulation& sim) {
  flush_probes(sim);
  h5::flush(file_, h5_path_);
  room_stale_ = true;
  RunWriterState s;
  s.frames = frames_written();
  auto bytes = [](const Csv& csv) {
    const long at = std::ftell(csv.file.get());
    if (at < 0) throw IoError(csv.path + ": cannot tell its length");
    return static_cast<std::uint64_t>(at);
  };
  for (std::size_t k = 0; k < probe_sets_.size(); ++k) {
    s.probe_rows.push_back(probe_rows_done_[k]);
    s.csv_bytes.push_back(bytes(probe_csv_[k]));
  }
  s.conservation_rows = conservation_set_.rows();
  s.csv_bytes.push_back(bytes(conservation_csv_));
  return s;
}

void RunWriter::shrink_room(const Simulation& sim) {
  flush_probes(sim);
  h5::flush(file_, h5_path_);
  room_stale_ = true;
  h5_room_.release();
  h5_room_.keep(kFinishBytes, "marking the run stopped");
  for (Csv* csv : all_csv()) {
    csv->room.release();
    csv->room.keep(kCsvTrailerBytes, "the line saying where the run stopped");
  }
}

void RunWriter::keep_room(const Simulation& sim) {
  const auto& probes = sim.probes();
  std::vector<std::size_t> pending(probes.size());
  bool covered = !room_stale_;
  for (std::size_t k = 0; k < probes.size(); ++k) {
    pending[k] = probes[k]->row_count() - probe_rows_done_[k] + 1;  // and one more step's
    covered = covered && pending[k] <= rows_covered_[k];
  }
  if (covered) return;  // nothing written since, and the probe rows within what is kept
  // Room for twice the probe rows pending: kept again about once a frame, not every step.
  std::uint64_t h5 = frame_bytes_ + kFrameMetadataBytes + kFinishBytes + conservation_set_.growth_bound(1);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    rows_covered_[k] = 2 * pending[k] + 16;
    h5 += probe_sets_[k].growth_bound(rows_covered_[k]);
  }
  h5_room_.keep(h5, "the next frame and the probe rows until then");
  for (std::size_t k = 0; k < probes.size(); ++k)
    probe_csv_[k].room.keep(rows_covered_[k] * (probe_sets_[k].cols() * kCsvCharsPerValue + 1) + kCsvTrailerBytes,
                            "the probe rows until the next frame");
  conservation_csv_.room.keep(conservation_set_.cols() * 25 + 1 + kCsvTrailerBytes, "the next frame's row");
  room_stale_ = false;
}

// One row of the conservation series per frame (docs/output-format.md).
void RunWriter::write_conservation(const Simulation& sim) {
  const std::vector<double> row = conservation_row(measure_conservation(sim, gravity_));
  conservation_set_.append(row.data(), 1);
  std::string line;
  for (std::size_t c = 0; c < row.size(); ++c) line += format("%s%.17g", c ? "," : "", row[c]);
  conservation_csv_.write(line + "\n");
}

void RunWriter::flush_probes(const Simulation& sim) {
  auto& probes = sim.probes();
  std::string text;
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const Probe& probe = *probes[k];
    const std::size_t done = probe_rows_done_[k], total = probe.row_count();
    if (total == done) continue;
    probe_sets_[k].append(probe.row(done), total - done);
    const std::size_t cols = probe.columns().size();
    text.clear();
    for (std::size_t r = done; r < total; ++r) {
      const double* row = probe.row(r);
      for (std::size_t c = 0; c < cols; ++c) text += format("%s%.9g", c ? "," : "", row[c]);
      text += "\n";
    }
    probe_csv_[k].write(text);
    probe_rows_done_[k] = total;
  }
}

void RunWriter::write_frame(const Simulation& sim, double dt) {
  if (sim.step_count() == last_frame_step_) return;  // this state is written already
  last_frame_step_ = sim.step_count();
  const std::string name = format("%06d", frames_written());
  h5::Handle g = h5::create_group(frames_, name);
  h5::set_attribute(g, "time", sim.time());
  h5::set_attribute(g, "step", sim.step_count());
  h5::set_attribute(g, "dt", dt);
  for (const ParticleField& field : particle_fields())
    if (field.has(kInFrames)) write_particle_field(g, field, sim, frame_buffer_);

  frame_times_.push_back(sim.time());
  frame_names_.push_back(name);
  write_conservation(sim);
  flush_probes(sim);
  h5::set_attribute(file_, "frames_written", static_cast<long>(frames_written()));
  h5::flush(file_, h5_path_);
  room_stale_ = true;
  write_xdmf();
}

void RunWriter::finish(const std::string& status, const Simulation& sim, double dt) {
  if (status == "completed") write_frame(sim, dt);
  flush_probes(sim);
  h5::set_attribute(file_, "status", status);
  h5::set_attribute(file_, "steps", sim.step_count());
  h5::set_attribute(file_, "clamped_positions", sim.stats().clamped_positions);
  h5::flush(file_, h5_path_);
  if (status != "completed") {
    // Where and why the rows end, for a reader of the CSV alone (a resumed run cuts it off).
    std::string why = status;
    for (char& c : why)
      if (c == '\n' || c == '\r') c = ' ';
    const std::string line = format("# the run stopped here, at t = %.9g s (step %ld, the last frame at t = %.9g s): %s\n",
                                    sim.time(), sim.step_count(), last_frame_time(), why.c_str());
    for (Csv* csv : all_csv()) csv->write(line);
  }
  h5_room_.release();
  for (Csv* csv : all_csv()) csv->room.release();
}

// XDMF 2 sidecar: a temporal collection of point clouds referencing run.h5. Rewritten
// whole after each frame through a temporary file, so it always parses.
void RunWriter::write_xdmf() const {
  const std::string tmp = xdmf_path_ + ".tmp";
  {
    std::ofstream x(tmp);
    const std::size_t n = particle_count_;
    x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
      << "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t f = 0; f < frame_names_.size(); ++f) {
      const std::string path = "run.h5:/frames/" + frame_names_[f] + "/";
      x << "   <Grid Name=\"frame " << frame_names_[f] << "\" GridType=\"Uniform\">\n"
        << "    <Time Value=\"" << frame_times_[f] << "\"/>\n"
        << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\"/>\n"
        << "    <Geometry GeometryType=\"XY\">\n";
      auto data_item = [&](const ParticleField& field) {
        x << "     <DataItem Dimensions=\"" << n;
        if (field.components > 1) x << " " << field.components;
        x << "\" " << xdmf_number_type(field) << " Format=\"HDF\">" << (field.has(kInFrames) ? path : std::string("run.h5:/particles/")) << field.name
          << "</DataItem>\n";
      };
      for (const ParticleField& field : particle_fields())
        if (field.has(kXdmfGeometry)) data_item(field);
      x << "    </Geometry>\n";
      for (const ParticleField& field : particle_fields()) {
        if (!field.has(kXdmfAttribute)) continue;
        if (field.components <= 2) {
          x << "    <Attribute Name=\"" << field.name << "\" AttributeType=\""
            << (field.components > 1 ? "Vector" : "Scalar") << "\" Center=\"Node\">\n";
          data_item(field);
          x << "    </Attribute>\n";
          continue;
        }
        // A tensor's components (the in-plane stress xx, yy, xy) as scalars of their own,
        // "stress_xx", ...: XDMF has no 2D symmetric tensor, and read as a Vector ParaView
        // would show its three components as x, y, z.
        const auto names = component_names(field);
        for (std::size_t c = 0; c < names.size(); ++c) {
          x << "    <Attribute Name=\"" << field.name << "_" << names[c] << "\" AttributeType=\"Scalar\" "
            << "Center=\"Node\">\n"
            << "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << " 1\" Type=\"HyperSlab\">\n"
            << "      <DataItem Dimensions=\"3 2\" Format=\"XML\">0 " << c << " 1 1 " << n << " 1</DataItem>\n"
            << " ";
          data_item(field);
          x << "     </DataItem>\n    </Attribute>\n";
        }
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n </Domain>\n</Xdmf>\n";
    if (!x) throw IoError(tmp + ": cannot write");
  }
  std::filesystem::rename(tmp, xdmf_path_);
}

}  // namespace bsmpm
