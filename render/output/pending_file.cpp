#include "output/pending_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace bsmpm::render {

PendingFile::PendingFile(std::string final_path) : final_path_(std::move(final_path)) {
  const fs::path p(final_path_);
  std::string name = ".";
  name.append(p.filename().string()).append(".").append(std::to_string(::getpid())).append(".partial");
  temp_path_ = (p.parent_path() / name).string();
}

PendingFile::~PendingFile() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temp_path_, ignored);
  }
}

void PendingFile::commit() {
  std::error_code ec;
  fs::rename(temp_path_, final_path_, ec);
  if (ec) throw IoError(final_path_ + ": cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

}  // namespace bsmpm::render
