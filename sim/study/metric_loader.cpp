// [[metrics]]: what to extract from each run (docs/studies.md, "Metrics").
#include <regex>

#include "study/study_loader_parts.hpp"

namespace bsmpm {

namespace {

using Type = MetricSpec::Type;

// Probe metrics that look at the filtered signal (the sensor model applies).
bool filtered(Type t) { return t == Type::kPeak || t == Type::kMean || t == Type::kImpactTime; }

std::array<double, 2> read_window(TableReader& t, std::string_view key) {
  const Vec2 w = t.vec2(key);
  if (!(w.y() > w.x())) t.fail(key, "the window's end must follow its start");
  return {w.x(), w.y()};
}

}  // namespace

bool is_identifier(const std::string& name) {
  static const std::regex identifier("[A-Za-z][A-Za-z0-9_]*");
  return std::regex_match(name, identifier);
}

const std::vector<std::string>& metric_type_names() {
  static const std::vector<std::string> names = {"peak",         "mean",  "min_raw",   "impact_time",
                                                 "max",          "time_of_max", "wall_seconds", "steps",
                                                 "particles",    "peak_memory_mb", "particle_steps_per_second"};
  return names;
}

std::vector<std::string> MetricSpec::columns() const {
  switch (type) {
    case Type::kPeak:
    case Type::kMinRaw:
    case Type::kMax: return {name, name + "_time", name + "_time_star"};
    case Type::kImpactTime:
    case Type::kTimeOfMax: return {name, name + "_star"};
    default: return {name};
  }
}

MetricSpec read_metric(TableReader& t, const SensorModel& defaults) {
  MetricSpec m;
  m.where = t.where();
  m.name = t.string("name");
  if (!is_identifier(m.name)) t.fail("name", "use a letter, then letters, digits and '_' (it names a CSV column)");
  const auto& names = metric_type_names();
  const std::string type = t.choice("type", names);
  m.type = static_cast<Type>(std::find(names.begin(), names.end(), type) - names.begin());
  if (m.uses_probe()) {
    m.probe_where = t.where("probe");
    m.probe = t.string("probe");
    m.column = t.string_or("column", "P*");
    if (t.has("time") && t.has("time_star")) t.fail("time_star", "give either time [s] or time_star [T*], not both");
    if (t.has("time")) m.time = read_window(t, "time");
    if (t.has("time_star")) m.time_star = read_window(t, "time_star");
    if (m.type == Type::kMinRaw) m.threshold = t.number_or("threshold", 0.01);  // first contact
    if (m.type == Type::kImpactTime) m.threshold = t.number("threshold");
    m.sensor = defaults;
    if (filtered(m.type)) {
      m.sensor.rate = t.number_or("rate", m.sensor.rate, Range::positive());
      m.sensor.window = t.number_or("window", m.sensor.window, Range::closed(0.0, 10.0));
    }
  }
  // Keys that belong to other metric types are reported as unknown here.
  t.finish();
  return m;
}

}  // namespace bsmpm
