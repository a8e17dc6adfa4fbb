#include "partreg/render/osmesa_context.hpp"

// glad's header first: it marks <GL/gl.h> as already included, so osmesa.h's own include of it is empty
// and every GL declaration comes from glad.
#include <glad/gl.h>
// clang-format off
#include <GL/osmesa.h>
// clang-format on

#include <cstdlib>
#include <string>
#include <vector>

#include "partreg/core/errors.hpp"

namespace partreg::render {

struct OsMesaContext::State {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer = std::vector<unsigned char>(4);  // OSMesa's own 1x1 RGBA target
};

namespace {

GlProc osmesa_proc(const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); }

}  // namespace

OsMesaContext::OsMesaContext() : state_(std::make_unique<State>()) {
  // Mesa's OSMesa crashes (it does not fail) when told to use a driver it was not built with.
  const char* driver = std::getenv("GALLIUM_DRIVER");
  if (driver && std::string(driver) != "llvmpipe" && std::string(driver) != "softpipe")
    throw InputError(std::string("cannot create an OSMesa context with GALLIUM_DRIVER=") + driver +
                     " (OSMesa draws with llvmpipe or softpipe)");
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  state_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!state_->context)
    throw InputError("cannot create an OSMesa OpenGL 3.3 core context (is Mesa's libOSMesa installed?)");
  make_current();
}

OsMesaContext::~OsMesaContext() {
  if (state_->context) OSMesaDestroyContext(state_->context);
}

void OsMesaContext::make_current() {
  if (!OSMesaMakeCurrent(state_->context, state_->buffer.data(), GL_UNSIGNED_BYTE, 1, 1))
    throw InputError("cannot make the OSMesa context current");
  load_gl_functions(osmesa_proc, "OSMesa");
}

}  // namespace partreg::render
