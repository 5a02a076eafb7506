// printf-style formatting into a std::string, for messages and descriptions of any length
// (g++ 12 has no std::format). The compiler checks the arguments against the format.
#pragma once

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

}  // namespace bsmpm
