#include "partreg/render/headless.hpp"

#include <iostream>

namespace partreg::render {

HeadlessRenderer::HeadlessRenderer(const RenderSettings& settings)
    : renderer_(std::make_unique<Renderer>(settings)) {}

// The renderer's GL objects belong to the context: free them while it is current.
HeadlessRenderer::~HeadlessRenderer() {
  context_.make_current();
  renderer_.reset();
}

Image HeadlessRenderer::render(const Scene& scene, const Camera& camera) {
  if (scene.empty()) std::cerr << "partreg: warning: the scene is empty; the image is blank\n";
  context_.make_current();
  return renderer_->render(scene, camera);
}

Image HeadlessRenderer::render(const Scene& scene, View view) {
  const RenderSettings& size = renderer_->settings();
  return render(scene, fit_camera(scene.all_points(), view, static_cast<double>(size.width) / size.height));
}

}  // namespace partreg::render
