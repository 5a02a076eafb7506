// JSON for the small files other programs read (summary.json, a study's plan and metrics):
// a writer for nested objects and arrays, and a reader for flat objects of scalars (and arrays of them). Numbers
// are written in their shortest round-trip form; NaN and infinities as null.
#pragma once

#include <map>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace bsmpm {

class JsonWriter {
 public:
  JsonWriter& begin_object() { return open('{'); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array() { return open('['); }
  JsonWriter& end_array() { return close(']'); }
  JsonWriter& key(const std::string& name);  // inside an object, before its value
  JsonWriter& value(const std::string& text);
  JsonWriter& value(const char* text) { return value(std::string(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(long number);
  JsonWriter& value(int number) { return value(static_cast<long>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& null();
  template <class T>
  JsonWriter& field(const std::string& name, const T& v) { return key(name).value(v); }

  std::string str() const { return out_.str(); }

 private:
  void separate();  // the comma and line break before an element
  JsonWriter& open(char bracket);
  JsonWriter& close(char bracket);
  std::ostringstream out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

std::string json_quoted(const std::string& text);
std::string json_number(double number);  // shortest round-trip form, "null" if not finite

// The value of one key of a flat object: null (monostate), a boolean, a number or a string.
using JsonScalar = std::variant<std::monostate, bool, double, std::string>;

// Parses `{"key": scalar, ...}`; throws IoError naming `source` on anything else.
std::map<std::string, JsonScalar> parse_flat_json_object(const std::string& text, const std::string& source);

// Parses `[{...}, ...]`, an array of flat objects; throws IoError naming `source` on anything else.
std::vector<std::map<std::string, JsonScalar>> parse_flat_json_array(const std::string& text, const std::string& source);

}  // namespace bsmpm
