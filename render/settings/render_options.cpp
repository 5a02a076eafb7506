#include "settings/render_options.hpp"

#include "core/error.hpp"
#include "figure/field.hpp"

namespace bsmpm::render {

namespace {

const std::vector<std::string> kPlacements = {"auto", "right", "bottom"};
const std::vector<std::string> kRangeKeys = {"pressure", "pstar", "velocity", "displacement"};

ValueRange read_range(TableReader& t, const std::string& key) {
  const Vec2 v = t.vec2(key);
  if (!(v.y() > v.x())) t.fail(key, "expected [min, max] with max > min");
  return {v.x(), v.y()};
}

}  // namespace

namespace {
// Each member `later` sets replaces `mine`'s: every option named once.
template <class... Members>
void take_set(RenderOptions& mine, const RenderOptions& later, Members... members) {
  ((later.*members ? void(mine.*members = later.*members) : void()), ...);
}
}  // namespace

void RenderOptions::override_with(const RenderOptions& later) {
  using O = RenderOptions;
  take_set(*this, later, &O::width, &O::height, &O::field, &O::colormap, &O::solid_colormap, &O::view);
  for (const auto& [key, range] : later.ranges) ranges[key] = range;
  take_set(*this, later, &O::water_range, &O::solid_range, &O::splat_scale, &O::colorbar, &O::fps, &O::slowmo);
}

ColorBarPlacement color_bar_placement_named(const std::string& name) {
  if (name == "auto") return ColorBarPlacement::kAuto;
  if (name == "right") return ColorBarPlacement::kRight;
  if (name == "bottom") return ColorBarPlacement::kBottom;
  throw UsageError("unknown colour-bar placement '" + name + "' (known: auto, right, bottom)");
}

RenderOptions read_render_table(TableReader& t) {
  RenderOptions o;
  if (t.has("width")) o.width = static_cast<int>(t.integer("width", kMinImageSide, kMaxImageSide));
  if (t.has("height")) o.height = static_cast<int>(t.integer("height", kMinImageSide, kMaxImageSide));
  if (t.has("field")) o.field = t.choice("field", water_field_names());
  if (t.has("colormap")) o.colormap = t.choice("colormap", ColorMap::names());
  if (t.has("solid_colormap")) o.solid_colormap = t.choice("solid_colormap", ColorMap::names());
  if (t.has("splat_scale"))
    o.splat_scale = t.number("splat_scale", Range::closed(kMinSplatScale, kMaxSplatScale));
  if (t.has("colorbar")) o.colorbar = color_bar_placement_named(t.choice("colorbar", kPlacements));
  if (t.has("fps")) o.fps = static_cast<int>(t.integer("fps", 1, kMaxFps));
  if (t.has("slowmo")) o.slowmo = t.number("slowmo", Range{Bound::exclusive(0.0), Bound::inclusive(1e6)});
  if (auto view = t.optional_table("view")) {
    WorldRect r{view->vec2("min"), view->vec2("max")};
    if (!(r.max.x() > r.min.x() && r.max.y() > r.min.y())) view->fail("max", "must exceed view.min in both x and y");
    view->finish();
    o.view = r;
  }
  if (auto ranges = t.optional_table("ranges")) {
    for (const auto& key : kRangeKeys)
      if (ranges->has(key)) o.ranges[key] = read_range(*ranges, key);
    ranges->finish();
  }
  t.finish();
  return o;
}

void validate_render_table(TableReader& table) { read_render_table(table); }

SceneExtension render_scene_extension() { return SceneExtension{"render", validate_render_table}; }

RenderOptions render_options_from_scene(const std::string& scene_text, const std::string& source) {
  const toml::table root = parse_toml(scene_text, source);
  const toml::node* node = root.get("render");
  if (!node) return {};
  if (!node->is_table()) throw SceneError(location_of(*node), "render", "expected a table");
  TableReader table(*node->as_table(), "render", location_of(*node));
  return read_render_table(table);
}

}  // namespace bsmpm::render
