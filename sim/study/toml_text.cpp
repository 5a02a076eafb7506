#include "study/toml_text.hpp"

#include <cmath>
#include <regex>

#include "core/format.hpp"
#include "parameters/table_reader.hpp"

namespace bsmpm {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string float_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::string s = shortest(x);
  // Keep it a float in TOML: "1" would read back as an integer.
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string key_text(const std::string& key) {
  static const std::regex bare("[A-Za-z0-9_-]+");
  return std::regex_match(key, bare) ? key : quoted(key);
}

}  // namespace

std::string toml_value_text(const toml::node& node) {
  if (const auto* s = node.as_string()) return quoted(s->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) return float_text(f->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < a->size(); ++k) out += (k ? ", " : "") + toml_value_text(*a->get(k));
    return out + "]";
  }
  if (const auto* t = node.as_table()) {
    std::string out = "{";
    bool first = true;
    for (auto&& [k, v] : *t) {
      out += (first ? " " : ", ") + key_text(std::string(k.str())) + " = " + toml_value_text(v);
      first = false;
    }
    return out + (first ? "}" : " }");
  }
  throw SceneError(location_of(node), "", "dates and times cannot be scene overrides");
}

}  // namespace bsmpm
