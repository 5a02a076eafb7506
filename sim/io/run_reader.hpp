// Reading run files (run.h5, layout in docs/output-format.md) back: frames, bodies, grid,
// reference scales, probes and provenance. The renderer reads frames only through this
// class. The constructor reads the small metadata once; frame fields are read on demand,
// one dataset at a time, so a renderer pays only for the fields it draws.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.hpp"
#include "io/hdf5.hpp"
#include "probes/probe.hpp"

namespace bsmpm {

struct RunFrameInfo {
  int index = 0;       // position in the frame list, 0 = first frame
  std::string group;   // "/frames/<group>", e.g. "000042"
  double time = 0.0;   // s
  long step = 0;
  double dt = 0.0;     // s, the step that led to this frame
};

struct RunBodyInfo {
  std::string name;
  std::string type;    // "fluid", "elastic" or "rigid"
  std::size_t first = 0, count = 0;  // particle id range [first, first + count)
  double density = 0.0;              // kg/m3
  Vec2 spacing = Vec2::Zero();       // initial particle spacing, m

  bool is_fluid() const { return type == "fluid"; }
  bool is_solid() const { return type == "elastic" || type == "rigid"; }
};

struct RunGridInfo {
  int order = 0;
  Vec2 origin = Vec2::Zero();
  Vec2 cell_size = Vec2::Zero();
  std::array<int, 2> cells{0, 0};
  Vec2 extent_max = Vec2::Zero();
};

struct RunProbeSeries {
  std::string name;
  std::string description;
  std::vector<std::string> columns;
  std::vector<std::string> units;  // per column ("s", "Pa", "1"); empty in files written before units
  std::size_t rows = 0;
  std::vector<double> values;  // row-major, rows x columns.size()
};

// In-plane Cauchy stress of one particle: xx, yy, xy [Pa].
using StressComponents = std::array<double, 3>;

class RunReader {
 public:
  // Opens a run file and reads its metadata; throws IoError naming `path` when the file is
  // missing, is not a bsmpm run, or lacks a part of the layout.
  explicit RunReader(const std::string& path);

  const std::string& path() const { return path_; }
  const std::string& title() const { return title_; }
  // "running", "completed", "interrupted" or "failed: ..." (read afresh each call: the
  // run may still be writing).
  std::string status() const;
  const std::string& effective_scene() const { return effective_scene_; }

  const std::vector<RunFrameInfo>& frames() const { return frames_; }
  const std::vector<RunBodyInfo>& bodies() const { return bodies_; }
  const RunGridInfo& grid() const { return grid_; }
  const ReferenceScales& reference() const { return reference_; }
  std::size_t particle_count() const { return particle_body_.size(); }
  // Body index of each particle, in id order (the row order of every frame dataset).
  const std::vector<BodyId>& particle_bodies() const { return particle_body_; }

  // Fields of frame `index` (0 .. frames().size() - 1), one entry per particle in id order.
  std::vector<Vec2> position(int index) const;
  std::vector<Vec2> velocity(int index) const;
  std::vector<Vec2> displacement(int index) const;  // position - reference position
  std::vector<double> pressure(int index) const;    // Pa
  std::vector<double> volume(int index) const;      // m2 per metre of depth
  std::vector<StressComponents> stress(int index) const;

  std::vector<std::string> probe_names() const;
  RunProbeSeries probe(const std::string& name) const;

 private:
  const RunFrameInfo& frame_info(int index) const;
  // The values of a frame field of io/particle_fields, checked against its component count.
  std::vector<double> read_frame_field(int index, std::string_view name) const;
  std::vector<Vec2> read_frame_vectors(int index, std::string_view name) const;

  std::string path_;
  h5::Handle file_;
  std::string title_;
  std::string effective_scene_;
  std::vector<RunFrameInfo> frames_;
  std::vector<RunBodyInfo> bodies_;
  RunGridInfo grid_;
  ReferenceScales reference_;
  std::vector<BodyId> particle_body_;
};

}  // namespace bsmpm
