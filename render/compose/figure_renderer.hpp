// Renders a FigureSpec into an image: a GL pass (OSMesa) draws each panel's tank walls,
// water and solids; then the header, panel labels and colour bars are drawn onto the
// read-back image with FreeType. One renderer keeps its GL context and font from figure to
// figure (a movie renders hundreds); use it from one thread.
#pragma once

#include <memory>
#include <string>

#include "figure/figure_layout.hpp"
#include "figure/figure_spec.hpp"
#include "gl/osmesa_context.hpp"
#include "image/image.hpp"
#include "paint/particle_painter.hpp"
#include "text/font.hpp"

namespace bsmpm::render {

class FigureRenderer {
 public:
  explicit FigureRenderer(const std::string& font_path = kDefaultFontPath);
  ~FigureRenderer();

  Font& font() { return font_; }
  // Renders `spec`; `layout_used`, when given, receives where everything went.
  Image render(const FigureSpec& spec, FigureLayout* layout_used = nullptr);

 private:
  Font font_;
  std::unique_ptr<OsMesaContext> gl_;           // created on first use, at the first size
  std::unique_ptr<ParticlePainter> particles_;  // needs gl_; declared after it, destroyed before
};

}  // namespace bsmpm::render
