#include "cli/render_arguments.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "figure/field.hpp"
#include "text/font.hpp"

namespace fs = std::filesystem;

namespace bsmpm::cli {

using render::RenderOptions;

const std::set<std::string>& picture_options() {
  static const std::set<std::string> options = {"--field",         "--range",   "--solid-range", "--colormap",
                                                "--solid-colormap", "--size",    "--view",        "--splat-scale",
                                                "--colorbar",       "--font"};
  return options;
}

const char* kPictureHelp =
    "picture (each defaults to the run scene's [render] table, then to the value shown)\n"
    "  --field NAME           water colour: pressure [kPa], pstar (P* = P/(rho g H), with\n"
    "                         the run's reference scales) or velocity (speed, m/s) [pressure]\n"
    "  --range MIN,MAX        colour range of the water field in SI units (Pa, -, m/s)\n"
    "                         [from a first pass over the run: 0.5th-99.5th percentile, 0 included]\n"
    "  --solid-range MIN,MAX  colour range of the solids' displacement, m [0 .. largest in the run]\n"
    "  --colormap NAME        water colour map: viridis, inferno or jet (the paper's) [viridis]\n"
    "  --solid-colormap NAME  solid colour map [inferno]\n"
    "  --size WxH             image size in pixels; W alone keeps the default height [1280x720]\n"
    "  --view X0,Y0,X1,Y1     world window in m [the tank]\n"
    "  --splat-scale S        how far the material is drawn past its outermost particles, in\n"
    "                         half spacings (sqrt(particle volume) / 2), 0.5..4 [1]\n"
    "  --colorbar WHERE       auto, right or bottom [auto: whichever leaves the plot larger]\n"
    "  --font FILE.ttf        label font [/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf]\n";

std::vector<double> parse_numbers(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument("trailing");
      out.push_back(v);
    } catch (const std::exception&) {
      throw UsageError(option + " expects comma-separated numbers, got '" + text + "'");
    }
  }
  if (out.empty()) throw UsageError(option + " expects comma-separated numbers, got '" + text + "'");
  return out;
}

namespace {

render::ValueRange parse_range(const std::string& option, const std::string& text) {
  const auto v = parse_numbers(option, text);
  if (v.size() != 2 || !(v[1] > v[0])) throw UsageError(option + " expects MIN,MAX with MAX > MIN, got '" + text + "'");
  return {v[0], v[1]};
}

int parse_side(const std::string& text, const std::string& whole) {
  try {
    std::size_t used = 0;
    const long v = std::stol(text, &used);
    if (used == text.size() && v >= render::kMinImageSide && v <= render::kMaxImageSide) return static_cast<int>(v);
  } catch (const std::exception&) {
  }
  throw UsageError("--size expects WxH (or W) with sides of " + std::to_string(render::kMinImageSide) + ".." +
                   std::to_string(render::kMaxImageSide) + " pixels, got '" + whole + "'");
}

}  // namespace

RenderOptions render_options_from(const Arguments& args) {
  RenderOptions o;
  if (args.has("--field")) {
    render::water_field_named(args.option("--field"));  // rejects an unknown name now
    o.field = args.option("--field");
  }
  if (args.has("--range")) o.water_range = parse_range("--range", args.option("--range"));
  if (args.has("--solid-range")) o.solid_range = parse_range("--solid-range", args.option("--solid-range"));
  if (args.has("--colormap")) o.colormap = render::ColorMap::named(args.option("--colormap")).name();
  if (args.has("--solid-colormap")) o.solid_colormap = render::ColorMap::named(args.option("--solid-colormap")).name();
  if (args.has("--size")) {
    const std::string s = args.option("--size");
    const auto x = s.find('x');
    o.width = parse_side(s.substr(0, x), s);
    if (x != std::string::npos) o.height = parse_side(s.substr(x + 1), s);
  }
  if (args.has("--view")) {
    const auto v = parse_numbers("--view", args.option("--view"));
    if (v.size() != 4 || !(v[2] > v[0]) || !(v[3] > v[1]))
      throw UsageError("--view expects X0,Y0,X1,Y1 with X1 > X0 and Y1 > Y0, got '" + args.option("--view") + "'");
    o.view = render::WorldRect{Vec2(v[0], v[1]), Vec2(v[2], v[3])};
  }
  if (args.has("--splat-scale")) {
    const double s = args.number("--splat-scale", render::kDefaultSplatScale);
    if (!(s >= render::kMinSplatScale && s <= render::kMaxSplatScale)) throw UsageError("--splat-scale expects 0.5..4");
    o.splat_scale = s;
  }
  if (args.has("--colorbar")) o.colorbar = render::color_bar_placement_named(args.option("--colorbar"));
  return o;
}

render::FrameSelection frame_selection_from(const Arguments& args) {
  using Kind = render::FrameSelection::Kind;
  render::FrameSelection s;
  int given = 0;
  for (const auto& [option, kind] : {std::pair{"--frames", Kind::kIndices}, std::pair{"--times", Kind::kTimes},
                                     std::pair{"--times-star", Kind::kTimesStar}})
    if (args.has(option)) {
      ++given;
      s.kind = kind;
      s.values = parse_numbers(option, args.option(option));
    }
  if (given > 1) throw UsageError("give one of --frames, --times and --times-star");
  return s;
}

RunReader open_input_run(const Arguments& args) {
  return RunReader(args.positional()[0]);  // an InputError (exit 2) when it cannot be read
}

void check_output_file(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) throw UsageError("--out " + path + " is a directory");
  if (p.has_parent_path() && !fs::is_directory(p.parent_path()))
    throw UsageError("--out " + path + ": the directory " + p.parent_path().string() + " does not exist");
}

std::string font_path_from(const Arguments& args) { return args.option("--font", render::kDefaultFontPath); }

}  // namespace bsmpm::cli
