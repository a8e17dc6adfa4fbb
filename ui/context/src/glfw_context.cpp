#include "partreg/render/glfw_context.hpp"

// GLFW_INCLUDE_NONE (set by the build) keeps glfw3.h from including any GL header; GL comes from glad.
#include <GLFW/glfw3.h>
#include <glad/gl.h>

#include "partreg/core/errors.hpp"

namespace partreg::render {
namespace {

GlProc glfw_proc(const char* name) { return reinterpret_cast<GlProc>(glfwGetProcAddress(name)); }

}  // namespace

GlfwContext::GlfwContext(int width, int height, const std::string& title, bool visible) {
  if (!glfwInit()) throw InputError("cannot start GLFW (is there a display?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw InputError("cannot create a GLFW window with an OpenGL 3.3 core context");
  }
  make_current();
}

GlfwContext::~GlfwContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GlfwContext::make_current() {
  glfwMakeContextCurrent(window_);
  load_gl_functions(glfw_proc, "GLFW");
}

void GlfwContext::present(unsigned source, int width, int height) {
  int window_width = 0, window_height = 0;
  glfwGetFramebufferSize(window_, &window_width, &window_height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, width, height, 0, 0, window_width, window_height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  glfwSwapBuffers(window_);
}

}  // namespace partreg::render
