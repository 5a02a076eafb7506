#include "scene/overrides.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace bsmpm {

namespace {

struct Segment {
  std::string key;
  std::optional<long> index;  // the array element, for key[N]
};

std::vector<Segment> parse_path(std::string_view path, std::string_view assignment) {
  std::vector<Segment> out;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    std::string_view part = path.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start);
    Segment seg;
    const std::size_t bracket = part.find('[');
    if (bracket != std::string_view::npos) {
      if (part.back() != ']') throw UsageError("--set " + std::string(assignment) + ": malformed index in '" + std::string(part) + "'");
      try {
        seg.index = std::stol(std::string(part.substr(bracket + 1, part.size() - bracket - 2)));
        if (*seg.index < 0) throw std::out_of_range("negative");
      } catch (const std::exception&) {
        throw UsageError("--set " + std::string(assignment) + ": malformed index in '" + std::string(part) + "'");
      }
      part = part.substr(0, bracket);
    }
    if (part.empty()) throw UsageError("--set " + std::string(assignment) + ": empty key segment");
    seg.key = std::string(part);
    out.push_back(seg);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return out;
}

// Parses VALUE into holder["v"]; the node keeps "--set KEY" as its source, so errors about
// it name the override. (Nodes must be moved, not copied: a copy drops its source.)
toml::node& parse_value(const std::string& key, const std::string& value, toml::table& holder) {
  const std::string source = "--set " + key;
  try {
    holder = toml::parse("v = " + value, source);
  } catch (const toml::parse_error&) {
    std::string escaped;
    for (char c : value) {
      if (c == '"' || c == '\\') escaped += '\\';
      escaped += c;
    }
    holder = toml::parse("v = \"" + escaped + "\"", source);
  }
  return *holder.get("v");
}

// A key that an override adds to the scene, with "--set KEY" as its source: an error about it
// (an unknown key, a misspelling) names the override rather than the scene file.
toml::key override_key(const std::string& name, const std::string& assignment_key) {
  toml::source_region source;
  source.path = std::make_shared<const std::string>("--set " + assignment_key);
  return toml::key(name, std::move(source));
}

}  // namespace

void apply_override(toml::table& root, std::string_view assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw UsageError("--set expects KEY=VALUE, got '" + std::string(assignment) + "'");
  const std::string key(assignment.substr(0, eq));
  const std::string value(assignment.substr(eq + 1));
  const std::vector<Segment> path = parse_path(key, assignment);

  toml::table* table = &root;
  for (std::size_t s = 0; s < path.size(); ++s) {
    const Segment& seg = path[s];
    const bool last = s + 1 == path.size();
    if (seg.index) {
      const long index = *seg.index;
      toml::array* array = (*table)[seg.key].as_array();
      if (!array) throw UsageError("--set " + key + ": '" + seg.key + "' is not an array in the scene");
      if (index >= static_cast<long>(array->size()))
        throw UsageError("--set " + key + ": index " + std::to_string(index) + " is past the end of '" +
                         seg.key + "' (" + std::to_string(array->size()) + " entries)");
      toml::node* element = array->get(static_cast<std::size_t>(index));
      if (last) {
        toml::table holder;
        array->replace(array->cbegin() + index, std::move(parse_value(key, value, holder)));
        return;
      }
      table = element->as_table();
      if (!table) throw UsageError("--set " + key + ": '" + seg.key + "[" + std::to_string(index) + "]' is not a table");
      continue;
    }
    if (last) {
      toml::table holder;
      toml::node& parsed = parse_value(key, value, holder);
      if (table->contains(seg.key)) table->insert_or_assign(seg.key, std::move(parsed));
      else table->insert_or_assign(override_key(seg.key, key), std::move(parsed));
      return;
    }
    toml::node* next = table->get(seg.key);
    if (!next) next = &table->insert_or_assign(override_key(seg.key, key), toml::table{}).first->second;
    table = next->as_table();
    if (!table) throw UsageError("--set " + key + ": '" + seg.key + "' is not a table in the scene");
  }
}

}  // namespace bsmpm
