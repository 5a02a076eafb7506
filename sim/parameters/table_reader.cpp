#include "parameters/table_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bsmpm {

namespace {

SourceLocation location_of_region(const toml::source_region& r) {
  SourceLocation loc;
  loc.file = r.path ? *r.path : std::string("<scene>");
  // Values given on the command line (--set key=value) have no meaningful line.
  if (loc.file.rfind("--set", 0) != 0) {
    loc.line = static_cast<int>(r.begin.line);
    loc.column = static_cast<int>(r.begin.column);
  }
  return loc;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// Levenshtein distance, for "did you mean" hints on misspelt keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string quoted_list(const std::vector<std::string>& options) {
  std::string s;
  for (std::size_t i = 0; i < options.size(); ++i) {
    if (i) s += (i + 1 == options.size()) ? " or " : ", ";
    s += "\"" + options[i] + "\"";
  }
  return s;
}

}  // namespace

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    SourceLocation where{path, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column)};
    throw SceneError(where, "", "TOML syntax error: " + std::string(e.description()));
  }
}

SourceLocation location_of(const toml::node& node) { return location_of_region(node.source()); }
SourceLocation location_of(const toml::key& key) { return location_of_region(key.source()); }

TableReader::TableReader(const toml::table& table, std::string prefix, SourceLocation where)
    : table_(table), prefix_(std::move(prefix)), where_(std::move(where)) {}

bool TableReader::has(std::string_view key) const {
  known_.insert(std::string(key));
  return table_.contains(key);
}

SourceLocation TableReader::where(std::string_view key) const {
  if (const toml::node* n = table_.get(key)) return location_of(*n);
  return where_;
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  throw SceneError(where(key), dotted(key), message);
}

const toml::node& TableReader::required(std::string_view key) {
  known_.insert(std::string(key));
  const toml::node* n = table_.get(key);
  if (!n) {
    // A misspelling of the key is the likelier mistake: report it where it stands.
    for (auto&& [k, v] : table_)
      if (!used_.count(k.str()) && !known_.count(k.str()) && edit_distance(k.str(), key) < 3)
        throw SceneError(location_of(k), dotted(k.str()), "unknown key (did you mean '" + std::string(key) + "'?)");
    throw SceneError(where_, dotted(key), "missing required key");
  }
  used_.insert(std::string(key));
  return *n;
}

double TableReader::checked(std::string_view key, const toml::node& node, Range r) const {
  const std::optional<double> value = node.is_number() ? node.value<double>() : std::nullopt;
  if (!value) throw SceneError(location_of(node), dotted(key), "expected a number, got " + type_name(node));
  const double x = *value;
  if (!std::isfinite(x)) throw SceneError(location_of(node), dotted(key), "must be finite");
  const bool below = r.min.included ? !(x >= r.min.value) : !(x > r.min.value);
  const bool above = r.max.included ? !(x <= r.max.value) : !(x < r.max.value);
  if (below || above) {
    std::string want;
    if (std::isfinite(r.min.value) && std::isfinite(r.max.value))
      want = "in " + std::string(r.min.included ? "[" : "(") + format_number(r.min.value) + ", " +
             format_number(r.max.value) + (r.max.included ? "]" : ")");
    else if (std::isfinite(r.min.value))
      want = std::string(r.min.included ? ">= " : "> ") + format_number(r.min.value);
    else
      want = std::string(r.max.included ? "<= " : "< ") + format_number(r.max.value);
    throw SceneError(location_of(node), dotted(key), "must be " + want + " (got " + format_number(x) + ")");
  }
  return x;
}

double TableReader::number(std::string_view key, Range range) { return checked(key, required(key), range); }

double TableReader::number_or(std::string_view key, double fallback, Range range) {
  return has(key) ? number(key, range) : fallback;
}

long TableReader::integer(std::string_view key, long min, long max) {
  const toml::node& n = required(key);
  if (!n.is_integer()) throw SceneError(location_of(n), dotted(key), "expected an integer, got " + type_name(n));
  const long x = static_cast<long>(*n.value<int64_t>());
  if (x < min || x > max)
    throw SceneError(location_of(n), dotted(key),
                     "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "] (got " + std::to_string(x) + ")");
  return x;
}

long TableReader::integer_or(std::string_view key, long fallback, long min, long max) {
  return has(key) ? integer(key, min, max) : fallback;
}

bool TableReader::boolean_or(std::string_view key, bool fallback) {
  if (!has(key)) return fallback;
  const toml::node& n = required(key);
  if (!n.is_boolean()) throw SceneError(location_of(n), dotted(key), "expected true or false, got " + type_name(n));
  return *n.value<bool>();
}

std::string TableReader::string(std::string_view key) {
  const toml::node& n = required(key);
  if (!n.is_string()) throw SceneError(location_of(n), dotted(key), "expected a string, got " + type_name(n));
  return *n.value<std::string>();
}

std::string TableReader::string_or(std::string_view key, std::string fallback) {
  return has(key) ? string(key) : fallback;
}

std::string TableReader::choice(std::string_view key, const std::vector<std::string>& options) {
  const std::string s = string(key);
  for (const auto& o : options)
    if (s == o) return s;
  fail(key, "must be " + quoted_list(options) + " (got \"" + s + "\")");
}

std::string TableReader::choice_or(std::string_view key, std::string fallback,
                                   const std::vector<std::string>& options) {
  return has(key) ? choice(key, options) : fallback;
}

Vec2 TableReader::vec2(std::string_view key, Range range) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2)
    throw SceneError(location_of(n), dotted(key), "expected an array of two numbers [x, y], got " +
                                                      (a ? "an array of " + std::to_string(a->size()) : type_name(n)));
  return {checked(key, *a->get(0), range), checked(key, *a->get(1), range)};
}

Vec2 TableReader::vec2_or(std::string_view key, Vec2 fallback, Range range) {
  return has(key) ? vec2(key, range) : fallback;
}

std::array<std::string, 2> TableReader::string_pair(std::string_view key) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2 || !a->get(0)->is_string() || !a->get(1)->is_string())
    throw SceneError(location_of(n), dotted(key), "expected two names [\"a\", \"b\"]");
  return {*a->get(0)->value<std::string>(), *a->get(1)->value<std::string>()};
}

std::vector<Vec2> TableReader::points(std::string_view key, std::size_t min_count) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a) throw SceneError(location_of(n), dotted(key), "expected an array of [x, y] points, got " + type_name(n));
  if (a->size() < min_count)
    throw SceneError(location_of(n), dotted(key), "needs at least " + std::to_string(min_count) + " points");
  std::vector<Vec2> out;
  for (const toml::node& item : *a) {
    const toml::array* pt = item.as_array();
    if (!pt || pt->size() != 2)
      throw SceneError(location_of(item), dotted(key), "each point must be [x, y]");
    out.emplace_back(checked(key, *pt->get(0), {}), checked(key, *pt->get(1), {}));
  }
  return out;
}

std::vector<std::string> TableReader::strings(std::string_view key) {
  const toml::node& n = required(key);
  if (n.is_string()) return {*n.value<std::string>()};
  const toml::array* a = n.as_array();
  if (!a || a->empty()) throw SceneError(location_of(n), dotted(key), "expected a string or a non-empty array of strings");
  std::vector<std::string> out;
  for (const toml::node& item : *a) {
    if (!item.is_string()) throw SceneError(location_of(item), dotted(key), "expected a string, got " + type_name(item));
    out.push_back(*item.value<std::string>());
  }
  return out;
}

std::vector<double> TableReader::numbers(std::string_view key, Range range) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->empty()) throw SceneError(location_of(n), dotted(key), "expected a non-empty array of numbers");
  std::vector<double> out;
  for (const toml::node& item : *a) out.push_back(checked(key, item, range));
  return out;
}

TableReader TableReader::table(std::string_view key) {
  const toml::node& n = required(key);
  if (!n.is_table()) throw SceneError(location_of(n), dotted(key), "expected a table, got " + type_name(n));
  return TableReader(*n.as_table(), dotted(key), location_of(n));
}

std::optional<TableReader> TableReader::optional_table(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return table(key);
}

std::vector<TableReader> TableReader::tables(std::string_view key) {
  std::vector<TableReader> out;
  if (!has(key)) return out;
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a) throw SceneError(location_of(n), dotted(key), "expected an array of tables ([[" + dotted(key) + "]]), got " + type_name(n));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& item = *a->get(i);
    if (!item.is_table())
      throw SceneError(location_of(item), dotted(key), "each entry must be a table, got " + type_name(item));
    out.emplace_back(*item.as_table(), dotted(key) + "[" + std::to_string(i) + "]", location_of(item));
  }
  return out;
}

std::vector<std::pair<std::string, TableReader>> TableReader::named_tables() {
  std::vector<std::pair<std::string, TableReader>> out;
  for (auto&& [k, v] : table_) {
    used_.insert(std::string(k.str()));
    if (!v.is_table()) throw SceneError(location_of(v), dotted(k.str()), "expected a table, got " + type_name(v));
    out.emplace_back(std::string(k.str()), TableReader(*v.as_table(), dotted(k.str()), location_of(v)));
  }
  return out;
}

void TableReader::finish() const {
  for (auto&& [k, v] : table_) {
    if (used_.count(k.str())) continue;
    std::string hint;
    std::size_t best = 3;  // suggest only near misses
    for (const auto& known : known_) {
      const std::size_t d = edit_distance(k.str(), known);
      if (d < best) {
        best = d;
        hint = " (did you mean '" + known + "'?)";
      }
    }
    throw SceneError(location_of(k), dotted(k.str()), "unknown key" + hint);
  }
}

}  // namespace bsmpm
