#include <cmath>

#include "partreg/scene/segmentation.hpp"

namespace partreg::scene {

std::shared_ptr<const core::FreeSpace> free_space_of(const SceneView& view) {
  if (!view.intrinsics) return nullptr;
  const Intrinsics& k = *view.intrinsics;
  auto free = std::make_shared<core::FreeSpace>();
  free->fx = k.fx, free->fy = k.fy, free->cx = k.cx, free->cy = k.cy;
  free->depth = Eigen::MatrixXf::Zero(k.height, k.width);
  const CameraPoints& measured = view.measured;
  for (std::size_t i = 0; i < measured.pixel.size(); ++i) {
    const int pixel = measured.pixel[i];
    const float z = static_cast<float>(measured.points(static_cast<Eigen::Index>(i), 2));
    if (pixel < 0 || !(z > 0.0f)) continue;
    float& at = free->depth(pixel / k.width, pixel % k.width);
    // Where a projected cloud puts several points on a pixel, the nearest is the one the camera saw.
    if (at == 0.0f || z < at) at = z;
  }
  return free;
}

}  // namespace partreg::scene
