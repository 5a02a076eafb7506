// bsmpm metrics: the metrics of a finished run as a study defines them, or one probe's
// series through the sensor model, so that plots filter exactly as the metrics do.
#include <array>
#include <cmath>
#include <stdexcept>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "diagnostics/pressure_stripes.hpp"
#include "io/json.hpp"
#include "study/run_metrics.hpp"
#include "study/study_loader.hpp"
#include "study/study_plan.hpp"

namespace bsmpm::cli {

namespace fs = std::filesystem;

namespace {

const char* kHelp =
    "usage: bsmpm metrics RUN_DIR --study STUDY.toml [--json]\n"
    "       bsmpm metrics RUN_DIR --series PROBE [--column P*] [--raw] [--rate HZ] [--window S]\n"
    "       bsmpm metrics --series-file FILE --length H [--rate HZ] [--window S]\n"
    "       bsmpm metrics RUN_DIR --stripes Y0,Y1 [--x X0,X1] [--time A,B | --time-star A,B]\n"
    "                     [--radius CELLS]\n"
    "\n"
    "The first form extracts the [[metrics]] of a study from a finished run (RUN_DIR/run.h5 and\n"
    "RUN_DIR/summary.json) and prints them, or one JSON object with --json. The second prints a\n"
    "probe's column as CSV (t, T*, value) through the sensor model: resampled to --rate\n"
    "(default 20000 Hz) by time-weighted averaging, then a centred moving average of --window\n"
    "seconds (default 0.001; 0: none); --raw prints the samples as recorded. The third filters\n"
    "a measured series the same way: two columns T* and value (whitespace or commas, '#'\n"
    "comments), T* = t sqrt(g/H) with g = 9.81 m/s2 and H = --length [m].\n"
    "With --study, the study's [sensor] settings are the defaults. docs/studies.md.\n"
    "The fourth prints the stripe number of the pressure cloud in each frame of the window\n"
    "(all frames without one): the RMS over the fluid particles with Y0 <= y <= Y1 (and\n"
    "X0 <= x <= X1) [m] of their pressure minus the mean pressure of their fluid neighbours\n"
    "within --radius grid cells (default 2), over rho g H of the run's [reference]; CSV\n"
    "t, T*, stripes, particles, then a '#' line with the RMS over all those frames.\n"
    "docs/validation.md, \"Pressure stripes\".\n";

void print_series(const Series& s, double time_factor, const std::string& column) {
  std::printf("t,T*,%s\n", column.c_str());
  for (std::size_t k = 0; k < s.t.size(); ++k)
    std::printf("%s,%s,%s\n", json_number(s.t[k]).c_str(), json_number(s.t[k] * time_factor).c_str(),
                json_number(s.y[k]).c_str());
}

// Two numeric columns (T*, value); other lines are skipped only if they are comments.
Series read_measured_series(const std::string& path, double time_factor) {
  std::istringstream in(read_input_file(path, "the series file"));
  Series s;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream fields(line);
    double t_star = 0.0, y = 0.0;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    if (!(fields >> t_star >> y)) throw InputError(path + ":" + std::to_string(number) + ": expected two numbers");
    const double t = t_star / time_factor;
    if (!s.t.empty() && !(t > s.t.back())) continue;  // repeated times in digitised data
    s.t.push_back(t);
    s.y.push_back(y);
  }
  return s;
}

// "A,B" with A < B, for --stripes, --x, --time, --time-star.
std::array<double, 2> pair_option(const Arguments& args, const std::string& name) {
  const std::string v = args.option(name);
  const auto comma = v.find(',');
  try {
    if (comma == std::string::npos) throw std::invalid_argument(v);
    std::size_t used_a = 0, used_b = 0;
    const double a = std::stod(v.substr(0, comma), &used_a), b = std::stod(v.substr(comma + 1), &used_b);
    if (used_a != comma || used_b != v.size() - comma - 1 || !(b > a)) throw std::invalid_argument(v);
    return {a, b};
  } catch (const std::exception&) {
    throw UsageError(name + " expects two numbers A,B with A < B, got \"" + v + "\"");
  }
}

int print_stripes(const Arguments& args, const std::string& dir) {
  StripeBand band;
  const auto y = pair_option(args, "--stripes");
  band.y_min = y[0], band.y_max = y[1];
  if (args.has("--x")) {
    const auto x = pair_option(args, "--x");
    band.x_min = x[0], band.x_max = x[1];
  }
  if (args.has("--time") && args.has("--time-star")) throw UsageError("give --time or --time-star, not both");
  std::array<double, 2> window{-1.0e300, 1.0e300};
  if (args.has("--time")) window = pair_option(args, "--time");
  if (args.has("--time-star")) window = pair_option(args, "--time-star");
  const double cells = args.number("--radius", 2.0);
  if (!(cells > 0.0)) throw UsageError("--radius must be > 0 (grid cells)");
  const RunReader run((fs::path(dir) / "run.h5").string());
  const double time_factor = run.reference().time_factor();
  if (args.has("--time-star")) window = {window[0] / time_factor, window[1] / time_factor};
  const double radius = cells * run.grid().cell_size.x(), scale = run.reference().pressure_scale();
  std::vector<char> fluid(run.particle_count());
  for (std::size_t i = 0; i < fluid.size(); ++i) fluid[i] = run.bodies()[run.particle_bodies()[i]].is_fluid();
  std::printf("t,T*,stripes,particles\n");
  StripeSum all;
  int frames = 0;
  for (const auto& f : run.frames()) {
    if (f.time < window[0] || f.time > window[1]) continue;
    const StripeSum s = pressure_stripes(run.position(f.index), run.pressure(f.index), fluid, band, radius);
    std::printf("%s,%s,%s,%zu\n", json_number(f.time).c_str(), json_number(f.time * time_factor).c_str(),
                json_number(s.rms() / scale).c_str(), s.count);
    all += s;
    ++frames;
  }
  std::printf("# over %d frames: %s\n", frames, json_number(all.rms() / scale).c_str());
  return kOk;
}

}  // namespace

int command_metrics(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help", "--json", "--raw"},
                 {"--study", "--series", "--column", "--rate", "--window", "--series-file", "--length", "--stripes", "--x",
                  "--time", "--time-star", "--radius"});
  if (args.help(kHelp)) return kOk;
  SensorModel sensor;
  std::unique_ptr<StudyDescription> study;
  if (args.has("--study")) {
    study = std::make_unique<StudyDescription>(load_study(args.option("--study")));
    sensor = study->sensor;
  }
  sensor.rate = args.number("--rate", sensor.rate);
  sensor.window = args.number("--window", sensor.window);
  if (!(sensor.rate > 0.0) || !(sensor.window >= 0.0)) throw UsageError("--rate must be > 0 and --window >= 0");

  if (args.has("--series-file")) {
    if (!args.positional().empty()) throw UsageError("--series-file takes no run directory");
    const double length = args.number("--length", 0.0);
    if (!(length > 0.0)) throw UsageError("--series-file needs --length H [m], the height its T* is scaled with");
    const double time_factor = std::sqrt(9.81 / length);
    print_series(apply_sensor_model(read_measured_series(args.option("--series-file"), time_factor), sensor),
                 time_factor, "value");
    return kOk;
  }
  if (args.positional().size() != 1) throw UsageError("metrics expects one run directory (see bsmpm metrics --help)");
  const std::string dir = args.positional()[0];
  if (args.has("--stripes")) return print_stripes(args, dir);
  if (args.has("--series")) {
    const RunReader run((fs::path(dir) / "run.h5").string());
    const std::string column = args.option("--column", "P*");
    const Series raw = probe_column(run, args.option("--series"), column);
    print_series(args.flag("--raw") ? raw : apply_sensor_model(raw, sensor), run.reference().time_factor(), column);
    return kOk;
  }
  if (!study) throw UsageError("metrics needs --study STUDY.toml or --series PROBE (see bsmpm metrics --help)");
  const MetricValues values = compute_metrics(dir, study->metrics);
  if (args.flag("--json")) {
    JsonWriter w;
    w.begin_object().field("metrics_hash", metrics_hash(*study));
    for (const auto& [name, value] : values) w.field(name, value);
    w.end_object();
    std::fputs(w.str().c_str(), stdout);
  } else {
    for (const auto& [name, value] : values) std::printf("%-32s %s\n", name.c_str(), json_number(value).c_str());
  }
  return kOk;
}

}  // namespace bsmpm::cli
