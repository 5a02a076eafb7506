// Reading a file the user named (a scene, a study, a measured series): its whole text, or an
// InputError that says why not (no such file, a directory, no permission).
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace bsmpm {

// `what` names the file's kind in the message: "the scene file".
inline std::string read_input_file(const std::string& path, const std::string& what) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(path + ": cannot read " + what + ": it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int cause = errno != 0 ? errno : ENOENT;
    throw InputError(path + ": cannot read " + what + ": " + std::strerror(cause));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read " + what + ": " + std::strerror(errno != 0 ? errno : EIO));
  return text.str();
}

}  // namespace bsmpm
