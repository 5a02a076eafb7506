#include "scene/calibration_file.hpp"

#include <unistd.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/json.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

namespace {

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// The value of `key` in record `index` of the file, of type T; throws IoError naming both.
template <class T>
T field(const std::map<std::string, JsonScalar>& object, const char* key, std::size_t index, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || !std::holds_alternative<T>(it->second))
    throw IoError(format("%s: record %zu has no %s \"%s\"", path.c_str(), index + 1,
                         std::is_same_v<T, double> ? "number" : std::is_same_v<T, bool> ? "boolean" : "string", key));
  return std::get<T>(it->second);
}

CalibrationRecord record_of(const std::map<std::string, JsonScalar>& o, std::size_t i, const std::string& path) {
  CalibrationRecord r;
  r.machine.cpu = field<std::string>(o, "cpu", i, path);
  r.machine.cores = static_cast<int>(field<double>(o, "cores", i, path));
  r.threads = static_cast<int>(field<double>(o, "threads", i, path));
  r.features.order = static_cast<int>(field<double>(o, "order", i, path));
  r.features.materials = field<std::string>(o, "materials", i, path);
  r.features.fluid_volume = field<std::string>(o, "fluid_volume", i, path);
  r.features.velocity_update = field<std::string>(o, "velocity_update", i, path);
  r.features.shifting = field<bool>(o, "shifting", i, path);
  r.features.grid_fields = static_cast<int>(field<double>(o, "grid_fields", i, path));
  r.particle_steps_per_second = field<double>(o, "particle_steps_per_second", i, path);
  r.particles = field<double>(o, "particles", i, path);
  r.rigid_particles = field<double>(o, "rigid_particles", i, path);
  r.scene = field<std::string>(o, "scene", i, path);
  r.recorded_at = field<double>(o, "recorded_at", i, path);
  r.program_version = field<std::string>(o, "program_version", i, path);
  if (!(r.particle_steps_per_second > 0.0) || r.threads < 1 || !(r.particles > 0.0) ||
      !(r.rigid_particles >= 0.0 && r.rigid_particles <= r.particles))
    throw IoError(format("%s: record %zu has a rate, thread or particle count out of range", path.c_str(), i + 1));
  return r;
}

// "2026-12-01T22:55:52Z", for a reader of the file (the program reads recorded_at).
std::string utc_text(double unix_seconds) {
  const std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string calibration_json(const std::vector<CalibrationRecord>& records) {
  JsonWriter w;
  w.begin_array();
  for (const CalibrationRecord& r : records)
    w.begin_object()
        .field("cpu", r.machine.cpu)
        .field("cores", r.machine.cores)
        .field("threads", r.threads)
        .field("order", r.features.order)
        .field("materials", r.features.materials)
        .field("fluid_volume", r.features.fluid_volume)
        .field("velocity_update", r.features.velocity_update)
        .field("shifting", r.features.shifting)
        .field("grid_fields", r.features.grid_fields)
        .field("particle_steps_per_second", r.particle_steps_per_second)
        .field("particles", r.particles)
        .field("rigid_particles", r.rigid_particles)
        .field("scene", r.scene)
        .field("recorded_at", r.recorded_at)
        .field("recorded", utc_text(r.recorded_at))
        .field("program_version", r.program_version)
        .end_object();
  w.end_array();
  return w.str();
}

}  // namespace

std::string calibration_path() {
  if (const std::string set = environment("BSMPM_CALIBRATION"); !set.empty()) return set;
  if (const std::string cache = environment("XDG_CACHE_HOME"); !cache.empty())
    return (fs::path(cache) / "bsmpm" / "calibration.json").string();
  if (const std::string home = environment("HOME"); !home.empty())
    return (fs::path(home) / ".cache" / "bsmpm" / "calibration.json").string();
  return "";
}

MachineIdentity this_machine() {
  MachineIdentity m;
  m.cpu = "unknown";
  m.cores = static_cast<int>(std::thread::hardware_concurrency());
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const auto begin = line.find_first_not_of(" \t", colon + 1);
    if (begin != std::string::npos) m.cpu = line.substr(begin);
    break;
  }
  return m;
}

CalibrationFile read_calibration(const std::string& path) {
  CalibrationFile file;
  if (path.empty()) return file;
  std::error_code error;
  if (!fs::exists(path, error)) return file;
  try {
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    const auto objects = parse_flat_json_array(text.str(), path);
    for (std::size_t i = 0; i < objects.size(); ++i) file.records.push_back(record_of(objects[i], i, path));
  } catch (const std::exception& e) {
    // Only a prediction depends on it: say so, and go on without it.
    file.records.clear();
    file.warning = format("%s; the calibration there is ignored (`bsmpm bench` writes a new one)", e.what());
  }
  return file;
}

std::string record_calibration(const std::string& path, const CalibrationRecord& fresh) {
  if (path.empty()) throw IoError("no place for the calibration: set BSMPM_CALIBRATION, XDG_CACHE_HOME or HOME");
  CalibrationFile file = read_calibration(path);
  const std::string text = calibration_json(merge_calibration(std::move(file.records), fresh));
  const fs::path target(path);
  std::error_code error;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), error);
  if (error) throw IoError(format("%s: cannot create its directory (%s)", path.c_str(), error.message().c_str()));
  const std::string tmp = format("%s.tmp.%ld", path.c_str(), static_cast<long>(::getpid()));
  {
    std::ofstream out(tmp);
    out << text;
    if (!out.flush()) {
      fs::remove(tmp, error);
      throw IoError(tmp + ": cannot write the calibration");
    }
  }
  fs::rename(tmp, target, error);
  if (error) {
    const std::string why = error.message();
    fs::remove(tmp, error);
    throw IoError(format("%s: cannot replace it (%s)", path.c_str(), why.c_str()));
  }
  return file.warning;
}

}  // namespace bsmpm
