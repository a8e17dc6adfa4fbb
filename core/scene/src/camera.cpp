#include "partreg/scene/camera.hpp"

#include <cmath>
#include <string>

#include "partreg/core/errors.hpp"

namespace partreg::scene {
namespace {

void require(bool condition, const std::string& what) {
  if (!condition) throw InputError("intrinsics: " + what);
}

void check_size(int width, int height, const Intrinsics& intrinsics, const char* what) {
  if (width != intrinsics.width || height != intrinsics.height)
    throw InputError(std::string(what) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels but the intrinsics say " + std::to_string(intrinsics.width) + "x" +
                     std::to_string(intrinsics.height));
}

}  // namespace

void Intrinsics::validate() const {
  require(std::isfinite(fx) && fx > 0 && std::isfinite(fy) && fy > 0,
          "the focal lengths fx, fy must be finite and positive");
  require(std::isfinite(cx) && std::isfinite(cy), "the principal point cx, cy must be finite");
  require(width >= 1 && height >= 1 && width <= 16384 && height <= 16384,
          "width and height must be 1 to 16384 pixels");
  require(std::isfinite(depth_scale) && depth_scale > 0, "depth_scale must be finite and positive");
}

CameraPoints back_project(const DepthImage& depth, const Intrinsics& intrinsics, const PixelMask* mask) {
  check_size(depth.width, depth.height, intrinsics, "the depth image");
  if (mask) check_size(mask->width, mask->height, intrinsics, "the mask");
  std::vector<int> pixels;
  for (int v = 0; v < depth.height; ++v)
    for (int u = 0; u < depth.width; ++u) {
      const float z = depth.at(u, v);
      if (std::isfinite(z) && z > 0 && (!mask || mask->at(u, v))) pixels.push_back(v * depth.width + u);
    }
  CameraPoints out;
  out.points.resize(static_cast<Eigen::Index>(pixels.size()), 3);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const int u = pixels[i] % depth.width, v = pixels[i] / depth.width;
    out.points.row(static_cast<Eigen::Index>(i)) = intrinsics.back_project(u, v, depth.at(u, v)).transpose();
  }
  out.pixel = std::move(pixels);
  return out;
}

std::vector<int> project_to_pixels(const core::Points& points, const Intrinsics& intrinsics) {
  std::vector<int> pixel(static_cast<std::size_t>(points.rows()), -1);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    if (!(p.z() > 0)) continue;
    const Eigen::Vector2d uv = intrinsics.project(p);
    const double u = std::round(uv.x()), v = std::round(uv.y());
    if (intrinsics.contains(u, v)) pixel[static_cast<std::size_t>(i)] = int(v) * intrinsics.width + int(u);
  }
  return pixel;
}

}  // namespace partreg::scene
