#include "study/study_cases.hpp"

#include "core/format.hpp"
#include "parameters/table_reader.hpp"
#include "probes/front_probe.hpp"
#include "probes/material_point.hpp"
#include "probes/pressure_probe.hpp"
#include "scene/overrides.hpp"

namespace bsmpm {

namespace {

std::vector<std::string> probe_columns(const ProbeDescription& p) {
  switch (p.kind) {
    case ProbeDescription::Kind::kMaterialPoint: return MaterialPointProbe::column_names();
    case ProbeDescription::Kind::kFront: return FrontProbe::column_names();
    default: return PressureProbe::column_names();
  }
}

const ProbeDescription* find_probe(const SceneDescription& scene, const std::string& name) {
  for (const auto& p : scene.probes)
    if (p.name == name) return &p;
  return nullptr;
}

// A probe and column a metric or plot names must exist in every case's scene.
void check_probe(const SceneDescription& scene, const std::string& probe, const std::string& column,
                 const SourceLocation& where, const std::string& key, const std::string& case_text) {
  const ProbeDescription* p = find_probe(scene, probe);
  std::string names;
  for (const auto& q : scene.probes) names += (names.empty() ? "" : ", ") + q.name;
  if (!p)
    throw SceneError(where, key, "the scene has no probe \"" + probe + "\" (" + case_text + "; probes: " +
                                     (names.empty() ? "none" : names) + ")");
  const auto columns = probe_columns(*p);
  if (std::find(columns.begin(), columns.end(), column) == columns.end()) {
    std::string list;
    for (const auto& c : columns) list += (list.empty() ? "" : ", ") + c;
    throw SceneError(where, key, "probe \"" + probe + "\" has no column \"" + column + "\" (columns: " + list + ")");
  }
}

// Whether dotted key `a` is `b` or lies inside it, or the other way round
// ("probes[2].name" and "probes", "grid" and "grid.cell_sze").
bool keys_overlap(const std::string& a, const std::string& b) {
  const std::string& shorter = a.size() < b.size() ? a : b;
  const std::string& longer = a.size() < b.size() ? b : a;
  if (longer.compare(0, shorter.size(), shorter) != 0) return false;
  return longer.size() == shorter.size() || longer[shorter.size()] == '.' || longer[shorter.size()] == '[';
}

// The assignment an error about `key` is about: the last one that sets it or a key in it.
const Assignment* assignment_for(const StudyCase& c, const std::string& key) {
  const Assignment* found = nullptr;
  for (const auto& a : c.assignments)
    if (!key.empty() && keys_overlap(a.key, key)) found = &a;
  return found;
}

}  // namespace

std::string hash_text(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return format("%016llx", static_cast<unsigned long long>(h));
}

std::vector<std::string> StudyCase::overrides() const {
  std::vector<std::string> out;
  for (const auto& a : assignments) out.push_back(a.text());
  return out;
}

std::vector<StudyCase> expand_cases(const StudyDescription& study, const std::string& version) {
  std::vector<StudyCase> cases;
  std::vector<std::size_t> index(study.axes.size(), 0);
  for (std::size_t n = 0; n < study.case_count(); ++n) {
    StudyCase c;
    c.value_index = index;
    c.assignments = study.defaults;
    for (std::size_t a = 0; a < study.axes.size(); ++a) {
      const auto& v = study.axes[a].values[index[a]].assignments;
      c.assignments.insert(c.assignments.end(), v.begin(), v.end());
    }
    std::string identity = study.scene_text + '\0';
    for (const auto& o : c.overrides()) identity += o + '\0';
    c.key = hash_text(identity + version);
    cases.push_back(std::move(c));
    // Odometer: the last axis turns fastest.
    for (std::size_t a = study.axes.size(); a-- > 0;) {
      if (++index[a] < study.axes[a].values.size()) break;
      index[a] = 0;
    }
  }
  return cases;
}

std::string describe_case(const StudyDescription& study, const StudyCase& c) {
  std::string s;
  for (std::size_t a = 0; a < study.axes.size(); ++a)
    s += (a ? ", " : "") + study.axes[a].name + " = " + study.axes[a].values[c.value_index[a]].label;
  return s;
}

void validate_cases(const StudyDescription& study, const std::vector<StudyCase>& cases,
                    const std::vector<SceneExtension>& extensions) {
  const std::string& text = study.scene_text;
  for (const auto& c : cases) {
    const std::string case_text = "case " + describe_case(study, c);
    // Each override alone first, so that a malformed one (an index past the end, a key
    // under a value) is pinned to its own line.
    toml::table root = parse_toml(text, study.scene_path);
    for (const auto& a : c.assignments) {
      try {
        apply_override(root, a.text());
      } catch (const UsageError& e) {
        throw SceneError(a.where, "\"" + a.key + "\"", std::string(e.what()) + " (" + case_text + ")");
      }
    }
    SceneDescription scene;
    try {
      scene = load_scene_text(text, study.scene_path, c.overrides(), extensions);
    } catch (const SceneError& e) {
      // The scene found fault with an override (its value comes from "--set KEY"; a key it
      // added has no place at all): name the study's line that gave it.
      const std::string& file = e.where().file;
      if (file.rfind("--set ", 0) == 0 || e.where().line <= 0) {
        const Assignment* a = file.rfind("--set ", 0) == 0 ? assignment_for(c, file.substr(6)) : nullptr;
        if (!a) a = assignment_for(c, e.key());
        if (a) throw SceneError(a->where, e.key(), e.message() + " (" + case_text + ")");
      }
      // The base scene, changed by the case's values together, does not hold: name the
      // case's values and pass the scene's own message on.
      SourceLocation where = study.axes.back().values[c.value_index.back()].where;
      throw SceneError(where, "", case_text + " makes an invalid scene: " + e.what());
    }
    for (const auto& m : study.metrics)
      if (m.uses_probe()) check_probe(scene, m.probe, m.column, m.probe_where, m.name, case_text);
    for (const auto& p : study.plots)
      for (const auto& probe : p.probes) check_probe(scene, probe, p.column, SourceLocation{study.path}, "plots." + p.name, case_text);
  }
}

}  // namespace bsmpm
