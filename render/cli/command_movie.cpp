// bsmpm movie RUN.h5 --out FILE.mp4: the run as an H.264 movie, in slow motion.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/interruption.hpp"
#include "cli/progress.hpp"
#include "cli/render_arguments.hpp"
#include "core/error.hpp"
#include "compose/figure_renderer.hpp"
#include "compose/run_figures.hpp"
#include "io/run_reader.hpp"
#include "movie/movie_writer.hpp"

namespace bsmpm::cli {

namespace {

const std::string kHelp = std::string(
    "usage: bsmpm movie RUN.h5 --out FILE.mp4 [options]\n"
    "\n"
    "Renders every frame of a run off screen and encodes an H.264 movie (MP4, yuv420p,\n"
    "BT.709, index at the front): it plays in presentation software and browsers. Colours\n"
    "and colour bars are as in bsmpm render, with ranges fixed for the whole movie.\n"
    "\n"
    "timing\n"
    "  --fps N                movie frames per second, 1..240 [30]\n"
    "  --slowmo F             movie seconds per simulated second [10]: a 1.05 s run lasts\n"
    "                         10.5 s; each movie frame shows the latest run frame at its time\n") +
    kPictureHelp +
    "                         (a movie needs even sides: odd ones are rounded down)\n"
    "  --quiet                no progress on stderr\n"
    "\n"
    "The movie appears complete or not at all (written under a temporary name, then renamed);\n"
    "Ctrl-C stops without one.\n"
    "exit status: 0 done, 2 bad usage or unreadable run file, 130 interrupted (143 by SIGTERM),\n"
    "1 other failure\n";

// Run frame shown by each movie frame: movie time k / fps is simulated time
// t0 + k / (fps slowmo); the frame shown is the last one at or before it.
std::vector<int> movie_schedule(const RunReader& run, int fps, double slowmo) {
  const auto& frames = run.frames();
  const double t0 = frames.front().time, t1 = frames.back().time;
  const double per_movie_frame = 1.0 / (fps * slowmo);
  // A hair of slack so that frames written exactly on the schedule are not skipped.
  const double slack = 1e-6 * per_movie_frame;
  const long count = static_cast<long>(std::floor((t1 - t0) / per_movie_frame + 1e-6)) + 1;
  if (count > 200000) throw UsageError("the movie would have " + std::to_string(count) + " frames: lower --slowmo or --fps");
  std::vector<int> schedule;
  std::size_t shown = 0;
  for (long k = 0; k < count; ++k) {
    const double t = t0 + k * per_movie_frame;
    while (shown + 1 < frames.size() && frames[shown + 1].time <= t + slack) ++shown;
    schedule.push_back(static_cast<int>(shown));
  }
  return schedule;
}

}  // namespace

int command_movie(const std::vector<std::string>& argv) {
  std::set<std::string> options = picture_options();
  options.insert({"--out", "--fps", "--slowmo"});
  Arguments args(argv, {"--help", "--quiet"}, options);
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 1) throw UsageError("movie expects one run file (see bsmpm movie --help)");
  if (!args.has("--out")) throw UsageError("movie needs --out FILE.mp4 (see bsmpm movie --help)");
  const std::string out = args.option("--out");
  if (std::filesystem::path(out).extension() != ".mp4") throw UsageError("--out must name an .mp4 file");
  check_output_file(out);
  const bool quiet = args.flag("--quiet");
  render::RenderOptions cli_options = render_options_from(args);
  if (args.has("--fps")) {
    const long fps = args.integer("--fps", render::kDefaultFps);
    if (fps < 1 || fps > render::kMaxFps) throw UsageError("--fps expects 1..240");
    cli_options.fps = static_cast<int>(fps);
  }
  if (args.has("--slowmo")) {
    const double s = args.number("--slowmo", render::kDefaultSlowmo);
    if (!(s > 0.0 && s <= 1e6)) throw UsageError("--slowmo expects a number > 0");
    cli_options.slowmo = s;
  }

  const RunReader run = open_input_run(args);
  render::FigureRenderer renderer(font_path_from(args));
  const render::RunFigures figures(run, cli_options);
  if (run.frames().empty()) throw UsageError(run.path() + ": the run has no frames yet");
  const int fps = figures.options().fps.value_or(render::kDefaultFps);
  const double slowmo = figures.options().slowmo.value_or(render::kDefaultSlowmo);
  const std::vector<int> schedule = movie_schedule(run, fps, slowmo);

  render::MovieSettings settings;
  settings.fps = fps;
  const int width = figures.options().width.value_or(render::kDefaultWidth);
  const int height = figures.options().height.value_or(render::kDefaultHeight);
  settings.width = width - width % 2;
  settings.height = height - height % 2;
  if (settings.width != width || settings.height != height)
    std::fprintf(stderr, "bsmpm: note: %dx%d rounded down to %dx%d (4:2:0 video needs even sides)\n", width, height,
                 settings.width, settings.height);
  for (const auto& note : figures.range_notes()) std::printf("range    %s\n", note.c_str());

  const std::unique_ptr<render::MovieWriter> encoder = render::open_movie(out, settings);
  Progress progress("movie", static_cast<long>(schedule.size()), quiet);
  int rendered_frame = -1;
  render::Image image;
  long renders = 0;
  catch_interruptions();
  for (std::size_t k = 0; k < schedule.size(); ++k) {
    if (interrupted()) {
      progress.finish();
      std::fprintf(stderr, "bsmpm: interrupted; no movie written\n");
      return interrupted_exit_status();  // the encoder removes its temporary file
    }
    // A run frame held for several movie frames is drawn once.
    if (schedule[k] != rendered_frame) {
      const render::FrameParticles particles = figures.load(schedule[k]);
      render::FigureSpec spec = figures.single(particles);
      spec.width = settings.width;
      spec.height = settings.height;
      image = renderer.render(spec);
      rendered_frame = schedule[k];
      ++renders;
    }
    encoder->add_frame(image);
    progress.update(static_cast<long>(k + 1), figures.time_label(run.frames()[schedule[k]]));
  }
  encoder->finish();
  progress.finish();
  std::printf("wrote    %s (%dx%d, %zu frames at %d fps = %.2f s, %ld run frames, slow motion x%g)\n", out.c_str(),
              settings.width, settings.height, schedule.size(), fps, schedule.size() / double(fps), renders, slowmo);
  return kOk;
}

}  // namespace bsmpm::cli
