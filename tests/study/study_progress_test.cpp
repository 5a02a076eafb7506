// How a study's progress reads its case directories: a case whose result was there before
// this invocation is "reused" however recently it was written (a second invocation right
// after the first once counted the last case as computed now), and a marker left by an
// earlier invocation does not make a case running or failed.
#include <catch2/catch.hpp>

#include <fstream>

#include "cli/study_progress.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {
void touch(const fs::path& p, const std::string& text = "") {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}
}  // namespace

TEST_CASE("a result written just before the study starts counts as reused, one written after as computed",
          "[study][progress]") {
  const fs::path out = test::scratch_dir("study_progress");
  touch(out / "cases" / "a" / "metrics.json", "{}");   // finished a moment ago
  touch(out / "cases" / "b" / "started");               // an earlier invocation's markers
  touch(out / "cases" / "b" / "failed", "exit status 3");
  cli::StudyProgress progress(out, {"a", "b", "c"}, 2);

  cli::StudyStatus s = progress.poll();
  CHECK(s.done == 1);
  CHECK(s.reused == 1);
  CHECK(s.failed == 0);
  CHECK(s.running == 0);
  CHECK(s.waiting == 2);

  // Now this invocation runs b (it fails again) and c (it completes).
  touch(out / "cases" / "c" / "started");
  CHECK(progress.state("c") == cli::CaseState::kRunning);
  touch(out / "cases" / "c" / "metrics.json", "{}");
  fs::last_write_time(out / "cases" / "b" / "failed",
                      fs::last_write_time(out / "cases" / "b" / "failed") + std::chrono::seconds(1));
  s = progress.poll();
  CHECK(s.done == 2);
  CHECK(s.reused == 1);
  CHECK(s.failed == 1);
  REQUIRE(s.failed_keys.size() == 1);
  CHECK(s.failed_keys[0] == "b");
}
