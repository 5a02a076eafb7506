#define GL_GLEXT_PROTOTYPES
#include "gl/shader_program.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// Shaders and programs have the same pair of query functions and a delete function each.
using GetIv = void (*)(GLuint, GLenum, GLint*);
using GetLog = void (*)(GLuint, GLsizei, GLsizei*, GLchar*);

// Deletes `object` and throws `failure` with GL's log when its `status` is not set.
void require(GLuint object, GLenum status, GetIv get_iv, GetLog get_log, void (*destroy)(GLuint),
             const std::string& failure) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return;
  GLint length = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log = "(no log)";
  if (length > 0) {
    log.assign(static_cast<std::size_t>(length), '\0');
    GLsizei written = 0;
    get_log(object, length, &written, log.data());
    log.resize(static_cast<std::size_t>(written));
  }
  destroy(object);
  throw Error(failure + ": " + log);
}

GLuint compile(const std::string& what, GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  require(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
          "OpenGL: " + what + " (" + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") + " stage) does not compile");
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const std::string& what, const char* vertex_source, const char* fragment_source,
                             const std::vector<std::pair<unsigned, const char*>>& attributes)
    : what_(what) {
  const GLuint vertex = compile(what, GL_VERTEX_SHADER, vertex_source);
  GLuint fragment = 0;
  try {
    fragment = compile(what, GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vertex);
  glAttachShader(id_, fragment);
  for (const auto& [location, name] : attributes) glBindAttribLocation(id_, location, name);
  glLinkProgram(id_);
  glDeleteShader(vertex);  // stay alive while attached
  glDeleteShader(fragment);
  require(id_, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram, "OpenGL: " + what + " does not link");
}

ShaderProgram::~ShaderProgram() { glDeleteProgram(id_); }

int ShaderProgram::uniform(const char* name) const {
  const GLint location = glGetUniformLocation(id_, name);
  if (location < 0) throw Error("OpenGL: " + what_ + " has no uniform " + name);
  return location;
}

}  // namespace bsmpm::render
