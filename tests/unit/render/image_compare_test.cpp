// compare: metrics checked against hand-computed values, tolerances, and the program's
// exit codes (0 within, 1 exceeded, 2 unreadable input).
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "image/image_compare.hpp"
#include "image/png_file.hpp"
#include "test_support.hpp"

using namespace bsmpm;
using namespace bsmpm::render;
namespace fs = std::filesystem;

namespace {

// A smooth test picture: gradients in all three channels.
Image gradient(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.set(x, y, {static_cast<std::uint8_t>(255 * x / (w - 1)), static_cast<std::uint8_t>(255 * y / (h - 1)),
                       static_cast<std::uint8_t>((x + y) % 256)});
  return image;
}

const fs::path& temp_dir() { return test::scratch_root("compare"); }

int run_compare(const std::string& args, std::string& output) {
  const test::ProgramResult r = test::run_program("compare " + args, temp_dir() / "compare.log");
  output = r.output;
  REQUIRE(r.status >= 0);  // it exited (not killed by a signal)
  return r.status;
}

}  // namespace

TEST_CASE("Identical images: no error, infinite PSNR, SSIM 1", "[render][compare]") {
  const Image a = gradient(64, 48);
  const ImageDifference d = compare_images(a, a);
  CHECK(d.max_error == 0);
  CHECK(d.rms_error == 0.0);
  CHECK(std::isinf(d.psnr_db));
  CHECK(d.differing_pixels == 0);
  CHECK(d.differing_share == 0.0);
  CHECK(d.ssim == 1.0);
}

TEST_CASE("One pixel off by 100 in one channel gives the hand-computed metrics", "[render][compare]") {
  const int w = 64, h = 48;
  const Image a = gradient(w, h);
  Image b = a;
  Rgb c = b.at(10, 20);
  c.g = static_cast<std::uint8_t>(c.g >= 100 ? c.g - 100 : c.g + 100);
  b.set(10, 20, c);
  const ImageDifference d = compare_images(a, b);
  // RMS over every channel of every pixel: sqrt(100^2 / (3 W H)).
  const double rms = std::sqrt(100.0 * 100.0 / (3.0 * w * h));
  CHECK(d.max_error == 100);
  CHECK(d.rms_error == Approx(rms).epsilon(1e-12));
  CHECK(d.rms_error == Approx(1.0416666).epsilon(1e-6));
  CHECK(d.psnr_db == Approx(20.0 * std::log10(255.0 / rms)).epsilon(1e-12));
  CHECK(d.psnr_db == Approx(47.7762).epsilon(1e-5));
  CHECK(d.differing_pixels == 1);
  CHECK(d.differing_share == Approx(1.0 / (w * h)));
  CHECK(d.ssim < 1.0);
  CHECK(d.ssim > 0.95);

  // The diff image marks exactly that pixel in full red.
  const Image diff = difference_image(a, b);
  CHECK(diff.at(10, 20) == Rgb{255, 0, 0});
  CHECK(diff.at(11, 20).r == diff.at(11, 20).g);  // grey elsewhere

  ImageTolerance t = ImageTolerance::parse("max=99");
  CHECK(t.violations(d) == "max 100 > 99");
  CHECK(ImageTolerance::parse("max=100,rms=1.1,share=0.001").violations(d).empty());
  CHECK_FALSE(ImageTolerance::parse("psnr=50").violations(d).empty());
  CHECK_FALSE(ImageTolerance::parse("ssim=0.9999999").violations(d).empty());
  CHECK_THROWS_AS(ImageTolerance::parse("maxx=3"), UsageError);
  CHECK_THROWS_AS(ImageTolerance::parse("rms=-1"), UsageError);
  CHECK_THROWS_AS(compare_images(a, gradient(w + 1, h)), UsageError);
}

TEST_CASE("SSIM falls with noise and stays 1 for an identical copy", "[render][compare]") {
  const Image a = gradient(80, 60);
  Image noisy = a;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 80; ++x)
      if ((x * 7 + y * 13) % 5 == 0) {
        Rgb c = noisy.at(x, y);
        c.r = static_cast<std::uint8_t>(255 - c.r);
        noisy.set(x, y, c);
      }
  const double s = compare_images(a, noisy).ssim;
  CHECK(s < 0.9);
  CHECK(s > 0.0);
  CHECK(compare_images(noisy, noisy).ssim == 1.0);
}

TEST_CASE("bsmpm compare prints the metrics and exits 0, 1 or 2", "[render][compare][cli]") {
  const fs::path dir = temp_dir();
  const Image a = gradient(64, 48);
  Image b = a;
  b.set(10, 20, {0, 0, 0});
  write_png(a, (dir / "a.png").string());
  write_png(b, (dir / "b.png").string());
  const std::string pa = (dir / "a.png").string(), pb = (dir / "b.png").string();
  std::string out;

  CHECK(run_compare(pa + " " + pa + " --tolerance max=0", out) == 0);
  CHECK(out.find("max_error 0\n") != std::string::npos);
  CHECK(out.find("psnr_db inf\n") != std::string::npos);
  CHECK(out.find("result: within the tolerance") != std::string::npos);

  const fs::path diff = dir / "diff.png";
  CHECK(run_compare(pa + " " + pb + " --tolerance rms=0.01 --diff " + diff.string(), out) == 1);
  CHECK(out.find("differing_pixels 1\n") != std::string::npos);
  CHECK(out.find("result: exceeds the tolerance: rms") != std::string::npos);
  REQUIRE(fs::exists(diff));
  CHECK(read_png(diff.string()).at(10, 20) == Rgb{255, 0, 0});

  CHECK(run_compare(pa + " " + pb, out) == 0);  // no tolerance: report only
  CHECK(run_compare(pa + " " + (dir / "missing.png").string(), out) == 2);
  CHECK(out.find("missing.png: no such file") != std::string::npos);
  CHECK(run_compare(pa + " " + pb + " --tolerance fuzzy", out) == 2);
  write_png(gradient(32, 48), (dir / "small.png").string());
  CHECK(run_compare(pa + " " + (dir / "small.png").string(), out) == 1);
  CHECK(out.find("differ in size") != std::string::npos);
  fs::remove_all(dir);
}
