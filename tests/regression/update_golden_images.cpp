// Re-renders the golden images on purpose (the update_golden_images target, run by
// scripts/regenerate_golden_images): after a change to the renderer meant to change them.
// The test itself only ever compares.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <system_error>

#include "regression/golden_images.hpp"

namespace fs = std::filesystem;

int main() {
  const fs::path work = fs::temp_directory_path() / ("bsmpm_golden_update_" + std::to_string(::getpid()));
  fs::create_directories(work);
  int failures = 0;
  for (const bsmpm::test::Golden& g : bsmpm::test::goldens()) {
    const auto r = bsmpm::test::render_golden(g, work);
    if (r.status != 0) {
      std::cerr << "update_golden_images: rendering " << g.name << " failed (status " << r.status << "):\n"
                << std::ifstream(r.log).rdbuf() << "\n";
      ++failures;
      continue;
    }
    const fs::path golden = fs::path(BSMPM_GOLDEN_DIR) / (g.name + ".png");
    fs::copy_file(r.image, golden, fs::copy_options::overwrite_existing);
    std::printf("wrote %s\n", golden.c_str());
  }
  std::error_code ignored;
  fs::remove_all(work, ignored);
  return failures == 0 ? 0 : 1;
}
