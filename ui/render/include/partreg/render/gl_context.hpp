#pragma once
/// \file
/// An OpenGL 3.3 core context the renderer can draw with, headless (OsMesaContext) or in a window
/// (GlfwContext). The renderer's GL functions come only from the glad loader, which each context fills from
/// its own proc-address function when it is made current.

#include <string>

namespace partreg::render {

/// A GL entry point as a proc-address function returns it.
using GlProc = void (*)();
/// A context's proc-address function (OSMesaGetProcAddress, glfwGetProcAddress).
using GlProcLoader = GlProc (*)(const char* name);

/// A GL 3.3 core context. Make it current (which loads the GL functions) before creating a Renderer.
class GlContext {
 public:
  virtual ~GlContext() = default;
  /// Makes the context current on this thread and loads the GL functions from it.
  virtual void make_current() = 0;
};

/// Fills the glad loader from `loader`. Throws InputError naming `context_name` when the functions cannot be
/// loaded or the context is older than GL 3.3.
void load_gl_functions(GlProcLoader loader, const std::string& context_name);

/// "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)" for the current context.
std::string gl_description();

}  // namespace partreg::render
