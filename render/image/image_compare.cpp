#include "image/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm::render {

namespace {

std::vector<double> luma(const Image& image) {
  std::vector<double> y(static_cast<std::size_t>(image.width()) * image.height());
  const std::uint8_t* p = image.data();
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = 0.299 * p[3 * k] + 0.587 * p[3 * k + 1] + 0.114 * p[3 * k + 2];
  return y;
}

// Gaussian-weighted local statistics via separable filtering, 'valid' positions only.
class WindowFilter {
 public:
  WindowFilter(int width, int height) : width_(width), height_(height) {
    double sum = 0.0;
    for (int k = 0; k < kSize; ++k) {
      const double d = k - kSize / 2;
      weights_[k] = std::exp(-d * d / (2.0 * kSigma * kSigma));
      sum += weights_[k];
    }
    for (double& w : weights_) w /= sum;
  }
  int out_width() const { return width_ - kSize + 1; }
  int out_height() const { return height_ - kSize + 1; }

  std::vector<double> apply(const std::vector<double>& in) const {
    const int ow = out_width(), oh = out_height();
    std::vector<double> rows(static_cast<std::size_t>(height_) * ow), out(static_cast<std::size_t>(oh) * ow);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < ow; ++x) {
        double s = 0.0;
        for (int k = 0; k < kSize; ++k) s += weights_[k] * in[static_cast<std::size_t>(y) * width_ + x + k];
        rows[static_cast<std::size_t>(y) * ow + x] = s;
      }
    for (int y = 0; y < oh; ++y)
      for (int x = 0; x < ow; ++x) {
        double s = 0.0;
        for (int k = 0; k < kSize; ++k) s += weights_[k] * rows[static_cast<std::size_t>(y + k) * ow + x];
        out[static_cast<std::size_t>(y) * ow + x] = s;
      }
    return out;
  }

  static constexpr int kSize = 11;
  static constexpr double kSigma = 1.5;

 private:
  int width_, height_;
  double weights_[kSize];
};

double ssim_term(double mx, double my, double sxx, double syy, double sxy) {
  constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  return ((2 * mx * my + c1) * (2 * sxy + c2)) / ((mx * mx + my * my + c1) * (sxx + syy + c2));
}

double mean_ssim(const Image& a, const Image& b) {
  const std::vector<double> x = luma(a), y = luma(b);
  const std::size_t n = x.size();
  if (a.width() < WindowFilter::kSize || a.height() < WindowFilter::kSize) {
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < n; ++k) {
      mx += x[k];
      my += y[k];
    }
    mx /= n;
    my /= n;
    double sxx = 0, syy = 0, sxy = 0;
    for (std::size_t k = 0; k < n; ++k) {
      sxx += (x[k] - mx) * (x[k] - mx);
      syy += (y[k] - my) * (y[k] - my);
      sxy += (x[k] - mx) * (y[k] - my);
    }
    return ssim_term(mx, my, sxx / n, syy / n, sxy / n);
  }
  const WindowFilter filter(a.width(), a.height());
  std::vector<double> xx(n), yy(n), xy(n);
  for (std::size_t k = 0; k < n; ++k) {
    xx[k] = x[k] * x[k];
    yy[k] = y[k] * y[k];
    xy[k] = x[k] * y[k];
  }
  const auto mx = filter.apply(x), my = filter.apply(y);
  const auto exx = filter.apply(xx), eyy = filter.apply(yy), exy = filter.apply(xy);
  double sum = 0.0;
  for (std::size_t k = 0; k < mx.size(); ++k)
    sum += ssim_term(mx[k], my[k], exx[k] - mx[k] * mx[k], eyy[k] - my[k] * my[k], exy[k] - mx[k] * my[k]);
  return sum / static_cast<double>(mx.size());
}

void require_same_size(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw UsageError("the images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                     " and " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
}

}  // namespace

ImageDifference compare_images(const Image& a, const Image& b) {
  require_same_size(a, b);
  ImageDifference d;
  const std::size_t pixels = static_cast<std::size_t>(a.width()) * a.height();
  const std::uint8_t* pa = a.data();
  const std::uint8_t* pb = b.data();
  double squares = 0.0;
  for (std::size_t k = 0; k < pixels; ++k) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = std::abs(static_cast<int>(pa[3 * k + c]) - static_cast<int>(pb[3 * k + c]));
      worst = std::max(worst, e);
      squares += static_cast<double>(e) * e;
    }
    d.max_error = std::max(d.max_error, worst);
    if (worst > 0) ++d.differing_pixels;
  }
  d.rms_error = pixels ? std::sqrt(squares / (3.0 * pixels)) : 0.0;
  d.psnr_db = d.rms_error > 0 ? 20.0 * std::log10(255.0 / d.rms_error) : std::numeric_limits<double>::infinity();
  d.differing_share = pixels ? static_cast<double>(d.differing_pixels) / pixels : 0.0;
  d.ssim = pixels ? mean_ssim(a, b) : 1.0;
  return d;
}

Image difference_image(const Image& a, const Image& b) {
  require_same_size(a, b);
  Image out(a.width(), a.height());
  int largest = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb p = a.at(x, y), q = b.at(x, y);
      largest = std::max({largest, std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
    }
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb p = a.at(x, y), q = b.at(x, y);
      const int e = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
      if (e == 0) {
        // Faded reference: luma squeezed into 200..255 keeps the picture recognisable.
        const int l = (299 * p.r + 587 * p.g + 114 * p.b) / 1000;
        const auto v = static_cast<std::uint8_t>(200 + l * 55 / 255);
        out.set(x, y, {v, v, v});
      } else {
        // 1 level -> light red, the largest difference -> full red.
        const auto fade = static_cast<std::uint8_t>(160 - 160 * e / largest);
        out.set(x, y, {255, fade, fade});
      }
    }
  return out;
}

ImageTolerance ImageTolerance::parse(const std::string& text) {
  ImageTolerance t;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    double value = 0.0;
    try {
      if (eq == std::string::npos) throw std::invalid_argument("no value");
      std::size_t used = 0;
      value = std::stod(item.substr(eq + 1), &used);
      if (used != item.size() - eq - 1 || !std::isfinite(value) || value < 0) throw std::invalid_argument("bad");
    } catch (const std::exception&) {
      throw UsageError("--tolerance: '" + item + "' is not KEY=VALUE with a number >= 0 (keys: max, rms, psnr, share, ssim)");
    }
    if (key == "max") t.max_error = static_cast<int>(value);
    else if (key == "rms") t.rms_error = value;
    else if (key == "psnr") t.min_psnr_db = value;
    else if (key == "share") t.differing_share = value;
    else if (key == "ssim") t.min_ssim = value;
    else throw UsageError("--tolerance: unknown key '" + key + "' (keys: max, rms, psnr, share, ssim)");
  }
  if (!t.any()) throw UsageError("--tolerance needs at least one KEY=VALUE (keys: max, rms, psnr, share, ssim)");
  return t;
}

std::string ImageTolerance::violations(const ImageDifference& d) const {
  std::string out;
  auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
  if (max_error && d.max_error > *max_error)
    add("max " + std::to_string(d.max_error) + " > " + std::to_string(*max_error));
  if (rms_error && d.rms_error > *rms_error) add("rms " + format("%.4g", d.rms_error) + " > " + format("%g", *rms_error));
  if (min_psnr_db && d.psnr_db < *min_psnr_db)
    add("psnr " + format("%.2f", d.psnr_db) + " dB < " + format("%g", *min_psnr_db) + " dB");
  if (differing_share && d.differing_share > *differing_share)
    add("share " + format("%.4g", d.differing_share) + " > " + format("%g", *differing_share));
  if (min_ssim && d.ssim < *min_ssim) add("ssim " + format("%.5f", d.ssim) + " < " + format("%g", *min_ssim));
  return out;
}

}  // namespace bsmpm::render
