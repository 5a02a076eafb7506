// The tiny study through a real one-node Slurm cluster. ctest runs this suite inside
// `scripts/slurm_cluster run --`, which starts the cluster, exports SLURM_CONF and shuts
// the cluster down afterwards, failed or not (plus a cleanup test, should this be killed).
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <string>
#include <thread>

#include "program_runner.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

TEST_CASE("a tiny study runs as Slurm jobs, visible to squeue while they run", "[study][slurm]") {
  REQUIRE(std::getenv("SLURM_CONF") != nullptr);  // run through scripts/slurm_cluster run
  // The study's runs predict their wall time from the tests' calibration in the build
  // directory, never from the user's own (tests/CMakeLists.txt).
  const char* calibration = std::getenv("BSMPM_CALIBRATION");
  REQUIRE(calibration != nullptr);
  CHECK(std::string(calibration).rfind(BSMPM_BUILD_DIR, 0) == 0);
  const fs::path dir = test::scratch_dir("tiny_slurm");
  const fs::path out = dir / "out";
  const std::string study = std::string(BSMPM_EXECUTABLE) + " study " + test::source_path("tests/study/tiny_study.toml") +
                            " --dir " + out.string() + " --slurm --partition debug --time-limit 10";
  const auto start = std::chrono::steady_clock::now();
  auto running = std::async(std::launch::async, [&] { return test::run_command(study, dir / "study.log"); });

  // Poll the queue while the study runs: its jobs must show up there.
  int jobs_seen = 0;
  while (running.wait_for(std::chrono::milliseconds(500)) != std::future_status::ready) {
    REQUIRE(std::chrono::steady_clock::now() - start < std::chrono::minutes(5));
    if (test::run_command("squeue -h -o '%i %j %T'", dir / "squeue.txt") == 0) {
      const std::string queue = test::read_text(dir / "squeue.txt");
      int lines = 0;
      for (char c : queue) lines += c == '\n';
      jobs_seen = std::max(jobs_seen, lines);
    }
  }
  const int status = running.get();
  INFO(test::read_text(dir / "study.log"));
  REQUIRE(status == 0);
  CHECK(jobs_seen >= 1);
  const test::Csv csv = test::read_csv(out / "tiny.csv");
  REQUIRE(csv.rows.size() == 4);
  for (const auto& row : csv.rows) CHECK(row.at("status") == "completed");
  // Snakemake's Slurm executor logged one sbatch submission per case.
  int submitted = 0;
  for (const auto& d : fs::recursive_directory_iterator(out / ".snakemake" / "slurm_logs"))
    submitted += d.is_regular_file();
  CHECK(submitted == 4);
}
