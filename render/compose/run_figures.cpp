#include "compose/run_figures.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "figure/color_range.hpp"
#include "figure/figure_layout.hpp"

namespace bsmpm::render {

namespace {

std::string quantity_label(const FieldInfo& info) {
  return info.unit.empty() ? info.quantity : info.quantity + " [" + info.unit + "]";
}

std::string range_note(const std::string& subject, const FieldInfo& info, ValueRange r, const char* origin) {
  return format("%s %s: %.4g .. %.4g%s%s (%s)", subject.c_str(), info.key.c_str(), r.min * info.display_scale,
                r.max * info.display_scale, info.unit.empty() ? "" : " ", info.unit.c_str(), origin);
}

}  // namespace

RunFigures::RunFigures(const RunReader& run, const RenderOptions& command_line) : run_(run) {
  options_ = render_options_from_scene(run.effective_scene(), run.path() + ":/provenance/effective_scene");
  options_.override_with(command_line);
  water_field_ = water_field_named(options_.field.value_or("pressure"));
  const ColorMap water_map = ColorMap::named(options_.colormap.value_or("viridis"));
  const ColorMap solid_map = ColorMap::named(options_.solid_colormap.value_or("inferno"));

  domain_ = {run.grid().origin, run.grid().extent_max};
  view_ = options_.view.value_or(domain_);

  bool has_water = false, has_solids = false;
  for (const auto& b : run.bodies()) {
    has_water = has_water || (b.is_fluid() && b.count > 0);
    has_solids = has_solids || (b.is_solid() && b.count > 0);
  }
  auto scale_for = [&](const std::string& subject, Field field, ParticleKind kind, const ColorMap& map,
                       const std::optional<ValueRange>& given) {
    const FieldInfo& info = field_info(field);
    ValueRange range;
    const auto in_scene = options_.ranges.find(info.key);
    if (given) {
      range = *given;
      range_notes_.push_back(range_note(subject, info, range, "from the command line"));
    } else if (in_scene != options_.ranges.end()) {
      range = in_scene->second;
      range_notes_.push_back(range_note(subject, info, range, "from the scene's [render.ranges]"));
    } else {
      range = scan_range(run_, field, kind);
      const char* fix = kind == ParticleKind::kWater ? "scanned over the run; fix it with --range"
                                                     : "scanned over the run; fix it with --solid-range";
      range_notes_.push_back(range_note(subject, info, range, fix));
    }
    return ColorScale{subject, quantity_label(info), map, range, info.display_scale};
  };
  if (has_water) water_ = scale_for("water", water_field_, ParticleKind::kWater, water_map, options_.water_range);
  if (has_solids)
    solids_ = scale_for("solid", Field::kDisplacement, ParticleKind::kSolid, solid_map, options_.solid_range);

  const auto& frames = run.frames();
  if (frames.size() > 1) {
    const double spacing = (frames.back().time - frames.front().time) / (frames.size() - 1);
    if (spacing > 0) time_decimals_ = std::clamp(static_cast<int>(std::ceil(-std::log10(spacing) - 1e-9)), 1, 6);
  }
}

std::string RunFigures::time_label(const RunFrameInfo& frame) const {
  return format("t = %.*f s   T* = %.2f", time_decimals_, frame.time, frame.time * run_.reference().time_factor());
}

FigureSpec RunFigures::base() const {
  FigureSpec spec;
  spec.view = view_;
  spec.domain = domain_;
  spec.splat_scale = options_.splat_scale.value_or(kDefaultSplatScale);
  spec.placement = options_.colorbar.value_or(ColorBarPlacement::kAuto);
  spec.water = water_;
  spec.solids = solids_;
  return spec;
}

FigureSpec RunFigures::single(const FrameParticles& frame) const {
  FigureSpec spec = base();
  spec.width = options_.width.value_or(kDefaultWidth);
  spec.height = options_.height.value_or(kDefaultHeight);
  spec.header_left = time_label(frame.frame);
  spec.header_right = run_.title();
  spec.panels = {FigurePanel{&frame, ""}};
  return spec;
}

FigureSpec RunFigures::grid(const std::vector<const FrameParticles*>& frames, int rows, int cols, Font& font) const {
  if (rows < 1 || cols < 1) throw UsageError("a grid needs at least one row and one column");
  if (frames.size() > static_cast<std::size_t>(rows) * cols)
    throw UsageError(std::to_string(frames.size()) + " frames do not fit a " + std::to_string(rows) + "x" +
                     std::to_string(cols) + " grid");
  FigureSpec spec = base();
  spec.rows = rows;
  spec.cols = cols;
  spec.width = options_.width.value_or(kDefaultGridWidth);
  spec.header_left = run_.title();
  for (const FrameParticles* f : frames) spec.panels.push_back({f, time_label(f->frame)});
  if (options_.height) {
    spec.height = *options_.height;
  } else {
    spec.font_px = default_font_px(spec.width, spec.width * 9 / 16);
    if (spec.placement == ColorBarPlacement::kAuto) spec.placement = ColorBarPlacement::kBottom;
    spec.height = fitted_height(spec, font);
  }
  return spec;
}

}  // namespace bsmpm::render
