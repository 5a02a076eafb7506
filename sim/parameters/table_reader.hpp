// Validated access to a TOML table (after pbrt-v4's ParameterDictionary + ReportUnused):
// every accessor checks type and range and names file:line:column and the dotted key on
// failure; finish() reports every key that no accessor asked for.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "core/error.hpp"
#include "core/types.hpp"

namespace bsmpm {

// Parses TOML text; a syntax error is a SceneError at its file:line:column.
toml::table parse_toml(const std::string& text, const std::string& path);

SourceLocation location_of(const toml::node& node);
SourceLocation location_of(const toml::key& key);

// One end of a Range: its value and whether the value itself is allowed.
struct Bound {
  double value;
  bool included;
  static constexpr Bound inclusive(double v) { return {v, true}; }
  static constexpr Bound exclusive(double v) { return {v, false}; }
};

// The values a number may take, e.g. Range{Bound::exclusive(0.0), Bound::inclusive(1.0)}
// for (0, 1]; an end left out is unbounded.
struct Range {
  Bound min = Bound::inclusive(-std::numeric_limits<double>::infinity());
  Bound max = Bound::inclusive(std::numeric_limits<double>::infinity());
  static constexpr Range positive() { return {Bound::exclusive(0.0)}; }
  static constexpr Range non_negative() { return {Bound::inclusive(0.0)}; }
  static constexpr Range non_positive() { return {.max = Bound::inclusive(0.0)}; }
  static constexpr Range closed(double a, double b) { return {Bound::inclusive(a), Bound::inclusive(b)}; }
};

class TableReader {
 public:
  TableReader(const toml::table& table, std::string prefix, SourceLocation where);

  bool has(std::string_view key) const;
  // Location of the key's value (or of the table if absent).
  SourceLocation where(std::string_view key) const;
  const SourceLocation& where() const { return where_; }
  std::string dotted(std::string_view key) const { return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key); }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  double number(std::string_view key, Range range = {});
  double number_or(std::string_view key, double fallback, Range range = {});
  long integer(std::string_view key, long min, long max);
  long integer_or(std::string_view key, long fallback, long min, long max);
  bool boolean_or(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  std::string choice(std::string_view key, const std::vector<std::string>& options);
  std::string choice_or(std::string_view key, std::string fallback, const std::vector<std::string>& options);
  Vec2 vec2(std::string_view key, Range range = {});
  Vec2 vec2_or(std::string_view key, Vec2 fallback, Range range = {});
  std::array<std::string, 2> string_pair(std::string_view key);
  std::vector<Vec2> points(std::string_view key, std::size_t min_count);
  // A string or an array of strings (one or more), as a list.
  std::vector<std::string> strings(std::string_view key);
  std::vector<double> numbers(std::string_view key, Range range = {});
  // The raw value, marked as used, for readers of free-form values (a study's overrides).
  const toml::node& node(std::string_view key) { return required(key); }

  TableReader table(std::string_view key);
  std::optional<TableReader> optional_table(std::string_view key);
  std::vector<TableReader> tables(std::string_view key);  // array of tables, may be absent
  // Keys of a table whose entries are all tables (e.g. [materials.water], [materials.steel]).
  std::vector<std::pair<std::string, TableReader>> named_tables();

  // Marks a key as accounted for without reading it (a table another component validates).
  void skip(std::string_view key) { used_.insert(std::string(key)); }

  // Throws on the first key no accessor used.
  void finish() const;

 private:
  const toml::node& required(std::string_view key);
  double checked(std::string_view key, const toml::node& node, Range range) const;

  const toml::table& table_;
  std::string prefix_;
  SourceLocation where_;
  std::set<std::string, std::less<>> used_;
  mutable std::set<std::string, std::less<>> known_;  // every key asked for, for suggestions
};

}  // namespace bsmpm
