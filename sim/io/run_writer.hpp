// Writes a run: one HDF5 file (frames, probe series, conservation series, provenance; layout
// in docs/output-format.md), an XDMF sidecar so ParaView opens the frames, one CSV per probe
// and conservation.csv. Everything is flushed after each frame, so a crash or Ctrl-C keeps
// what was written; a resumed run reopens the files and cuts them back to its checkpoint.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/hdf5.hpp"
#include "probes/probe.hpp"
#include "step/simulation.hpp"

namespace bsmpm {

struct RunProvenance {
  std::string title;
  std::string scene_path;
  std::string scene_text;       // the file as read
  std::string effective_scene;  // after --set overrides
  std::string command_line;
  int threads = 1;
  double end_time = 0.0;
  ReferenceScales reference;
  Vec2 gravity = Vec2::Zero();  // for the gravitational energy of the conservation series
};

class RunWriter {
 public:
  // Creates DIR/run.h5, DIR/run.xdmf and DIR/<probe>.csv; DIR must exist.
  RunWriter(const std::string& directory, const RunProvenance& provenance, const Simulation& sim);
  // Reopens the run in DIR where a checkpoint left it: frames, probe rows, conservation rows
  // and CSV lines written after it are removed, and the run is "running" again.
  RunWriter(const std::string& directory, const RunWriterState& at, Vec2 gravity, const Simulation& sim);
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  // Appends the current state as a frame, plus the probe rows sampled since the last call.
  void write_frame(const Simulation& sim, double dt);
  // Marks the run "completed", "interrupted" or "failed: ..." and flushes.
  void finish(const std::string& status, const Simulation& sim, double dt);

  // Flushes everything and tells how far the files reach (for a checkpoint).
  RunWriterState state(const Simulation& sim);

  int frames_written() const { return static_cast<int>(frame_times_.size()); }
  const std::string& h5_path() const { return h5_path_; }

 private:
  void flush_probes(const Simulation& sim);
  void write_conservation(const Simulation& sim);
  void open_csv(const std::string& path, const std::string& comment, const std::vector<std::string>& columns);
  void write_xdmf() const;

  std::string directory_, h5_path_, xdmf_path_;
  h5::Handle file_, frames_;
  std::vector<h5::RowAppender> probe_sets_;
  struct CloseFile {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::vector<std::unique_ptr<std::FILE, CloseFile>> probe_csv_;  // closed even if the constructor throws
  h5::RowAppender conservation_set_;
  std::unique_ptr<std::FILE, CloseFile> conservation_csv_;
  Vec2 gravity_ = Vec2::Zero();
  std::vector<std::size_t> probe_rows_done_;
  std::vector<double> frame_times_;
  std::vector<std::string> frame_names_;
  std::vector<double> frame_buffer_;  // the values of one frame dataset
  std::size_t particle_count_ = 0;
  long last_frame_step_ = -1;
};

}  // namespace bsmpm
