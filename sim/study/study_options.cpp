#include "study/study_options.hpp"

#include <sstream>

#include "core/error.hpp"

namespace bsmpm {

namespace {

std::pair<std::string, std::string> split_assignment(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw UsageError(option + " expects NAME=VALUE, got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

// Splits "0.01,0.008" and "[0.6, 0.3],[0.6, 0.6]" at the commas outside brackets.
std::vector<std::string> split_values(const std::string& list) {
  std::vector<std::string> out(1);
  int depth = 0;
  for (const char c : list) {
    depth += (c == '[' || c == '{') - (c == ']' || c == '}');
    if (c == ',' && depth == 0) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

// An axis of tables (no key) takes no bare values: --axis NAME=LABEL,... keeps the values
// with those labels, in the order given.
void select_values_by_label(Axis& axis, const std::vector<std::string>& labels) {
  std::vector<AxisValue> kept;
  for (const auto& label : labels) {
    bool found = false;
    for (const auto& v : axis.values)
      if (v.label == label) kept.push_back(v), found = true;
    if (!found) {
      std::string known;
      for (const auto& v : axis.values) known += (known.empty() ? "\"" : ", \"") + v.label + "\"";
      throw UsageError("--axis " + axis.name + ": no value labelled \"" + label +
                       "\" (an axis of tables is narrowed by its labels: " + known + ")");
    }
  }
  axis.values = std::move(kept);
}

}  // namespace

void apply_study_options(StudyDescription& study, const std::vector<std::string>& sets,
                         const std::vector<std::string>& axes) {
  for (const auto& s : sets) {
    const auto [key, value] = split_assignment(s, "--set");
    study.defaults.push_back({key, value, SourceLocation{"--set " + key}});
  }
  for (const auto& a : axes) {
    const auto [name, list] = split_assignment(a, "--axis");
    Axis* axis = nullptr;
    for (auto& candidate : study.axes)
      if (candidate.name == name) axis = &candidate;
    if (!axis) throw UsageError("--axis " + name + ": the study has no axis \"" + name + "\"");
    if (axis->key.empty()) {
      select_values_by_label(*axis, split_values(list));
      continue;
    }
    axis->values.clear();
    for (const auto& text : split_values(list)) {
      AxisValue v;
      v.label = text;
      v.where = SourceLocation{"--axis " + name};
      v.assignments.push_back({axis->key, text, v.where});
      std::istringstream number(text);
      double x = 0.0;
      if (number >> x && number.eof()) v.coordinate = x;
      axis->values.push_back(v);
    }
  }
}

}  // namespace bsmpm
