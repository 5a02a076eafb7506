#include "io/run_summary.hpp"

#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "core/error.hpp"
#include "io/json.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

namespace {

// Every key of summary.json with its member, in the file's order: the one list the writer and
// the reader walk. visit(key, member, always): `always` false for the keys that summaries of
// earlier versions lack (the reader then keeps the member's default).
template <class Summary, class Visit>
void for_each_field(Summary& s, Visit&& visit) {
  visit("status", s.status, true);
  visit("exit_status", s.exit_status, true);
  visit("steps", s.steps, true);
  visit("time", s.time, true);
  visit("end_time", s.end_time, true);
  visit("wall_seconds", s.wall_seconds, true);
  visit("predicted_wall_seconds", s.predicted_wall_seconds, false);  // since the prediction
  visit("threads", s.threads, true);
  visit("cores", s.cores, true);
  visit("particles", s.particles, true);
  visit("particle_steps_per_second", s.particle_steps_per_second, true);
  visit("peak_memory_mb", s.peak_memory_mb, true);
  visit("min_dt", s.min_dt, true);
  visit("max_dt", s.max_dt, true);
  visit("frames", s.frames, true);
  visit("checkpoint_time", s.checkpoint_time, false);  // since checkpoints
  visit("checkpoints", s.checkpoints, false);
  visit("checkpoint_seconds", s.checkpoint_seconds, false);
  visit("pressure_solves", s.pressure_solves, false);  // since the incompressible fluid
  visit("pressure_iterations_mean", s.pressure_iterations_mean, false);
  visit("pressure_iterations_max", s.pressure_iterations_max, false);
  visit("pressure_residual_max", s.pressure_residual_max, false);
  visit("program_version", s.program_version, true);
  visit("git_revision", s.git_revision, true);
}

}  // namespace

void write_run_summary(const std::string& dir, const RunSummary& s) {
  JsonWriter w;
  w.begin_object().field("format", "bsmpm-run-summary").field("format_version", 1);
  for_each_field(s, [&](const char* key, const auto& value, bool) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::size_t>) w.field(key, static_cast<long>(value));
    else w.field(key, value);
  });
  w.end_object();
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
  for_each_field(s, [&](const char* key, auto& member, bool always) {
    using T = std::decay_t<decltype(member)>;
    if (!always && !values.count(key)) return;
    if constexpr (std::is_same_v<T, std::string>) member = text_of(key);
    else member = static_cast<T>(number(key));
  });
  return s;
}

double peak_resident_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

}  // namespace bsmpm
