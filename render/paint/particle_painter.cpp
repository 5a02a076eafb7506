#define GL_GLEXT_PROTOTYPES
#include "paint/particle_painter.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// Compatibility-profile GLSL: fixed-function arrays in, fixed-function fragments out. The
// side is rounded up to whole pixels (GL rounds point sizes to the nearest integer), so that
// splats never shrink below the particle spacing.
const char* kSplatShader = R"(#version 120
uniform float pixels_per_unit;
void main() {
  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
  gl_FrontColor = gl_Color;
  gl_PointSize = max(1.0, ceil(gl_MultiTexCoord0.x * pixels_per_unit));
}
)";

}  // namespace

ParticlePainter::ParticlePainter() {
  const GLuint shader = glCreateShader(GL_VERTEX_SHADER);
  glShaderSource(shader, 1, &kSplatShader, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {0};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw Error(std::string("OpenGL: the splat shader does not compile: ") + log);
  }
  program_ = glCreateProgram();
  glAttachShader(program_, shader);
  glLinkProgram(program_);
  glDeleteShader(shader);  // stays alive while attached
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[1024] = {0};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    throw Error(std::string("OpenGL: the splat shader does not link: ") + log);
  }
  scale_location_ = glGetUniformLocation(program_, "pixels_per_unit");
  GLfloat range[2] = {1.0f, 1.0f};
  glGetFloatv(GL_ALIASED_POINT_SIZE_RANGE, range);
  max_point_size_ = range[1];
}

ParticlePainter::~ParticlePainter() { glDeleteProgram(program_); }

void ParticlePainter::paint(const std::vector<Vec2>& position, const std::vector<double>& side,
                            const std::vector<double>& value, const ColorMap& map, ValueRange range,
                            double splat_scale, double pixels_per_unit) {
  const std::size_t n = position.size();
  if (n == 0) return;
  xy_.resize(2 * n);
  side_.resize(n);
  rgba_.resize(4 * n);
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    xy_[2 * k] = static_cast<float>(position[k].x());
    xy_[2 * k + 1] = static_cast<float>(position[k].y());
    side_[k] = static_cast<float>(splat_scale * side[k]);
    largest = std::max(largest, splat_scale * side[k]);
    const Rgb c = map.at(range.normalized(value[k]));
    rgba_[4 * k] = c.r;
    rgba_[4 * k + 1] = c.g;
    rgba_[4 * k + 2] = c.b;
    rgba_[4 * k + 3] = 255;
  }
  if (std::ceil(largest * pixels_per_unit) > max_point_size_)
    throw UsageError("particles would be drawn " + std::to_string(static_cast<int>(std::ceil(largest * pixels_per_unit))) +
                     " pixels wide, more than OpenGL's largest point (" +
                     std::to_string(static_cast<int>(max_point_size_)) + "): widen the view or lower the image size");

  glUseProgram(program_);
  glUniform1f(scale_location_, static_cast<float>(pixels_per_unit));
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, xy_.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, rgba_.data());
  glTexCoordPointer(1, GL_FLOAT, 0, side_.data());
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisable(GL_PROGRAM_POINT_SIZE);
  glUseProgram(0);
}

}  // namespace bsmpm::render
