#pragma once
/// \file
/// Headless rendering in one object: an OSMesa context with a renderer in it.

#include <memory>

#include "partreg/render/osmesa_context.hpp"
#include "partreg/render/renderer.hpp"

namespace partreg::render {

/// An OSMesa context and a renderer, for figures and tests. Throws InputError when the context cannot be
/// created or a shader does not compile.
class HeadlessRenderer {
 public:
  explicit HeadlessRenderer(const RenderSettings& settings = {});
  ~HeadlessRenderer();

  /// Renders `scene` seen by `camera`; warns on stderr when the scene is empty (the image is then blank).
  Image render(const Scene& scene, const Camera& camera);
  /// Renders `scene` from a named view fitted to its bounds.
  Image render(const Scene& scene, View view);
  void resize(int width, int height) { renderer_->resize(width, height); }
  const RenderSettings& settings() const { return renderer_->settings(); }

 private:
  OsMesaContext context_;
  std::unique_ptr<Renderer> renderer_;
};

}  // namespace partreg::render
