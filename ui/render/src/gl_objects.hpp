#pragma once
// Small owners of GL object names, so that every early return and exception frees what was created.
#include <glad/gl.h>

#include <utility>

namespace partreg::render::detail {

/// Owns one GL name; `Deleter` frees it (glDeleteBuffers and friends wrapped in a function).
template <void (*Deleter)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint name) : name_(name) {}
  ~GlName() { reset(); }
  GlName(GlName&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GLuint get() const { return name_; }
  /// Gives up ownership and returns the name.
  GLuint release() { return std::exchange(name_, 0); }
  void reset() {
    if (name_ != 0) Deleter(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

inline void delete_buffer(GLuint name) { glDeleteBuffers(1, &name); }
inline void delete_vertex_array(GLuint name) { glDeleteVertexArrays(1, &name); }
inline void delete_framebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }
inline void delete_renderbuffer(GLuint name) { glDeleteRenderbuffers(1, &name); }
inline void delete_program(GLuint name) { glDeleteProgram(name); }
inline void delete_shader(GLuint name) { glDeleteShader(name); }

using Buffer = GlName<delete_buffer>;
using VertexArray = GlName<delete_vertex_array>;
using Framebuffer = GlName<delete_framebuffer>;
using Renderbuffer = GlName<delete_renderbuffer>;
using Program = GlName<delete_program>;
using Shader = GlName<delete_shader>;

inline Buffer make_buffer() {
  GLuint name = 0;
  glGenBuffers(1, &name);
  return Buffer(name);
}
inline VertexArray make_vertex_array() {
  GLuint name = 0;
  glGenVertexArrays(1, &name);
  return VertexArray(name);
}

}  // namespace partreg::render::detail
