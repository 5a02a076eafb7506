#include "text/font.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// Decodes UTF-8; a malformed byte becomes U+FFFD.
std::vector<char32_t> decode_utf8(std::string_view s) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || (extra > 0 && i + extra >= s.size())) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    char32_t code = extra == 0 ? c : extra == 1 ? (c & 0x1F) : extra == 2 ? (c & 0x0F) : (c & 0x07);
    bool ok = true;
    for (int k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 0x2) ok = false;
      code = (code << 6) | (d & 0x3F);
    }
    out.push_back(ok ? code : 0xFFFD);
    i += ok ? extra + 1 : 1;
  }
  return out;
}

}  // namespace

Font::Font(const std::string& path) : path_(path) {
  if (!std::filesystem::exists(path))
    throw IoError(path + ": font not found (install the Debian package fonts-dejavu-core, or pass --font FILE.ttf)");
  if (FT_Init_FreeType(&library_) != 0) throw Error("FreeType: cannot initialise the library");
  if (FT_New_Face(library_, path.c_str(), 0, &face_) != 0) {
    FT_Done_FreeType(library_);
    throw IoError(path + ": FreeType cannot read this font file");
  }
}

Font::~Font() {
  FT_Done_Face(face_);
  FT_Done_FreeType(library_);
}

void Font::set_size(int pixel_size) {
  if (pixel_size == current_size_) return;
  if (FT_Set_Pixel_Sizes(face_, 0, static_cast<FT_UInt>(std::max(1, pixel_size))) != 0)
    throw Error(path_ + ": cannot scale the font to " + std::to_string(pixel_size) + " pixels");
  current_size_ = pixel_size;
}

const Font::Glyph& Font::glyph(char32_t code, int pixel_size) {
  const auto key = std::make_pair(pixel_size, code);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  set_size(pixel_size);
  Glyph g;
  g.index = FT_Get_Char_Index(face_, code);
  if (FT_Load_Glyph(face_, g.index, FT_LOAD_RENDER) == 0) {
    const FT_GlyphSlot slot = face_->glyph;
    g.advance = slot->advance.x;
    g.left = slot->bitmap_left;
    g.top = slot->bitmap_top;
    g.width = static_cast<int>(slot->bitmap.width);
    g.rows = static_cast<int>(slot->bitmap.rows);
    g.coverage.resize(static_cast<std::size_t>(g.width) * g.rows);
    for (int r = 0; r < g.rows; ++r)
      std::copy_n(slot->bitmap.buffer + static_cast<std::ptrdiff_t>(r) * slot->bitmap.pitch, g.width,
                  g.coverage.begin() + static_cast<std::ptrdiff_t>(r) * g.width);
  }
  return cache_.emplace(key, std::move(g)).first->second;
}

template <class Visit>
long Font::layout(std::string_view utf8, int pixel_size, Visit&& visit) {
  long pen = 0;
  unsigned previous = 0;
  for (const char32_t code : decode_utf8(utf8)) {
    const Glyph& g = glyph(code, pixel_size);
    if (previous != 0 && g.index != 0 && FT_HAS_KERNING(face_)) {
      set_size(pixel_size);
      FT_Vector delta{0, 0};
      if (FT_Get_Kerning(face_, previous, g.index, FT_KERNING_DEFAULT, &delta) == 0) pen += delta.x;
    }
    visit(g, pen);
    pen += g.advance;
    previous = g.index;
  }
  return pen;
}

int Font::text_width(std::string_view utf8, int pixel_size) {
  const long pen = layout(utf8, pixel_size, [](const Glyph&, long) {});
  return static_cast<int>((pen + 32) >> 6);
}

int Font::ascent(int pixel_size) {
  set_size(pixel_size);
  return static_cast<int>((face_->size->metrics.ascender + 63) >> 6);
}

int Font::descent(int pixel_size) {
  set_size(pixel_size);
  return static_cast<int>((-face_->size->metrics.descender + 63) >> 6);
}

void Font::draw(Image& image, int x, int baseline, std::string_view utf8, int pixel_size, Rgb color, TextAlign align) {
  if (align != TextAlign::kLeft) {
    const int w = text_width(utf8, pixel_size);
    x -= align == TextAlign::kCenter ? w / 2 : w;
  }
  layout(utf8, pixel_size, [&](const Glyph& g, long pen) {
    const int gx = x + static_cast<int>((pen + 32) >> 6) + g.left;
    const int gy = baseline - g.top;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.width; ++c) {
        const int a = g.coverage[static_cast<std::size_t>(r) * g.width + c];
        if (a == 0 || !image.contains(gx + c, gy + r)) continue;
        // Coverage blending in sRGB values, the usual compromise for small UI text.
        const Rgb bg = image.at(gx + c, gy + r);
        auto mix = [a](std::uint8_t b, std::uint8_t f) {
          return static_cast<std::uint8_t>((b * (255 - a) + f * a + 127) / 255);
        };
        image.set(gx + c, gy + r, {mix(bg.r, color.r), mix(bg.g, color.g), mix(bg.b, color.b)});
      }
  });
}

}  // namespace bsmpm::render
