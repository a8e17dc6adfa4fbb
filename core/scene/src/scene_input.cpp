#include "partreg/scene/scene_input.hpp"

#include "partreg/io/cloud_io.hpp"
#include "partreg/scene/camera_io.hpp"

namespace partreg::scene {

SceneView depth_view(const DepthImage& depth, const Intrinsics& intrinsics, const PixelMask* mask) {
  intrinsics.validate();
  SceneView view;
  view.intrinsics = intrinsics;
  view.measured = back_project(depth, intrinsics);
  if (mask) {
    back_project(depth, intrinsics, mask);  // checks the mask's size
    view.mask = *mask;
  }
  return view;
}

SceneView read_depth_view(const std::filesystem::path& depth, const std::filesystem::path& intrinsics,
                          const std::filesystem::path& mask) {
  const Intrinsics k = read_intrinsics(intrinsics);
  const DepthImage image = read_depth_image(depth, k);
  if (mask.empty()) return depth_view(image, k);
  const PixelMask selected = read_mask(mask, k);
  return depth_view(image, k, &selected);
}

SceneView read_scene_cloud(const std::filesystem::path& cloud, const std::filesystem::path& intrinsics) {
  SceneView view;
  view.measured.points = io::read_cloud_file(cloud).cloud.points;
  view.measured.pixel.assign(static_cast<std::size_t>(view.measured.points.rows()), -1);
  if (!intrinsics.empty()) {
    view.intrinsics = read_intrinsics(intrinsics);
    view.measured.pixel = project_to_pixels(view.measured.points, *view.intrinsics);
  }
  return view;
}

}  // namespace partreg::scene
