// When an HDF5 write fails for lack of room anyway (the room the run writer keeps did not
// foresee it), the error says so (an OutOfSpaceError, not clean, naming the cause) and the
// program still exits normally: HDF5 1.10 keeps the identifier of a file whose close failed,
// and its clean-up at exit closes it again and crashes (SIGSEGV in H5_term_library: without
// h5::leave_failed_objects_at_exit() the child below dies of it). A program of its own: the
// child must make the first HDF5 call of its process.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "io/hdf5.hpp"
#include "test_support.hpp"

using namespace bsmpm;
namespace fs = std::filesystem;

TEST_CASE("A failed HDF5 write is an out-of-space error and the program still exits normally", "[io][disk]") {
  const fs::path dir = test::scratch_dir("hdf5_failure");
  // The child's report comes through a pipe: at its exit the child removes the scratch
  // directory it inherited.
  int report[2];
  REQUIRE(pipe(report) == 0);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    h5::leave_failed_objects_at_exit();
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{256 * 1024, 256 * 1024};
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(10);
    close(report[0]);
    std::FILE* out = fdopen(report[1], "w");
    if (!out) _exit(11);
    int outcome = 12;  // no error at all
    try {
      h5::Handle file = h5::create_file((dir / "run.h5").string());
      const std::vector<double> values(4096, 1.0);  // 32 KiB a dataset
      for (int k = 0; k < 64; ++k) {
        const std::string name = std::to_string(k);  // ("d" + to_string trips g++ 12's -Wrestrict)
        h5::write_dataset(file, name, values.data(), values.size(), 1);
        h5::flush(file, "run.h5");
      }
    } catch (const OutOfSpaceError& e) {
      std::fprintf(out, "%s\n%d\n", e.what(), e.clean() ? 1 : 0);
      outcome = 0;
    } catch (const std::exception& e) {
      std::fprintf(out, "%s\n", e.what());
      outcome = 13;  // the wrong kind of error
    }
    std::fclose(out);
    std::exit(outcome);  // runs the clean-up at exit, where HDF5 crashed
  }
  close(report[1]);
  std::string text;
  char buffer[512];
  for (ssize_t n; (n = read(report[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  close(report[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  INFO(text);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(text.find("failed: File too large") != std::string::npos);
  CHECK(text.find("\n0\n") != std::string::npos);  // not clean: the write failed half-way
}
