#include "io/json.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm {

std::string json_quoted(const std::string& text) {
  std::string s = "\"";
  for (const unsigned char c : text) {
    if (c == '"' || c == '\\') {
      s += '\\';
      s += static_cast<char>(c);
    } else if (c == '\n') {
      s += "\\n";
    } else if (c == '\t') {
      s += "\\t";
    } else if (c < 0x20) {
      s += format("\\u%04x", c);
    } else {
      s += static_cast<char>(c);
    }
  }
  return s + "\"";
}

std::string json_number(double number) {
  return std::isfinite(number) ? shortest(number) : "null";
}

void JsonWriter::separate() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (first_.empty()) return;
  if (!first_.back()) out_ << ",";
  out_ << "\n" << std::string(2 * first_.size(), ' ');
  first_.back() = false;
}

JsonWriter& JsonWriter::open(char bracket) {
  separate();
  out_ << bracket;
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::close(char bracket) {
  const bool empty = first_.back();
  first_.pop_back();
  if (!empty) out_ << "\n" << std::string(2 * first_.size(), ' ');
  out_ << bracket;
  if (first_.empty()) out_ << "\n";
  return *this;
}

JsonWriter& JsonWriter::key(const std::string& name) {
  separate();
  out_ << json_quoted(name) << ": ";
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& text) {
  separate();
  out_ << json_quoted(text);
  return *this;
}

JsonWriter& JsonWriter::value(double number) {
  separate();
  out_ << json_number(number);
  return *this;
}

JsonWriter& JsonWriter::value(long number) {
  separate();
  out_ << number;
  return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
  separate();
  out_ << (flag ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::null() {
  separate();
  out_ << "null";
  return *this;
}

namespace {

class FlatParser {
 public:
  FlatParser(const std::string& text, const std::string& source) : s_(text), source_(source) {}

  std::map<std::string, JsonScalar> object() {
    expected_ = "a flat JSON object";
    auto out = members();
    end();
    return out;
  }

  std::vector<std::map<std::string, JsonScalar>> array() {
    expected_ = "a JSON array of flat objects";
    std::vector<std::map<std::string, JsonScalar>> out;
    expect('[');
    if (peek() == ']') {
      ++i_;
      end();
      return out;
    }
    while (true) {
      out.push_back(members());
      const char c = next();
      if (c == ']') break;
      if (c != ',') fail("expected ',' or ']'");
    }
    end();
    return out;
  }

 private:
  std::map<std::string, JsonScalar> members() {
    std::map<std::string, JsonScalar> out;
    expect('{');
    if (peek() == '}') {
      ++i_;
      return out;
    }
    while (true) {
      const std::string k = string();
      expect(':');
      out[k] = scalar();
      const char c = next();
      if (c == '}') return out;
      if (c != ',') fail("expected ',' or '}'");
    }
  }

  void end() {
    if (peek() != '\0') fail("unexpected text after the value");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw IoError(source_ + ": not " + expected_ + " (" + what + " at offset " + std::to_string(i_) + ")");
  }

  char peek() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
    return i_ < s_.size() ? s_[i_] : '\0';
  }
  char next() {
    const char c = peek();
    if (c) ++i_;
    return c;
  }
  void expect(char c) {
    if (next() != c) fail(std::string("expected '") + c + "'");
  }

  std::string string() {
    expect('"');
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      char c = s_[i_++];
      if (c == '\\') {
        if (i_ >= s_.size()) break;
        const char e = s_[i_++];
        if (e == 'n') c = '\n';
        else if (e == 't') c = '\t';
        else if (e == 'u') {
          if (i_ + 4 > s_.size()) fail("truncated escape");
          unsigned code = 0;
          const auto r = std::from_chars(s_.data() + i_, s_.data() + i_ + 4, code, 16);
          if (r.ec != std::errc() || r.ptr != s_.data() + i_ + 4) fail("a bad \\u escape");
          c = static_cast<char>(code);
          i_ += 4;
        } else c = e;
      }
      out += c;
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return out;
  }

  JsonScalar scalar() {
    const char c = peek();
    if (c == '"') return string();
    for (const auto& [word, value] : {std::pair<const char*, JsonScalar>{"null", std::monostate{}},
                                      {"true", true}, {"false", false}}) {
      const std::string w(word);
      if (s_.compare(i_, w.size(), w) == 0) {
        i_ += w.size();
        return value;
      }
    }
    double x = 0.0;
    const auto result = std::from_chars(s_.data() + i_, s_.data() + s_.size(), x);
    if (result.ec != std::errc()) fail("expected a value");
    i_ = static_cast<std::size_t>(result.ptr - s_.data());
    return x;
  }

  const std::string& s_;
  const std::string& source_;
  std::string expected_;
  std::size_t i_ = 0;
};

}  // namespace

std::map<std::string, JsonScalar> parse_flat_json_object(const std::string& text, const std::string& source) {
  return FlatParser(text, source).object();
}

std::vector<std::map<std::string, JsonScalar>> parse_flat_json_array(const std::string& text, const std::string& source) {
  return FlatParser(text, source).array();
}

}  // namespace bsmpm
