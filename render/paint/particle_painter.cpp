#define GL_GLEXT_PROTOTYPES
#include "paint/particle_painter.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "gl/gl_state_guard.hpp"

namespace bsmpm::render {

namespace {

enum Attribute : unsigned { kPosition = 0, kColor, kAxis, kSupportA, kSupportB, kReach };

// Every splat keeps at least the pixel its particle falls in: a radius of half a pixel's
// diagonal, so that a particle never disappears at a coarse resolution (in the shader and in
// the size check of draw()).
constexpr float kLeastSplatPixels = 0.71f;

// Compatibility-profile GLSL 1.30 (flat varyings; the fixed-function matrices). Sizes in
// pixels.

const std::string kVertexShader = std::string(R"(#version 130
uniform float pixels_per_unit;
in vec2 position;
in vec4 color;
in vec2 axis;
in vec4 support_a;
in vec4 support_b;
in float reach;
flat out vec4 splat_color;
flat out vec2 splat_axis;
flat out vec4 splat_support_a;
flat out vec4 splat_support_b;
flat out float splat_reach;
flat out float splat_size;
void main() {
)") + "  const float kLeast = " + shortest(static_cast<double>(kLeastSplatPixels)) + ";" + R"(
  gl_Position = gl_ModelViewProjectionMatrix * vec4(position, 0.0, 1.0);
  splat_color = color;
  splat_axis = axis;
  splat_support_a = max(support_a * pixels_per_unit, vec4(kLeast));
  splat_support_b = max(support_b * pixels_per_unit, vec4(kLeast));
  splat_reach = max(reach * pixels_per_unit, kLeast);
  // A point covers the pixel centres within half its size of the particle on each axis.
  splat_size = ceil(2.0 * splat_reach);
  gl_PointSize = splat_size;
}
)";

// gl_PointCoord runs from the lower left (GL_POINT_SPRITE_COORD_ORIGIN), as the world does.
// Depth: distance to the particle, so that the depth test keeps the nearest particle.
const std::string kFragmentShader = std::string(R"(#version 130
uniform float depth_scale;
flat in vec4 splat_color;
flat in vec2 splat_axis;
flat in vec4 splat_support_a;
flat in vec4 splat_support_b;
flat in float splat_reach;
flat in float splat_size;
void main() {
  vec2 p = (gl_PointCoord - 0.5) * splat_size;
  float r = length(p);
  if (r > splat_reach) discard;
  // Along u_0 .. u_7: u_0 = axis, each next one turned by 45 degrees.
  vec2 f = vec2(dot(p, splat_axis), dot(p, vec2(-splat_axis.y, splat_axis.x)));
)") + "  const float kHalfSqrt2 = " + shortest(static_cast<double>(kHalfSqrt2)) + ";" + R"(
  vec4 along = vec4(f.x, kHalfSqrt2 * (f.x + f.y), f.y, kHalfSqrt2 * (f.y - f.x));
  if (any(greaterThan(along, splat_support_a)) || any(greaterThan(-along, splat_support_b))) discard;
  gl_FragDepth = r * depth_scale;
  gl_FragColor = splat_color;
}
)";

}  // namespace

ParticlePainter::ParticlePainter() {
  program_ = std::make_unique<ShaderProgram>("the splat shader", kVertexShader.c_str(), kFragmentShader.c_str(),
                                             std::vector<std::pair<unsigned, const char*>>{{kPosition, "position"},
                                                                                           {kColor, "color"},
                                                                                           {kAxis, "axis"},
                                                                                           {kSupportA, "support_a"},
                                                                                           {kSupportB, "support_b"},
                                                                                           {kReach, "reach"}});
  pixels_per_unit_location_ = program_->uniform("pixels_per_unit");
  depth_scale_location_ = program_->uniform("depth_scale");
  glGenBuffers(1, &buffer_);
  GLfloat range[2] = {1.0f, 1.0f};
  glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
  max_point_size_ = range[1];
}

ParticlePainter::~ParticlePainter() { glDeleteBuffers(1, &buffer_); }

void ParticlePainter::paint(const std::vector<Vec2>& position, const std::vector<double>& side,
                            const std::vector<double>& value, const ColorMap& map, ValueRange range,
                            double splat_scale, double pixels_per_unit, const SplatObstacles& obstacles) {
  const std::size_t n = position.size();
  if (n == 0) return;
  compute_splat_shapes(position, side, splat_scale, obstacles, shapes_);
  vertices_.resize(n);
  float largest = 0.0f;
  for (std::size_t k = 0; k < n; ++k) {
    SplatVertex& v = vertices_[k];
    v.x = static_cast<float>(position[k].x());
    v.y = static_cast<float>(position[k].y());
    const Rgb c = map.at(range.normalized(value[k]));
    v.rgba = {c.r, c.g, c.b, 255};
    v.shape = shapes_[k];
    largest = std::max(largest, v.shape.reach);
  }
  // The same size as the vertex shader computes, in single precision.
  const float largest_px = std::max(largest * static_cast<float>(pixels_per_unit), kLeastSplatPixels);
  const float largest_size = std::ceil(2.0f * largest_px);
  if (largest_size > max_point_size_)
    throw UsageError("particles would be drawn " + std::to_string(static_cast<int>(largest_size)) +
                     " pixels wide, more than OpenGL's largest point (" +
                     std::to_string(static_cast<int>(max_point_size_)) + "): widen the view or lower the image size");

  const GlStateGuard saved;  // restores what this changes, on every way out
  glUseProgram(program_->id());
  glUniform1f(pixels_per_unit_location_, static_cast<float>(pixels_per_unit));
  // Depth = distance / (a bit more than the largest reach): within [0, 1).
  glUniform1f(depth_scale_location_, 1.0f / (largest_px + 2.0f));
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);  // inside the scissor box: this panel only
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_POINT_SPRITE);
  glPointParameteri(GL_POINT_SPRITE_COORD_ORIGIN, GL_LOWER_LEFT);

  // One interleaved buffer object: Mesa fetches it as it is, where separate client arrays
  // are gathered into a buffer of their own at every draw.
  // GL drops a point whose centre lies outside the viewport, but a splat reaches past its
  // particle: particles just outside the panel must still paint its edge. The viewport
  // grows by the largest splat on every side, the projection with it (the same world per
  // pixel); the scissor box keeps the drawing inside the panel.
  const GLint* viewport = saved.viewport();
  const GLint grow = static_cast<GLint>(largest_size) + 1;
  glViewport(viewport[0] - grow, viewport[1] - grow, viewport[2] + 2 * grow, viewport[3] + 2 * grow);
  glMatrixMode(GL_PROJECTION);
  GLdouble projection[16];
  glGetDoublev(GL_PROJECTION_MATRIX, projection);
  glLoadIdentity();
  glScaled(static_cast<double>(viewport[2]) / (viewport[2] + 2 * grow),
           static_cast<double>(viewport[3]) / (viewport[3] + 2 * grow), 1.0);
  glMultMatrixd(projection);
  glMatrixMode(GL_MODELVIEW);

  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * sizeof(SplatVertex)), vertices_.data(), GL_STREAM_DRAW);
  const GLsizei stride = sizeof(SplatVertex);
  auto at = [](std::size_t offset) { return reinterpret_cast<const void*>(offset); };
  const std::size_t shape = offsetof(SplatVertex, shape);
  glVertexAttribPointer(kPosition, 2, GL_FLOAT, GL_FALSE, stride, at(offsetof(SplatVertex, x)));
  glVertexAttribPointer(kColor, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, at(offsetof(SplatVertex, rgba)));
  glVertexAttribPointer(kAxis, 2, GL_FLOAT, GL_FALSE, stride, at(shape + offsetof(SplatShape, axis_x)));
  glVertexAttribPointer(kSupportA, 4, GL_FLOAT, GL_FALSE, stride, at(shape + offsetof(SplatShape, support)));
  glVertexAttribPointer(kSupportB, 4, GL_FLOAT, GL_FALSE, stride,
                        at(shape + offsetof(SplatShape, support) + 4 * sizeof(float)));
  glVertexAttribPointer(kReach, 1, GL_FLOAT, GL_FALSE, stride, at(shape + offsetof(SplatShape, reach)));
  for (unsigned a : {kPosition, kColor, kAxis, kSupportA, kSupportB, kReach}) glEnableVertexAttribArray(a);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  for (unsigned a : {kPosition, kColor, kAxis, kSupportA, kSupportB, kReach}) glDisableVertexAttribArray(a);
}

}  // namespace bsmpm::render
