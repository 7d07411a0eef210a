#include "render/program.h"

#include <vector>

#include "render/context.h"
#include "render/shaders.h"

namespace scour {

namespace {

GLuint compile(GLenum type, const std::string& name) {
  const std::string text = std::string("#version 450 core\n#line 1\n") + shaderSource(name);
  const char* src = text.c_str();
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &n);
    std::vector<char> log(size_t(std::max(n, 1)));
    glGetShaderInfoLog(s, n, nullptr, log.data());
    glDeleteShader(s);
    throw GlError("shaders/" + name + ".glsl: " + std::string(log.data()));
  }
  return s;
}

GLuint link(const std::vector<GLuint>& shaders, const std::string& name) {
  GLuint p = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(p, s);
  glLinkProgram(p);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &n);
    std::vector<char> log(size_t(std::max(n, 1)));
    glGetProgramInfoLog(p, n, nullptr, log.data());
    glDeleteProgram(p);
    throw GlError("linking " + name + ": " + std::string(log.data()));
  }
  return p;
}

}  // namespace

Program Program::compute(const std::string& name) {
  return Program(link({compile(GL_COMPUTE_SHADER, name)}, name));
}

Program Program::graphics(const std::string& vertex, const std::string& fragment) {
  return Program(link({compile(GL_VERTEX_SHADER, vertex), compile(GL_FRAGMENT_SHADER, fragment)},
                      vertex + " + " + fragment));
}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

}  // namespace scour
