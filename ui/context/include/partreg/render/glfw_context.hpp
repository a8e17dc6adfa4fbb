#pragma once
/// \file
/// A window with a GL 3.3 core context, from GLFW. Link partreg_render_glfw for it; headless code never
/// needs it (nor a display).

#include <memory>
#include <string>

#include "partreg/render/gl_context.hpp"

struct GLFWwindow;

namespace partreg::render {

/// A GLFW window and its GL 3.3 core context; creating it makes it current.
class GlfwContext : public GlContext {
 public:
  /// Throws InputError when GLFW cannot start (no display) or the window cannot be created.
  GlfwContext(int width, int height, const std::string& title, bool visible = true);
  ~GlfwContext() override;
  GlfwContext(const GlfwContext&) = delete;
  GlfwContext& operator=(const GlfwContext&) = delete;

  void make_current() override;
  GLFWwindow* window() const { return window_; }
  /// Copies the renderer's resolved frame (GL framebuffer `source`, width x height) to the window and swaps.
  void present(unsigned source, int width, int height);

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace partreg::render
