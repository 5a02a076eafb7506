#include "study/study_plan.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/json.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

namespace {

void write_strings(JsonWriter& w, const std::string& key, const std::vector<std::string>& items) {
  w.key(key).begin_array();
  for (const auto& s : items) w.value(s);
  w.end_array();
}

void write_metric(JsonWriter& w, const MetricSpec& m) {
  w.begin_object().field("name", m.name).field("type", metric_type_names()[static_cast<int>(m.type)]);
  if (m.uses_probe()) {
    w.field("probe", m.probe).field("column", m.column).field("threshold", m.threshold);
    w.field("rate", m.sensor.rate).field("window", m.sensor.window);
    for (const auto& [key, window] : {std::pair{"time", m.time}, std::pair{"time_star", m.time_star}})
      if (window) w.key(key).begin_array().value((*window)[0]).value((*window)[1]).end_array();
  }
  write_strings(w, "columns", m.columns());
  w.end_object();
}

void write_plot(JsonWriter& w, const PlotSpec& p) {
  w.begin_object()
      .field("name", p.name)
      .field("type", p.type)
      .field("title", p.title)
      .field("xlabel", p.xlabel)
      .field("ylabel", p.ylabel)
      .field("x", p.x)
      .field("fit", p.fit)
      .field("fit_offset", p.fit_offset)
      .field("column", p.column);
  write_strings(w, "y", p.y);
  write_strings(w, "probes", p.probes);
  w.key("positions").begin_array();
  for (double x : p.positions) w.value(x);
  w.end_array();
  w.key("references").begin_array();
  for (const auto& r : p.references)
    w.begin_object().field("path", r.path).field("probe", r.probe).field("label", r.label).field("length", r.length).end_object();
  w.end_array();
  w.end_object();
}

}  // namespace

std::string metrics_hash(const StudyDescription& study) {
  JsonWriter w;
  w.begin_array();
  for (const auto& m : study.metrics) write_metric(w, m);
  w.end_array();
  return hash_text(w.str());
}

std::string plan_json(const StudyDescription& study, const std::vector<StudyCase>& cases, const PlanContext& context) {
  JsonWriter w;
  w.begin_object()
      .field("format", "bsmpm-study-plan")
      .field("format_version", 1)
      .field("name", study.name)
      .field("title", study.title)
      .field("study_file", study.path)
      .field("scene", study.scene_path)
      .field("program", context.program)
      .field("version", context.version)
      .field("threads", study.threads)
      .field("metrics_hash", metrics_hash(study));
  w.key("sensor").begin_object().field("rate", study.sensor.rate).field("window", study.sensor.window).end_object();
  w.key("axes").begin_array();
  for (const auto& a : study.axes) {
    w.begin_object().field("name", a.name).field("unit", a.unit).key("values").begin_array();
    for (const auto& v : a.values) w.begin_object().field("label", v.label).field("value", v.coordinate).end_object();
    w.end_array().end_object();
  }
  w.end_array();
  w.key("metrics").begin_array();
  for (const auto& m : study.metrics) write_metric(w, m);
  w.end_array();
  w.key("plots").begin_array();
  for (const auto& p : study.plots) write_plot(w, p);
  w.end_array();
  w.key("cases").begin_array();
  for (const auto& c : cases) {
    w.begin_object().field("key", c.key).key("axes").begin_array();
    for (std::size_t i : c.value_index) w.value(static_cast<long>(i));
    w.end_array();
    write_strings(w, "overrides", c.overrides());
    w.end_object();
  }
  w.end_array();
  w.end_object();
  return w.str();
}

bool write_if_changed(const std::string& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::ostringstream old;
      old << in.rdbuf();
      if (old.str() == text) return false;
    }
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) throw IoError(tmp + ": cannot write");
  }
  fs::rename(tmp, path);
  return true;
}

}  // namespace bsmpm
