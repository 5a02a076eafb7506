// Text with a real font: FreeType rasterises the glyphs (anti-aliased coverage), which are
// blended onto an Image. UTF-8 input (labels use T*, ρ, −, ‖v‖). Default face: DejaVu Sans
// from fonts-dejavu-core.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "image/image.hpp"

struct FT_LibraryRec_;
struct FT_FaceRec_;

namespace bsmpm::render {

inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

enum class TextAlign { kLeft, kCenter, kRight };

class Font {
 public:
  // Throws IoError naming the path (and the Debian package) when the face is missing or
  // FreeType cannot read it.
  explicit Font(const std::string& path = kDefaultFontPath);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // Metrics in pixels for a font of `pixel_size` pixels (the em size).
  int text_width(std::string_view utf8, int pixel_size);
  int ascent(int pixel_size);   // above the baseline
  int descent(int pixel_size);  // below the baseline, positive

  // Draws one line of text with its baseline at y; x is the left end, centre or right end.
  void draw(Image& image, int x, int baseline, std::string_view utf8, int pixel_size, Rgb color,
            TextAlign align = TextAlign::kLeft);

 private:
  struct Glyph {
    unsigned index = 0;    // glyph index in the face, for kerning
    long advance = 0;      // 26.6 fixed point pixels
    int left = 0, top = 0; // bitmap offset from the pen position (top is above the baseline)
    int width = 0, rows = 0;
    std::vector<std::uint8_t> coverage;
  };
  const Glyph& glyph(char32_t code, int pixel_size);
  void set_size(int pixel_size);
  // Pen advance of each glyph including kerning, 26.6 fixed point.
  template <class Visit>
  long layout(std::string_view utf8, int pixel_size, Visit&& visit);

  std::string path_;
  FT_LibraryRec_* library_ = nullptr;
  FT_FaceRec_* face_ = nullptr;
  int current_size_ = 0;
  std::map<std::pair<int, char32_t>, Glyph> cache_;
};

}  // namespace bsmpm::render
