#pragma once
// Shader programs: compiled from the built-in sources, with the compiler's log in the error.
#include <string>

#include "render/gl.h"

namespace scour {

class Program {
 public:
  Program() = default;
  /// A compute program from shaders/<name>.glsl. Throws GlError with the compile log.
  static Program compute(const std::string& name);
  /// A vertex + fragment program.
  static Program graphics(const std::string& vertex, const std::string& fragment);
  Program(Program&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Program& operator=(Program&& o) noexcept;
  ~Program();

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  GLint location(const char* uniform) const { return glGetUniformLocation(id_, uniform); }

 private:
  explicit Program(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

}  // namespace scour
