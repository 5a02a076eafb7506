// Difference metrics between two images of the same size, for regression tests of rendered
// frames, and a diff image that shows where they differ. Channels are compared as 8-bit
// values (R, G, B).
#pragma once

#include <optional>
#include <string>

#include "image/image.hpp"

namespace bsmpm::render {

struct ImageDifference {
  int max_error = 0;            // largest |a - b| over all channels, 0..255
  double rms_error = 0.0;       // sqrt(mean of (a - b)^2 over all channels)
  double psnr_db = 0.0;         // 20 log10(255 / rms); +infinity for identical images
  long differing_pixels = 0;    // pixels where any channel differs
  double differing_share = 0.0; // differing_pixels / (width * height)
  double ssim = 1.0;            // mean structural similarity of the luma (see below)
};

// Throws UsageError when the sizes differ.
//
// SSIM after Wang, Bovik, Sheikh & Simoncelli, "Image quality assessment: from error
// visibility to structural similarity", IEEE Trans. Image Process. 13(4):600-612 (2004):
// on luma Y = 0.299 R + 0.587 G + 0.114 B, an 11x11 Gaussian window (sigma 1.5) at every
// position where it fits, C1 = (0.01 L)^2, C2 = (0.03 L)^2 with L = 255, averaged. An
// image smaller than the window is treated as one window with uniform weights.
ImageDifference compare_images(const Image& a, const Image& b);

// Where the images differ: `a` faded to light grey, differing pixels in red, darker red
// for larger differences (the largest at full red).
Image difference_image(const Image& a, const Image& b);

// Limits a comparison must stay within; unset limits are not checked.
struct ImageTolerance {
  std::optional<int> max_error;
  std::optional<double> rms_error;
  std::optional<double> min_psnr_db;
  std::optional<double> differing_share;
  std::optional<double> min_ssim;

  // "max=8,rms=0.5,psnr=40,share=0.001,ssim=0.99" (any subset, any order); throws
  // UsageError on anything else.
  static ImageTolerance parse(const std::string& text);
  bool any() const { return max_error || rms_error || min_psnr_db || differing_share || min_ssim; }
  // Empty when `d` is within every limit, else what it exceeds, e.g. "rms 0.61 > 0.5".
  std::string violations(const ImageDifference& d) const;
};

}  // namespace bsmpm::render
