// An 8-bit RGB image, rows top to bottom: what the renderer produces, PNG files hold, the
// movie encoder consumes and the comparison reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bsmpm::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgb fill = {255, 255, 255})
      : width_(width), height_(height), pixels_(3 * static_cast<std::size_t>(width) * height) {
    for (std::size_t k = 0; k < pixels_.size(); k += 3) {
      pixels_[k] = fill.r;
      pixels_[k + 1] = fill.g;
      pixels_[k + 2] = fill.b;
    }
  }

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return pixels_.empty(); }

  Rgb at(int x, int y) const {
    const std::uint8_t* p = &pixels_[offset(x, y)];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, Rgb c) {
    std::uint8_t* p = &pixels_[offset(x, y)];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

  std::uint8_t* data() { return pixels_.data(); }
  const std::uint8_t* data() const { return pixels_.data(); }
  std::size_t row_bytes() const { return 3 * static_cast<std::size_t>(width_); }

 private:
  std::size_t offset(int x, int y) const { return 3 * (static_cast<std::size_t>(y) * width_ + x); }

  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace bsmpm::render
