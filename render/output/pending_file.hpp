// An output file written under a temporary name in its destination directory and renamed
// into place only when complete: a failure or an interruption never leaves a half-written
// PNG or movie behind (the destructor removes the temporary file unless commit() ran).
#pragma once

#include <string>

namespace bsmpm::render {

class PendingFile {
 public:
  explicit PendingFile(std::string final_path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  // Where to write: "<dir>/.<name>.<pid>.partial", beside the final file so that the
  // rename stays on one file system (and is atomic).
  const std::string& temp_path() const { return temp_path_; }
  // Renames the temporary file to the final path; throws IoError on failure.
  void commit();

 private:
  std::string final_path_, temp_path_;
  bool committed_ = false;
};

}  // namespace bsmpm::render
