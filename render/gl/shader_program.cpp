#define GL_GLEXT_PROTOTYPES
#include "gl/shader_program.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// The info log of a shader or a program (the two have the same pair of query functions).
std::string info_log(GLuint object, void (*get_iv)(GLuint, GLenum, GLint*),
                     void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint length = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &length);
  if (length <= 0) return "(no log)";
  std::string log(static_cast<std::size_t>(length), '\0');
  GLsizei written = 0;
  get_log(object, length, &written, log.data());
  log.resize(static_cast<std::size_t>(written));
  return log;
}

GLuint compile(const std::string& what, GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    throw Error("OpenGL: " + what + " (" + (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                " stage) does not compile: " + log);
  }
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
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(id_, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(id_);
    throw Error("OpenGL: " + what + " does not link: " + log);
  }
}

ShaderProgram::~ShaderProgram() { glDeleteProgram(id_); }

int ShaderProgram::uniform(const char* name) const {
  const GLint location = glGetUniformLocation(id_, name);
  if (location < 0) throw Error("OpenGL: " + what_ + " has no uniform " + name);
  return location;
}

}  // namespace bsmpm::render
