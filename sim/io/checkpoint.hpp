// Checkpoints: everything a step depends on, so that `bsmpm run --resume DIR` continues a run
// bit for bit (docs/output-format.md, "checkpoint.h5"). The particles are every field of
// io/particle_fields marked as state, in slot order (the order the step keeps them in
// between two sorts by cell, so the next sort gives the same order); then the counters of
// the step, the run loop and the probes, the state of the run writer (how much of run.h5
// and the CSVs belongs to the run up to here), and the scene as given (text and --set
// overrides) so that the same simulation is built again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particles/particles.hpp"
#include "probes/probe.hpp"
#include "step/run_loop.hpp"
#include "step/simulation.hpp"

namespace bsmpm {

// The scene a run was started from.
struct CheckpointScene {
  std::string path;
  std::string text;                    // the file as read
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
  std::string command_line;
};

// How far the run's files reach at the checkpoint: a resumed run cuts them back to this.
struct RunWriterState {
  long frames = 0;                      // /frames/000000 .. frames - 1
  std::vector<std::uint64_t> probe_rows;  // per probe, rows in run.h5 (and in its CSV)
  std::uint64_t conservation_rows = 0;
  std::vector<std::uint64_t> csv_bytes;  // per probe CSV, then conservation.csv
};

struct Checkpoint {
  CheckpointScene scene;
  std::string program_version, git_revision;
  StepCounters counters;
  RunLoopState loop;
  RunWriterState writer;
  double wall_seconds = 0.0;  // spent by the run up to here, all sessions
  std::vector<ProbeState> probes;
  Particles particles;  // slot order
};

// Writes `path` whole or not at all (a temporary file, synced, then renamed).
void write_checkpoint(const std::string& path, const CheckpointScene& scene, const Simulation& sim,
                      const RunLoopState& loop, const RunWriterState& writer, double wall_seconds);

// Reads a checkpoint; throws IoError naming the file when it is not one or lacks a field.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace bsmpm
