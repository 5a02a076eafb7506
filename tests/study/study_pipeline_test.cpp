// The tiny study end to end through `bsmpm study` and Snakemake on local cores: its CSV,
// a second invocation that runs nothing, a deleted case that alone runs again, cases stopped
// by a full disk that resume from their checkpoints, a failing case reported with its log
// while the other completes, and a bad study that runs nothing.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <thread>

#include "program_runner.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

namespace {

std::string study_command(const std::string& study, const fs::path& out, const std::string& extra = "") {
  return std::string(BSMPM_EXECUTABLE) + " study " + test::source_path("tests/study/" + study) + " --dir '" +
         out.string() + "' --cores 2 " + extra;
}

// The time stamp of every case's summary.json: a case that ran again has a new one.
std::map<std::string, fs::file_time_type> run_stamps(const fs::path& out) {
  std::map<std::string, fs::file_time_type> stamps;
  for (const auto& d : fs::directory_iterator(out / "cases"))
    if (fs::exists(d.path() / "summary.json"))
      stamps[d.path().filename().string()] = fs::last_write_time(d.path() / "summary.json");
  return stamps;
}

}  // namespace

TEST_CASE("a tiny study runs through Snakemake, resumes, and reruns only what is missing", "[study][pipeline]") {
  const fs::path out = test::scratch_dir("tiny_local") / "out";
  REQUIRE(test::run_command(study_command("tiny_study.toml", out), out.string() + ".1.log") == 0);

  const test::Csv csv = test::read_csv(out / "tiny.csv");
  for (const char* column : {"case", "H", "H_label", "grid", "peak_P", "peak_P_time", "peak_Pstar", "impact",
                             "impact_star", "lowest", "cost", "wall_seconds", "steps", "particles",
                             "peak_memory_mb", "particle_steps_per_second", "status", "run_dir"})
    CHECK(std::find(csv.header.begin(), csv.header.end(), column) != csv.header.end());
  REQUIRE(csv.rows.size() == 4);
  // Rows in case order: (H, grid) = (0.15, 0.025), (0.15, 0.02), (0.3, 0.025), (0.3, 0.02).
  for (std::size_t r = 0; r < 4; ++r) {
    CHECK(csv.rows[r].at("status") == "completed");
    CHECK(csv.number(r, "steps") > 1000);
    CHECK(csv.number(r, "wall_seconds") > 0.0);
    CHECK(csv.number(r, "peak_memory_mb") > 1.0);
    CHECK(fs::exists(out / csv.rows[r].at("run_dir") / "run.h5"));
  }
  CHECK(csv.number(2, "H") == 0.3);
  CHECK(csv.number(1, "grid") == 0.02);
  for (std::size_t g = 0; g < 2; ++g) {
    // A column twice as tall holds twice the particles and strikes the wall harder.
    CHECK(csv.number(2 + g, "particles") == 2 * csv.number(g, "particles"));
    CHECK(csv.number(2 + g, "peak_P") > 1.5 * csv.number(g, "peak_P"));
    // H = 300 mm reaches the wall at T* = 2.5 (Lobovsky et al. 2014: 2.5 at z = 30 mm).
    CHECK(csv.number(2 + g, "impact_star") == Approx(2.5).margin(0.3));
    CHECK(csv.number(2 + g, "lowest") <= 0.0);
  }
  CHECK(fs::exists(out / "tiny_peak_vs_H.png"));
  CHECK(fs::exists(out / "plan.json"));
  const auto first = run_stamps(out);
  REQUIRE(first.size() == 4);

  // Again: every case is found, none runs. Its progress (the "study" lines on stderr, the
  // last one always written) is there, and gone with --quiet, which keeps the result lines.
  REQUIRE(test::run_command(study_command("tiny_study.toml", out), out.string() + ".2.log") == 0);
  const std::string again = test::read_text(out.string() + ".2.log");
  CHECK(again.find("4 reused, 0 computed now") != std::string::npos);
  CHECK(again.find("4/4 done") != std::string::npos);
  CHECK(run_stamps(out) == first);
  REQUIRE(test::run_command(study_command("tiny_study.toml", out, "--quiet"), out.string() + ".2q.log") == 0);
  const std::string quiet = test::read_text(out.string() + ".2q.log");
  CHECK(quiet.find("4 reused, 0 computed now") != std::string::npos);
  CHECK(quiet.find("/4 done") == std::string::npos);

  // One case's result deleted: that case alone runs again.
  const std::string gone = first.begin()->first;
  fs::remove_all(out / "cases" / gone);
  REQUIRE(test::run_command(study_command("tiny_study.toml", out), out.string() + ".3.log") == 0);
  CHECK(test::read_text(out.string() + ".3.log").find("3 reused, 1 computed now") != std::string::npos);
  const auto third = run_stamps(out);
  REQUIRE(third.size() == 4);
  for (const auto& [key, stamp] : first)
    if (key != gone) CHECK(third.at(key) == stamp);
  CHECK(test::read_csv(out / "tiny.csv").rows.size() == 4);
}

TEST_CASE("a case stopped by a full disk continues from its checkpoint when the study runs again", "[study][pipeline]") {
  // Files limited to 400 KiB: each case's run.h5 stops after a frame or two (exit 4, with a
  // checkpoint); with room again, each case resumes from its checkpoint, to the metrics of
  // the same study run with room.
  const fs::path out = test::scratch_dir("tiny_full_disk") / "out";
  const std::string narrow = " --axis grid=0.025 --keep-going";
  CHECK(test::run_command("prlimit --fsize=409600 -- " + study_command("tiny_study.toml", out, narrow),
                          out.string() + ".1.log") == 1);
  const std::string stopped = test::read_text(out.string() + ".1.log");
  INFO(stopped);
  CHECK(stopped.find("failed: bsmpm: error: out of space: cases/") != std::string::npos);
  std::size_t with_checkpoint = 0;
  for (const auto& d : fs::directory_iterator(out / "cases")) {
    CHECK(test::read_text(d.path() / "run.log").find("bsmpm: error: out of space: ") != std::string::npos);
    with_checkpoint += fs::exists(d.path() / "checkpoint.h5");
  }
  REQUIRE(with_checkpoint == 2);
  REQUIRE(test::run_command(study_command("tiny_study.toml", out, narrow), out.string() + ".2.log") == 0);
  for (const auto& d : fs::directory_iterator(out / "cases"))
    CHECK(test::read_text(d.path() / "run.log").find("resume   cases/" + d.path().filename().string() + " at step ") !=
          std::string::npos);
  const fs::path reference = test::scratch_dir("tiny_with_room") / "out";
  REQUIRE(test::run_command(study_command("tiny_study.toml", reference, narrow), reference.string() + ".log") == 0);
  const test::Csv resumed = test::read_csv(out / "tiny.csv"), fresh = test::read_csv(reference / "tiny.csv");
  REQUIRE(resumed.rows.size() == 2);
  REQUIRE(fresh.rows.size() == 2);
  for (std::size_t r = 0; r < 2; ++r)
    for (const char* metric : {"peak_P", "peak_P_time", "impact", "lowest", "steps"}) {
      INFO(metric);
      CHECK(resumed.rows[r].at(metric) == fresh.rows[r].at(metric));
    }
}

TEST_CASE("a failing case is reported with its log while the others complete", "[study][pipeline]") {
  // A directory name a shell would split or run (the partial CSV is aggregated by a child
  // process given its arguments one by one, never through a shell line).
  const fs::path out = test::scratch_dir("failing") / "out dir; touch pwned";
  const fs::path log = out.string() + ".log";
  CHECK(test::run_command(study_command("failing_study.toml", out, "--keep-going"), log) == 1);
  const std::string text = test::read_text(log);
  INFO(text);
  // g = 1e6 m/s2 is numerically unstable at this time step: bsmpm run exits 3.
  CHECK(text.find("failed: bsmpm: error: numerical instability") != std::string::npos);
  CHECK(text.find("g = 1e+06") != std::string::npos);
  const auto at = text.find("log: ");
  REQUIRE(at != std::string::npos);
  const std::string case_log = text.substr(at + 5, text.find('\n', at) - at - 5);
  CHECK(fs::exists(case_log));
  CHECK(test::read_text(case_log).find("numerical instability") != std::string::npos);
  const test::Csv csv = test::read_csv(out / "failing.csv");
  REQUIRE(csv.rows.size() == 2);
  CHECK(csv.rows[0].at("status") == "completed");
  CHECK(csv.number(0, "peak_P") > 1000.0);
  CHECK(csv.rows[1].at("status") == "failed");
  CHECK(csv.rows[1].at("peak_P").empty());
  CHECK(!fs::exists("pwned"));
  CHECK(!fs::exists(out.parent_path() / "pwned"));
}

TEST_CASE("a bad study file is an error naming file:line:column, and nothing runs", "[study][errors]") {
  const fs::path dir = test::scratch_dir("bad_study");
  const fs::path study = dir / "bad.toml";
  {
    std::ofstream f(study);
    f << "[study]\nname = \"bad\"\nscene = \"" << test::scene_path("lobovsky_h300.toml") << "\"\n"
      << "[[axes]]\nname = \"g\"\nkey = \"gravity.gg\"\nvalues = [9.81]\n";
  }
  const fs::path out = dir / "out";
  const std::string command = std::string(BSMPM_EXECUTABLE) + " study " + study.string() + " --dir " + out.string();
  CHECK(test::run_command(command, dir / "log") == 2);
  const std::string text = test::read_text(dir / "log");
  CHECK(text.find(study.string() + ":7:11: gravity.gg: unknown key") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("Ctrl-C stops a study with exit status 130, and the same command resumes it", "[study][pipeline]") {
  // As a terminal does: SIGINT to the whole process group (bsmpm, Snakemake and the runs),
  // once the first case has started (the group is stopped while the signal goes out, so
  // that no case finishes in between).
  const fs::path out = test::scratch_dir("tiny_interrupted") / "out";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    setpgid(0, 0);
    if (!freopen((out.string() + ".1.log").c_str(), "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(126);
    const std::string study = test::source_path("tests/study/tiny_study.toml"), dir = out.string();
    execl(BSMPM_EXECUTABLE, BSMPM_EXECUTABLE, "study", study.c_str(), "--dir", dir.c_str(), "--cores", "2", nullptr);
    _exit(127);
  }
  setpgid(pid, pid);  // whichever of the two runs first
  auto started = [&] {
    std::error_code ec;
    if (!fs::exists(out / "cases", ec)) return false;
    for (const auto& d : fs::directory_iterator(out / "cases", ec))
      if (fs::exists(d.path() / "started")) return true;
    return false;
  };
  int status = 0;
  bool signalled = false;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (started()) {
      kill(-pid, SIGSTOP);
      kill(-pid, SIGINT);
      kill(-pid, SIGCONT);
      signalled = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (signalled) waitpid(pid, &status, 0);
  REQUIRE(signalled);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  // The same command resumes: every case done, the CSV written.
  REQUIRE(test::run_command(study_command("tiny_study.toml", out), out.string() + ".2.log") == 0);
  CHECK(test::read_csv(out / "tiny.csv").rows.size() == 4);
}
