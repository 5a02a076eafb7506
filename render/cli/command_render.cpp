// bsmpm render RUN.h5 --out DIR|FILE.png: frames of a run as PNG images, off screen.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <future>
#include <optional>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/interruption.hpp"
#include "cli/progress.hpp"
#include "cli/render_arguments.hpp"
#include "core/error.hpp"
#include "compose/figure_renderer.hpp"
#include "compose/run_figures.hpp"
#include "image/png_file.hpp"
#include "io/run_reader.hpp"

namespace fs = std::filesystem;

namespace bsmpm::cli {

namespace {

const std::string kHelp = std::string(
    "usage: bsmpm render RUN.h5 --out DIR|FILE.png [options]\n"
    "\n"
    "Draws frames of a run as PNG images, off screen (OSMesa: no display, no GPU). Water\n"
    "particles are coloured by --field; solid bodies (elastic, rigid) by their displacement,\n"
    "drawn where their particles are now (deformed). Each has its own colour bar, with ranges\n"
    "fixed for the whole run. The header shows t and T* = t sqrt(g/H).\n"
    "\n"
    "output\n"
    "  --out DIR              one PNG per frame, DIR/<field>_<frame>.png (DIR is created)\n"
    "  --out FILE.png         one frame, or a --layout figure\n"
    "  --layout RxC           the selected frames in one image, R rows x C columns, sharing\n"
    "                         one set of colour bars (fig. 5 of the paper: --layout 2x3\n"
    "                         --times-star 1,2,3,4,5,6 --colormap jet --out fig5.png);\n"
    "                         without a height, 1920 wide and as tall as the panels need\n"
    "frames (default: all)\n"
    "  --frames LIST          frame indices, e.g. 0,10,20 (-1 is the last)\n"
    "  --times LIST           times t in s, e.g. 0.1,0.2: the nearest frames\n"
    "  --times-star LIST      non-dimensional times T*, e.g. 1,2,3: the nearest frames\n") +
    kPictureHelp +
    "  --quiet                no progress on stderr\n"
    "\n"
    "Images appear complete or not at all (written under a temporary name, then renamed);\n"
    "Ctrl-C stops after the current frame and keeps the images written so far.\n"
    "exit status: 0 done, 2 bad usage or unreadable run file, 130 interrupted (143 by SIGTERM),\n"
    "1 other failure\n";

std::pair<int, int> parse_layout(const std::string& text) {
  const auto x = text.find('x');
  try {
    std::size_t a = 0, b = 0;
    const int rows = std::stoi(text.substr(0, x), &a);
    const int cols = std::stoi(text.substr(x + 1), &b);
    if (x != std::string::npos && a == x && b == text.size() - x - 1 && rows >= 1 && cols >= 1 && rows * cols <= 64)
      return {rows, cols};
  } catch (const std::exception&) {
  }
  throw UsageError("--layout expects RxC, e.g. 2x3 (at most 64 panels), got '" + text + "'");
}

bool is_png_path(const std::string& path) { return fs::path(path).extension() == ".png"; }

// An --out that names an image of another kind: render writes PNG only, and a directory of
// that name (one PNG per frame inside) is not what was meant.
void refuse_other_image_types(const std::string& out) {
  std::string ext = fs::path(out).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* image : {".jpg", ".jpeg", ".gif", ".bmp", ".tif", ".tiff", ".webp", ".svg", ".pdf", ".eps", ".ppm"})
    if (ext == image)
      throw UsageError("--out " + out + ": render writes PNG images; give FILE.png for one image (or a --layout "
                       "figure), or a directory for one PNG per frame");
}

// The output directory; removed again if this command created it and wrote nothing into
// it (a failure or an interruption before the first image).
class OutputDirectory {
 public:
  explicit OutputDirectory(const fs::path& dir) : dir_(dir), created_(!fs::exists(dir)) {
    fs::create_directories(dir);
  }
  ~OutputDirectory() {
    std::error_code ignored;
    if (created_ && fs::is_empty(dir_, ignored)) fs::remove(dir_, ignored);
  }
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

 private:
  fs::path dir_;
  bool created_;
};

}  // namespace

int command_render(const std::vector<std::string>& argv) {
  std::set<std::string> options = picture_options();
  options.insert({"--out", "--layout", "--frames", "--times", "--times-star"});
  Arguments args(argv, {"--help", "--quiet"}, options);
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 1) throw UsageError("render expects one run file (see bsmpm render --help)");
  if (!args.has("--out")) throw UsageError("render needs --out DIR or --out FILE.png (see bsmpm render --help)");
  const std::string out = args.option("--out");
  const bool quiet = args.flag("--quiet");
  const bool layout = args.has("--layout");
  const auto [rows, cols] = layout ? parse_layout(args.option("--layout")) : std::pair{1, 1};
  refuse_other_image_types(out);
  if (layout && !is_png_path(out)) throw UsageError("--layout draws one image: give --out FILE.png");
  if (is_png_path(out)) check_output_file(out);
  else if (fs::exists(out) && !fs::is_directory(out)) throw UsageError("--out " + out + " exists and is not a directory");
  const render::RenderOptions cli_options = render_options_from(args);
  const render::FrameSelection selection = frame_selection_from(args);

  // Everything is checked before anything is written: a bad run file, field or frame list
  // leaves no output behind.
  const RunReader run = open_input_run(args);
  render::FigureRenderer renderer(font_path_from(args));
  const render::RunFigures figures(run, cli_options);
  const std::vector<int> frames = render::select_frames(run, selection);
  if (!layout && is_png_path(out) && frames.size() != 1)
    throw UsageError("--out " + out + " holds one image but " + std::to_string(frames.size()) +
                     " frames are selected: pick one (--frames, --times) or use --out DIR or --layout");
  for (const auto& note : figures.range_notes()) std::printf("range    %s\n", note.c_str());

  if (layout) {
    std::vector<render::FrameParticles> loaded;
    for (int f : frames) loaded.push_back(figures.load(f));
    std::vector<const render::FrameParticles*> panels;
    for (const auto& p : loaded) panels.push_back(&p);
    if (static_cast<int>(frames.size()) < rows * cols)
      std::fprintf(stderr, "bsmpm: warning: --layout %dx%d has %d panels for %zu frame%s: %d stay blank\n", rows, cols,
                   rows * cols, frames.size(), frames.size() == 1 ? "" : "s",
                   rows * cols - static_cast<int>(frames.size()));
    const render::FigureSpec spec = figures.grid(panels, rows, cols, renderer.font());
    render::write_png(renderer.render(spec), out);
    std::printf("wrote    %s (%dx%d, %zu frames in %dx%d)\n", out.c_str(), spec.width, spec.height, frames.size(), rows,
                cols);
    return kOk;
  }

  const bool single_file = is_png_path(out);
  std::optional<OutputDirectory> directory;
  if (!single_file) directory.emplace(out);
  const std::string field = figures.options().field.value_or("pressure");
  Progress progress("render", static_cast<long>(frames.size()), quiet);
  std::string first, last;
  int width = 0, height = 0;
  // PNG compression (zlib, one thread) costs about as much as drawing a frame; it runs on
  // a second thread while the next frame is drawn (GL stays on this thread).
  std::future<void> writing;
  catch_interruptions();
  std::size_t done = 0;
  for (std::size_t i = 0; i < frames.size() && !interrupted(); ++i) {
    const render::FrameParticles particles = figures.load(frames[i]);
    const render::FigureSpec spec = figures.single(particles);
    const std::string path =
        single_file ? out : (fs::path(out) / (field + "_" + particles.frame.group + ".png")).string();
    render::Image image = renderer.render(spec);
    if (writing.valid()) writing.get();  // rethrows a failed write
    writing = std::async(std::launch::async, [image = std::move(image), path] { render::write_png(image, path); });
    if (first.empty()) first = path;
    else last = path;
    width = spec.width;
    height = spec.height;
    progress.update(static_cast<long>(i + 1), figures.time_label(particles.frame));
    done = i + 1;
  }
  if (writing.valid()) writing.get();
  progress.finish();
  if (done > 0)
    std::printf("wrote    %s%s%s (%zu image%s, %dx%d)\n", first.c_str(), last.empty() ? "" : " .. ", last.c_str(), done,
                done == 1 ? "" : "s", width, height);
  if (interrupted()) {
    std::fprintf(stderr, "bsmpm: interrupted after %zu of %zu images\n", done, frames.size());
    return interrupted_exit_status();
  }
  return kOk;
}

}  // namespace bsmpm::cli
