// The one place the glad loader is filled. glad keeps its function pointers in globals (that is how GL
// works: one current context per thread); each context reloads them when it is made current.
#include <glad/gl.h>

#include "partreg/core/errors.hpp"
#include "partreg/render/gl_context.hpp"

namespace partreg::render {

void load_gl_functions(GlProcLoader loader, const std::string& context_name) {
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
  if (version == 0) throw InputError("cannot load the OpenGL functions of the " + context_name + " context");
  if (GLAD_VERSION_MAJOR(version) < 3 ||
      (GLAD_VERSION_MAJOR(version) == 3 && GLAD_VERSION_MINOR(version) < 3))
    throw InputError("the " + context_name + " context is OpenGL " +
                     std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                     std::to_string(GLAD_VERSION_MINOR(version)) + "; partreg needs 3.3 core");
}

std::string gl_description() {
  const auto text = [](GLenum name) {
    const GLubyte* value = glGetString(name);
    return value ? std::string(reinterpret_cast<const char*>(value)) : std::string("?");
  };
  return "OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace partreg::render
