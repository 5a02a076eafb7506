// [[plots]]: what the study draws from its CSV (docs/studies.md, "Plots").
#include <filesystem>
#include <regex>

#include "study/study_loader_parts.hpp"

namespace bsmpm {

namespace fs = std::filesystem;

namespace {

void check_metric(TableReader& t, std::string_view key, const std::string& name, const StudyDescription& s) {
  for (const auto& m : s.metrics)
    for (const auto& column : m.columns())
      if (column == name) return;
  t.fail(key, "no metric \"" + name + "\" in [[metrics]] (declare metrics before the plots that use them)");
}

ReferenceSeries read_reference(TableReader& r, const std::string& study_dir) {
  ReferenceSeries ref;
  ref.path = (fs::path(study_dir) / r.string("path")).lexically_normal().string();
  if (!fs::is_regular_file(ref.path)) r.fail("path", "no file " + ref.path);
  ref.probe = r.string("probe");
  ref.label = r.string_or("label", fs::path(ref.path).filename().string());
  ref.length = r.number("length", Range::positive());
  r.finish();
  return ref;
}

}  // namespace

PlotSpec read_plot(TableReader& t, const StudyDescription& s, const std::string& study_dir) {
  PlotSpec p;
  p.name = t.string("name");
  static const std::regex file_name("[A-Za-z0-9_.-]+");
  if (!std::regex_match(p.name, file_name)) t.fail("name", "use letters, digits, '_', '-' and '.' only (it names a file)");
  p.type = t.choice_or("type", "metric", {"metric", "profile", "series"});
  p.title = t.string_or("title", "");
  p.xlabel = t.string_or("xlabel", "");
  p.ylabel = t.string_or("ylabel", "");
  if (p.type == "series") {
    p.probes = t.strings("probes");
    p.column = t.string_or("column", "P*");
    p.x = t.choice_or("x", "T*", {"T*", "t"});
    for (auto& r : t.tables("references")) {
      p.references.push_back(read_reference(r, study_dir));
      if (std::find(p.probes.begin(), p.probes.end(), p.references.back().probe) == p.probes.end())
        r.fail("probe", "\"" + p.references.back().probe + "\" is not among this plot's probes");
    }
  } else {
    if (p.type == "metric") {
      p.x = t.string("x");
      bool is_axis = false;
      for (const auto& a : s.axes) is_axis = is_axis || a.name == p.x;
      if (!is_axis) t.fail("x", "no axis named \"" + p.x + "\"");
      p.y = t.strings("y");
      for (const auto& y : p.y) check_metric(t, "y", y, s);
    } else {
      p.y = t.strings("metrics");
      for (const auto& y : p.y) check_metric(t, "metrics", y, s);
      p.positions = t.numbers("positions");
      if (p.positions.size() != p.y.size()) t.fail("positions", "needs one position per metric");
    }
    p.fit = t.choice_or("fit", "", {"parabola", "exponential", "decaying_exponential"});
    if (p.fit == "exponential") p.fit_offset = t.boolean_or("offset", true);
  }
  t.finish();
  return p;
}

}  // namespace bsmpm
