#include "study/study_loader.hpp"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/input_file.hpp"
#include "parameters/table_reader.hpp"
#include "study/study_loader_parts.hpp"
#include "study/toml_text.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

namespace {

// A table of scene overrides: { "grid.cell_size" = 0.01, time.end = 0.5 }. Dotted keys
// written bare are nested tables in TOML, so nested tables are flattened into dotted keys;
// arrays (of tables too: probes = [...]) are one value.
void flatten(const toml::table& table, const std::string& prefix, std::vector<Assignment>& out) {
  for (auto&& [k, v] : table) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const toml::table* sub = v.as_table()) flatten(*sub, key, out);
    else out.push_back({key, toml_value_text(v), location_of(v)});
  }
}

// An axis value may set nothing (`set = {}`: the base scene as it is, the baseline of an axis
// that changes one choice at a time); the study's own `set` must set something.
std::vector<Assignment> read_set_table(TableReader& t, std::string_view key, bool allow_empty) {
  const toml::node& n = t.node(key);
  const toml::table* table = n.as_table();
  if (!table) t.fail(key, "expected a table of scene keys, e.g. { \"grid.cell_size\" = 0.01 }");
  std::vector<Assignment> out;
  flatten(*table, "", out);
  if (out.empty() && !allow_empty) t.fail(key, "sets no scene key");
  return out;
}

std::string number_label(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

Axis read_axis(TableReader& t, const std::vector<Axis>& earlier) {
  Axis a;
  a.where = t.where();
  a.name = t.string("name");
  if (!is_identifier(a.name)) t.fail("name", "use a letter, then letters, digits and '_' (it names a CSV column)");
  for (const auto& other : earlier)
    if (other.name == a.name) t.fail("name", "an axis named \"" + a.name + "\" already exists");
  a.unit = t.string_or("unit", "");
  const bool keyed = t.has("key");
  const std::string key = keyed ? t.string("key") : "";
  a.key = key;
  const toml::node& values = t.node("values");
  const toml::array* list = values.as_array();
  if (!list) t.fail("values", "expected an array of values");
  if (list->empty()) t.fail("values", "an axis needs at least one value");
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::node& item = *list->get(i);
    const std::string prefix = t.dotted("values") + "[" + std::to_string(i) + "]";
    AxisValue v;
    v.where = location_of(item);
    const toml::table* table = item.as_table();
    if (keyed) {
      // A bare value, or { value = ..., label = "..." } to name it.
      const toml::node* value = &item;
      if (table) {
        TableReader vt(*table, prefix, v.where);
        v.label = vt.string_or("label", "");
        value = &vt.node("value");
        vt.finish();
      }
      v.assignments.push_back({key, toml_value_text(*value), location_of(*value)});
      if (value->is_number()) v.coordinate = *value->value<double>();
      if (v.label.empty()) v.label = v.coordinate == v.coordinate ? number_label(v.coordinate) : toml_value_text(*value);
    } else {
      if (!table)
        throw SceneError(v.where, prefix,
                         "an axis without a key takes tables { value = X, label = \"...\", set = { KEY = VALUE, ... } };"
                         " give the axis a key to list bare values");
      TableReader vt(*table, prefix, v.where);
      v.coordinate = vt.number_or("value", static_cast<double>(i));
      v.label = vt.string_or("label", vt.has("value") ? number_label(v.coordinate) : "value " + std::to_string(i));
      v.assignments = read_set_table(vt, "set", true);
      vt.finish();
    }
    a.values.push_back(std::move(v));
  }
  t.finish();
  return a;
}

SensorModel read_sensor(TableReader t) {
  SensorModel s;
  s.rate = t.number_or("rate", s.rate, Range::positive());
  s.window = t.number_or("window", s.window, Range::closed(0.0, 10.0));
  t.finish();
  return s;
}

}  // namespace

StudyDescription load_study_text(const std::string& text, const std::string& path) {
  toml::table root = parse_toml(text, path);
  const fs::path dir = fs::absolute(path).parent_path();
  StudyDescription s;
  s.path = fs::absolute(path).lexically_normal().string();
  TableReader t(root, "", SourceLocation{path, 1, 1});
  {
    TableReader st = t.table("study");
    s.name = st.string("name");
    static const std::regex file_name("[A-Za-z0-9_.-]+");
    if (!std::regex_match(s.name, file_name)) st.fail("name", "use letters, digits, '_', '-' and '.' only (it names files)");
    s.title = st.string_or("title", s.name);
    const std::string scene = st.string("scene");
    s.scene_path = (dir / scene).lexically_normal().string();
    std::ifstream scene_file(s.scene_path, std::ios::binary);
    if (!fs::is_regular_file(s.scene_path) || !scene_file) st.fail("scene", "no scene file " + s.scene_path);
    s.scene_text.assign(std::istreambuf_iterator<char>(scene_file), std::istreambuf_iterator<char>());
    s.threads = static_cast<int>(st.integer_or("threads", 1, 1, 1024));
    if (st.has("set")) s.defaults = read_set_table(st, "set", false);
    st.finish();
  }
  if (auto sensor = t.optional_table("sensor")) s.sensor = read_sensor(*sensor);
  for (auto& a : t.tables("axes")) s.axes.push_back(read_axis(a, s.axes));
  if (s.axes.empty()) t.fail("axes", "a study needs at least one [[axes]] table");
  for (auto& m : t.tables("metrics")) {
    MetricSpec spec = read_metric(m, s.sensor);
    for (const auto& a : s.axes)
      if (a.name == spec.name) m.fail("name", "\"" + spec.name + "\" names an axis already");
    for (const auto& other : s.metrics)
      if (other.name == spec.name) m.fail("name", "a metric named \"" + spec.name + "\" already exists");
    s.metrics.push_back(spec);
  }
  for (auto& p : t.tables("plots")) {
    PlotSpec plot = read_plot(p, s, dir.string());
    for (const auto& other : s.plots)
      if (other.name == plot.name) p.fail("name", "a plot named \"" + plot.name + "\" already exists");
    s.plots.push_back(plot);
  }
  t.finish();
  return s;
}

StudyDescription load_study(const std::string& path) {
  return load_study_text(read_input_file(path, "the study file"), path);
}

std::size_t StudyDescription::case_count() const {
  std::size_t n = 1;
  for (const auto& a : axes) n *= a.values.size();
  return n;
}

}  // namespace bsmpm
