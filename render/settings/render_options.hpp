// How to render a run: image size, view window, colour maps and ranges, splat size,
// colour-bar placement, movie timing. Each source (the scene's [render] table stored in the
// run file, the command line) gives a partial RenderOptions; later sources override
// earlier ones key by key, and the commands fill in what none of them set.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "color/color_map.hpp"
#include "figure/figure_spec.hpp"
#include "image/rect.hpp"
#include "scene/scene_loader.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm::render {

struct RenderOptions {
  std::optional<int> width, height;                 // pixels
  std::optional<std::string> field;                 // water: pressure, pstar, velocity
  std::optional<std::string> colormap;              // water
  std::optional<std::string> solid_colormap;        // solids
  std::optional<WorldRect> view;                    // m
  std::map<std::string, ValueRange> ranges;         // by field key, incl. "displacement"; SI
  std::optional<ValueRange> water_range;            // of whichever water field is drawn (--range)
  std::optional<ValueRange> solid_range;            // of the displacement (--solid-range)
  std::optional<double> splat_scale;                // reach past the outermost particles / (sqrt(volume) / 2)
  std::optional<ColorBarPlacement> colorbar;
  std::optional<int> fps;                           // movie frames per second
  std::optional<double> slowmo;                     // movie seconds per simulated second

  // Every option `later` sets replaces this one's; ranges merge field by field.
  void override_with(const RenderOptions& later);
};

// Defaults of what nothing set, and their limits (shared by the scene table and the CLI).
inline constexpr int kMinImageSide = 16, kMaxImageSide = 8192;
// Splat scale 1: the material ends half a spacing beyond its outermost particles, where the
// edge of a block seeded at cell centres lies.
inline constexpr double kDefaultSplatScale = 1.0, kMinSplatScale = 0.5, kMaxSplatScale = 4.0;
inline constexpr int kDefaultFps = 30, kMaxFps = 240;
inline constexpr double kDefaultSlowmo = 10.0;

// Reads and validates a [render] table: every key typed and range-checked, unknown keys
// rejected (finish()), errors as file:line:column: render.key: message (SceneError).
RenderOptions read_render_table(TableReader& table);

// The SceneExtension hook for load_scene: validates [render] when a scene loads.
void validate_render_table(TableReader& table);
SceneExtension render_scene_extension();

// The [render] table of a scene's text (a run's /provenance effective_scene), or nothing
// set when it has none. `source` names the text in error messages.
RenderOptions render_options_from_scene(const std::string& scene_text, const std::string& source);

ColorBarPlacement color_bar_placement_named(const std::string& name);  // auto, right, bottom

}  // namespace bsmpm::render
