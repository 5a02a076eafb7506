// printf-style formatting into a std::string, for messages and descriptions of any length
// (g++ 12 has no std::format). The compiler checks the arguments against the format. And
// the shortest round-trip text of a double, for files other programs read back; sizes in bytes
// for people.
#pragma once

#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace bsmpm {

__attribute__((format(printf, 1, 2))) inline std::string format(const char* pattern, ...) {
  va_list args, again;
  va_start(args, pattern);
  va_copy(again, args);
  const int length = std::vsnprintf(nullptr, 0, pattern, args);
  va_end(args);
  std::string out(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length > 0) std::vsnprintf(out.data(), out.size() + 1, pattern, again);
  va_end(again);
  return out;
}

// The shortest text that reads back as the same double (std::to_chars): 0.3, 1e-05, 2.
inline std::string shortest(double x) {
  char digits[32];  // to_chars writes at most 24 characters for a double
  return std::string(digits, std::to_chars(digits, digits + sizeof digits, x).ptr);
}

// "1.5 GiB", "320 MiB", "512 B": bytes in binary units, three significant digits.
inline std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 5) {
    bytes /= 1024.0;
    ++u;
  }
  return format(u == 0 || bytes >= 100.0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
}

}  // namespace bsmpm
