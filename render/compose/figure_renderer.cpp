#include "compose/figure_renderer.hpp"

#include <GL/gl.h>

#include "core/error.hpp"
#include "gl/panel_view.hpp"
#include "paint/color_bar_painter.hpp"
#include "paint/tank_painter.hpp"

namespace bsmpm::render {

namespace {
constexpr Rgb kWallColor{70, 70, 70};
}

FigureRenderer::FigureRenderer(const std::string& font_path) : font_(font_path) {}

FigureRenderer::~FigureRenderer() {
  // The painter releases its shader in this context (never throw from a destructor).
  try {
    if (gl_) gl_->make_current();
  } catch (const Error&) {
  }
  particles_.reset();
}

Image FigureRenderer::render(const FigureSpec& spec, FigureLayout* layout_used) {
  const FigureLayout layout = compute_figure_layout(spec, font_);
  if (!gl_) {
    gl_ = std::make_unique<OsMesaContext>(spec.width, spec.height);
    particles_ = std::make_unique<ParticlePainter>();
  } else if (gl_->width() != spec.width || gl_->height() != spec.height) {
    gl_->resize(spec.width, spec.height);
  } else {
    gl_->make_current();
  }

  reset_view(spec.width, spec.height);
  glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  for (std::size_t i = 0; i < layout.plots.size(); ++i) {
    const PixelRect& plot = layout.plots[i];
    // The viewport reaches a wall's thickness beyond the view so that walls at the view's
    // edge are drawn; scale per axis exactly as the plot rectangle maps the view.
    const int wall = layout.wall_px;
    const Vec2 per_pixel(spec.view.width() / plot.width, spec.view.height() / plot.height);
    const WorldRect world{spec.view.min - wall * per_pixel, spec.view.max + wall * per_pixel};
    set_panel_view(plot.expanded(wall), world, spec.height);
    // Solids over water (the obstacle stays visible under a splash), walls last: they lie
    // outside the domain and trim the splats of particles touching a wall.
    // The water reaches up to the walls and the solids, which cover it (MPM holds particles
    // of different bodies about a cell apart at a contact).
    if (const FrameParticles* p = spec.panels[i].particles) {
      if (spec.water)
        particles_->paint(p->water.position, p->water.side, p->water.value, spec.water->map, spec.water->range,
                          spec.splat_scale, layout.pixels_per_unit,
                          SplatObstacles{&spec.domain, spec.solids ? &p->solids.position : nullptr});
      if (spec.solids)
        particles_->paint(p->solids.position, p->solids.side, p->solids.value, spec.solids->map,
                          spec.solids->range, spec.splat_scale, layout.pixels_per_unit, SplatObstacles{&spec.domain});
    }
    paint_tank_walls(spec.domain, wall * per_pixel.x(), kWallColor);
  }
  reset_view(spec.width, spec.height);
  Image image = gl_->read_image();

  const int big = layout.font_px, small = layout.small_font_px;
  const int header_baseline = layout.header.y + font_.ascent(big);
  font_.draw(image, layout.header.x, header_baseline, spec.header_left, big, kInkColor);
  // The right-hand text (the run's title) only where it does not run into the left one.
  if (!spec.header_right.empty() &&
      font_.text_width(spec.header_left, big) + font_.text_width(spec.header_right, big) + 2 * big <= layout.header.width)
    font_.draw(image, layout.header.right(), header_baseline, spec.header_right, big, kInkColor, TextAlign::kRight);
  for (std::size_t i = 0; i < layout.plots.size(); ++i)
    font_.draw(image, layout.plots[i].x, layout.label_baselines[i], spec.panels[i].label, small, kInkColor);
  std::size_t bar = 0;
  for (const auto* scale : {&spec.water, &spec.solids})
    if (*scale) paint_color_bar(image, font_, layout.bars.at(bar++), **scale, small);

  if (layout_used) *layout_used = layout;
  return image;
}

}  // namespace bsmpm::render
