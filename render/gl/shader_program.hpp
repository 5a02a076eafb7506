// A linked GLSL program of one vertex and one fragment shader, owned (RAII) in the current
// GL context: compile and link errors are thrown with GL's own log.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bsmpm::render {

class ShaderProgram {
 public:
  // `attributes` binds vertex attribute names to locations before linking. Throws
  // bsmpm::Error naming `what` ("the splat shader") when a stage does not compile or link.
  ShaderProgram(const std::string& what, const char* vertex_source, const char* fragment_source,
                const std::vector<std::pair<unsigned, const char*>>& attributes);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  unsigned id() const { return id_; }
  // Location of a uniform (throws when the program has none of that name: a typo in the
  // shader source would otherwise fail silently).
  int uniform(const char* name) const;

 private:
  std::string what_;
  unsigned id_ = 0;
};

}  // namespace bsmpm::render
