#include "io/run_summary.hpp"

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/json.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

void write_run_summary(const std::string& dir, const RunSummary& s) {
  JsonWriter w;
  w.begin_object()
      .field("format", "bsmpm-run-summary")
      .field("format_version", 1)
      .field("status", s.status)
      .field("exit_status", s.exit_status)
      .field("steps", s.steps)
      .field("time", s.time)
      .field("end_time", s.end_time)
      .field("wall_seconds", s.wall_seconds)
      .field("predicted_wall_seconds", s.predicted_wall_seconds)
      .field("threads", s.threads)
      .field("cores", s.cores)
      .field("particles", static_cast<long>(s.particles))
      .field("particle_steps_per_second", s.particle_steps_per_second)
      .field("peak_memory_mb", s.peak_memory_mb)
      .field("min_dt", s.min_dt)
      .field("max_dt", s.max_dt)
      .field("frames", s.frames)
      .field("checkpoint_time", s.checkpoint_time)
      .field("checkpoints", s.checkpoints)
      .field("checkpoint_seconds", s.checkpoint_seconds)
      .field("pressure_solves", s.pressure_solves)
      .field("pressure_iterations_mean", s.pressure_iterations_mean)
      .field("pressure_iterations_max", s.pressure_iterations_max)
      .field("pressure_residual_max", s.pressure_residual_max)
      .field("program_version", s.program_version)
      .field("git_revision", s.git_revision)
      .end_object();
  const fs::path final_path = fs::path(dir) / "summary.json";
  const fs::path tmp = fs::path(dir) / "summary.json.tmp";
  {
    std::ofstream out(tmp);
    out << w.str();
    if (!out.flush()) throw IoError(tmp.string() + ": cannot write the run summary");
  }
  fs::rename(tmp, final_path);
}

RunSummary read_run_summary(const std::string& dir) {
  const fs::path path = fs::path(dir) / "summary.json";
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": no run summary (did the run finish?)");
  std::ostringstream text;
  text << in.rdbuf();
  const auto values = parse_flat_json_object(text.str(), path.string());
  auto number = [&](const char* key) {
    const auto it = values.find(key);
    if (it == values.end()) throw IoError(path.string() + ": no \"" + key + "\"");
    if (std::holds_alternative<std::monostate>(it->second)) return std::nan("");
    if (!std::holds_alternative<double>(it->second)) throw IoError(path.string() + ": \"" + key + "\" is not a number");
    return std::get<double>(it->second);
  };
  auto text_of = [&](const char* key) {
    const auto it = values.find(key);
    if (it == values.end() || !std::holds_alternative<std::string>(it->second))
      throw IoError(path.string() + ": no string \"" + key + "\"");
    return std::get<std::string>(it->second);
  };
  RunSummary s;
  s.status = text_of("status");
  s.exit_status = static_cast<int>(number("exit_status"));
  s.steps = static_cast<long>(number("steps"));
  s.time = number("time");
  s.end_time = number("end_time");
  s.wall_seconds = number("wall_seconds");
  // Absent from the summaries of versions before the prediction.
  if (values.count("predicted_wall_seconds")) s.predicted_wall_seconds = number("predicted_wall_seconds");
  s.threads = static_cast<int>(number("threads"));
  s.cores = static_cast<int>(number("cores"));
  s.particles = static_cast<std::size_t>(number("particles"));
  s.particle_steps_per_second = number("particle_steps_per_second");
  s.peak_memory_mb = number("peak_memory_mb");
  s.min_dt = number("min_dt");
  s.max_dt = number("max_dt");
  s.frames = static_cast<int>(number("frames"));
  if (values.count("checkpoint_time")) {  // absent before they existed
    s.checkpoint_time = number("checkpoint_time");
    s.checkpoints = static_cast<int>(number("checkpoints"));
    s.checkpoint_seconds = number("checkpoint_seconds");
  }
  if (values.count("pressure_solves")) {  // written since the incompressible fluid
    s.pressure_solves = static_cast<long>(number("pressure_solves"));
    s.pressure_iterations_mean = number("pressure_iterations_mean");
    s.pressure_iterations_max = static_cast<int>(number("pressure_iterations_max"));
    s.pressure_residual_max = number("pressure_residual_max");
  }
  s.program_version = text_of("program_version");
  s.git_revision = text_of("git_revision");
  return s;
}

double peak_resident_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

}  // namespace bsmpm
