// Figures of one run: the run's [render] table (from its effective scene) overridden by
// the command line, defaults for the rest, colour ranges fixed for the whole run, and the
// FigureSpec of a single frame or of a grid of frames.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "figure/field.hpp"
#include "figure/figure_spec.hpp"
#include "figure/frame_particles.hpp"
#include "io/run_reader.hpp"
#include "settings/render_options.hpp"
#include "text/font.hpp"

namespace bsmpm::render {

inline constexpr int kDefaultWidth = 1280, kDefaultHeight = 720;  // single frames, movies
inline constexpr int kDefaultGridWidth = 1920;                      // grid figures

class RunFigures {
 public:
  // Validates every option against the run (field, colour maps, ranges) before any frame
  // is read; ranges not given are found by a first pass over the run (scan_range).
  RunFigures(const RunReader& run, const RenderOptions& command_line);

  const RenderOptions& options() const { return options_; }
  Field water_field() const { return water_field_; }
  // One line per colour scale: what it shows, its range and where the range came from.
  const std::vector<std::string>& range_notes() const { return range_notes_; }

  FrameParticles load(int frame) const { return load_frame_particles(run_, frame, water_field_); }
  // "t = 0.30 s   T* = 1.72", with as many decimals as the frame spacing needs.
  std::string time_label(const RunFrameInfo& frame) const;

  // One frame, the time in the header; size from the options or 1280x720.
  FigureSpec single(const FrameParticles& frame) const;
  // Frames in a rows x cols grid, each labelled with its time, one set of colour bars;
  // size from the options, else 1920 wide and as tall as the panels need.
  FigureSpec grid(const std::vector<const FrameParticles*>& frames, int rows, int cols, Font& font) const;

 private:
  FigureSpec base() const;

  const RunReader& run_;
  RenderOptions options_;
  Field water_field_ = Field::kPressure;
  std::optional<ColorScale> water_, solids_;
  WorldRect domain_, view_;
  int time_decimals_ = 2;
  std::vector<std::string> range_notes_;
};

}  // namespace bsmpm::render
