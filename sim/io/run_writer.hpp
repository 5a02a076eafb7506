// Writes a run: one HDF5 file (frames, probe series, conservation series, provenance; layout
// in docs/output-format.md), an XDMF sidecar so ParaView opens the frames, one CSV per probe
// and conservation.csv. Everything is flushed after each frame, so a crash or Ctrl-C keeps
// what was written; the room on the disk for the next frame is taken before it is written,
// so a full disk stops the run with every file whole; a resumed run reopens the files and
// cuts them back to its checkpoint.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/hdf5.hpp"
#include "io/output_space.hpp"
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
  // Creates DIR/run.h5, DIR/run.xdmf and DIR/<probe>.csv; DIR must exist. Throws
  // OutOfSpaceError when the disk cannot hold the run's header and its first frame.
  RunWriter(const std::string& directory, const RunProvenance& provenance, const Simulation& sim);
  // Reopens the run in DIR where a checkpoint left it: frames, probe rows, conservation rows
  // and CSV lines written after it are removed, and the run is "running" again.
  RunWriter(const std::string& directory, const RunWriterState& at, Vec2 gravity, const Simulation& sim);
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  // Makes sure the disk holds what the run writes until the end of its next step: the next
  // frame, the probe rows sampled since the last frame and those of one more step, and what
  // finish() adds. Called before the first frame and after every step; throws
  // OutOfSpaceError (clean: nothing is half-written) when there is no room, so that the run
  // stops between two steps with every file whole (io/output_space.hpp).
  void keep_room(const Simulation& sim);
  // Writes the probe rows sampled so far and gives back the room kept beyond what finish()
  // needs: a run that stops for lack of room leaves the rest to its checkpoint.
  void shrink_room(const Simulation& sim);

  // Appends the current state as a frame, plus the probe rows sampled since the last call.
  void write_frame(const Simulation& sim, double dt);
  // Marks the run "completed", "interrupted" or "failed: ..." and flushes; a run that did not
  // complete also gets a last comment line in each CSV file saying where and why it stopped.
  void finish(const std::string& status, const Simulation& sim, double dt);

  // Flushes everything and tells how far the files reach (for a checkpoint).
  RunWriterState state(const Simulation& sim);

  int frames_written() const { return static_cast<int>(frame_times_.size()); }
  double last_frame_time() const { return frame_times_.empty() ? 0.0 : frame_times_.back(); }
  const std::string& h5_path() const { return h5_path_; }

 private:
  struct CloseFile {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  // A CSV file, written through stdio, with the room kept beyond its end.
  struct Csv {
    std::string path;
    std::unique_ptr<std::FILE, CloseFile> file;  // closed even if the constructor throws
    FileRoom room;
    void write(const std::string& text);  // throws naming the file
  };

  void flush_probes(const Simulation& sim);
  std::vector<Csv*> all_csv();  // the probes' and conservation.csv
  void write_conservation(const Simulation& sim);
  Csv create_csv(const std::string& path, const std::string& comment, const std::vector<std::string>& columns);
  void write_xdmf() const;

  std::string directory_, h5_path_, xdmf_path_;
  h5::Handle file_, frames_;
  FileRoom h5_room_;
  std::vector<h5::RowAppender> probe_sets_;
  std::vector<Csv> probe_csv_;
  h5::RowAppender conservation_set_;
  Csv conservation_csv_;
  Vec2 gravity_ = Vec2::Zero();
  std::vector<std::size_t> probe_rows_done_;
  std::vector<std::size_t> rows_covered_;  // probe rows the room kept covers, until the next write
  bool room_stale_ = true;                 // written since the room was last kept
  std::uint64_t frame_bytes_ = 0;          // the particle fields of one frame
  std::vector<double> frame_times_;
  std::vector<std::string> frame_names_;
  std::vector<double> frame_buffer_;  // the values of one frame dataset
  std::size_t particle_count_ = 0;
  long last_frame_step_ = -1;
};

}  // namespace bsmpm
