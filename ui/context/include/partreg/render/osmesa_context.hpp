#pragma once
/// \file
/// A headless GL 3.3 core context from Mesa's OSMesa (llvmpipe): no display, no window system.

#include <memory>

#include "partreg/render/gl_context.hpp"

namespace partreg::render {

/// An OSMesa core-profile context. The renderer draws into its own framebuffer, so OSMesa's buffer is a
/// token 1x1 one. Creating it makes it current.
class OsMesaContext : public GlContext {
 public:
  /// Throws InputError ("cannot create an OSMesa OpenGL 3.3 core context ...") when Mesa refuses.
  OsMesaContext();
  ~OsMesaContext() override;
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  void make_current() override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace partreg::render
