// bsmpm compare A.png B.png: difference metrics between two images, with a tolerance.
#include <cmath>
#include <cstdio>
#include <optional>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "image/image_compare.hpp"
#include "image/png_file.hpp"

namespace bsmpm::cli {

namespace {

const char* kHelp =
    "usage: bsmpm compare A.png B.png [--tolerance LIMITS] [--diff DIFF.png]\n"
    "\n"
    "Compares two images of the same size channel by channel (8-bit R, G, B) and prints\n"
    "  max_error         largest difference of a channel, 0..255\n"
    "  rms_error         root mean square difference over all channels\n"
    "  psnr_db           20 log10(255 / rms_error); inf for identical images\n"
    "  differing_pixels  pixels where any channel differs, and their share\n"
    "  ssim              mean structural similarity of the luma (Wang et al. 2004: 11x11\n"
    "                    Gaussian window, sigma 1.5), 1 for identical images\n"
    "This is how rendered frames are regression-tested (tests/regression/).\n"
    "\n"
    "options\n"
    "  --tolerance LIMITS   fail when a limit is exceeded; any of, comma-separated:\n"
    "                       max=N rms=X share=F (at most) psnr=DB ssim=S (at least),\n"
    "                       e.g. --tolerance max=64,rms=1.5,ssim=0.98\n"
    "  --diff DIFF.png      write where they differ: A faded to grey, differences in red\n"
    "                       (darker red for larger ones)\n"
    "\n"
    "exit status: 0 within the tolerance (or none given), 1 tolerance exceeded or sizes\n"
    "differ, 2 bad usage or an unreadable image\n";

}  // namespace

int command_compare(const std::vector<std::string>& argv) {
  Arguments args(argv, {"--help"}, {"--tolerance", "--diff"});
  if (args.help(kHelp)) return kOk;
  if (args.positional().size() != 2) throw UsageError("compare expects two PNG files (see bsmpm compare --help)");
  const std::optional<render::ImageTolerance> tolerance =
      args.has("--tolerance") ? std::optional(render::ImageTolerance::parse(args.option("--tolerance"))) : std::nullopt;
  render::Image a, b;
  try {
    a = render::read_png(args.positional()[0]);
    b = render::read_png(args.positional()[1]);
  } catch (const IoError& e) {
    std::fprintf(stderr, "bsmpm: error: %s\n", e.what());
    return kBadInput;
  }
  if (a.width() != b.width() || a.height() != b.height()) {
    std::printf("size %dx%d %dx%d\nresult: the images differ in size\n", a.width(), a.height(), b.width(), b.height());
    return kFailure;
  }
  const render::ImageDifference d = render::compare_images(a, b);
  std::printf("size %dx%d\n", a.width(), a.height());
  std::printf("max_error %d\n", d.max_error);
  std::printf("rms_error %.6g\n", d.rms_error);
  if (std::isinf(d.psnr_db)) std::printf("psnr_db inf\n");
  else std::printf("psnr_db %.4f\n", d.psnr_db);
  std::printf("differing_pixels %ld\n", d.differing_pixels);
  std::printf("differing_share %.6g\n", d.differing_share);
  std::printf("ssim %.6f\n", d.ssim);
  if (args.has("--diff")) {
    try {
      render::write_png(render::difference_image(a, b), args.option("--diff"));
    } catch (const IoError& e) {
      std::fprintf(stderr, "bsmpm: error: %s\n", e.what());
      return kBadInput;
    }
  }
  if (!tolerance) {
    std::printf("result: %s (no tolerance given)\n", d.differing_pixels == 0 ? "identical" : "different");
    return kOk;
  }
  const std::string exceeded = tolerance->violations(d);
  if (!exceeded.empty()) {
    std::printf("result: exceeds the tolerance: %s\n", exceeded.c_str());
    return kFailure;
  }
  std::printf("result: within the tolerance\n");
  return kOk;
}

}  // namespace bsmpm::cli
