#pragma once
/// \file
/// A pinhole depth camera in OpenCV's convention: the camera frame has x to the right of the image, y down it
/// and z forward along the optical axis; pixel (u, v) is column u, row v, its centre at integer coordinates.
/// A pixel at depth z (metres, along z, not along the ray) is the point ((u - cx) z / fx, (v - cy) z / fy, z).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::scene {

/// A pinhole camera's intrinsics.
struct Intrinsics {
  double fx = 615.0, fy = 615.0;  ///< focal lengths (pixels)
  double cx = 319.5, cy = 239.5;  ///< principal point (pixels)
  int width = 640, height = 480;  ///< image size (pixels)
  double depth_scale = 1000.0;    ///< stored depth units per metre (1000: a 16-bit PNG in millimetres)

  /// InputError naming what is wrong for a non-finite or non-positive focal length or depth scale, a
  /// non-finite principal point or a size outside 1..16384 pixels.
  void validate() const;
  bool contains(double u, double v) const { return u >= 0 && v >= 0 && u < width && v < height; }
  /// The pixel a camera-frame point projects to (z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& point) const {
    return {fx * point.x() / point.z() + cx, fy * point.y() / point.z() + cy};
  }
  /// The camera-frame point of pixel (u, v) at depth z (metres).
  Eigen::Vector3d back_project(double u, double v, double z) const {
    return {(u - cx) * z / fx, (v - cy) * z / fy, z};
  }
};

/// A depth image: depth along the optical axis in metres, row-major; 0 where the sensor measured nothing.
struct DepthImage {
  int width = 0, height = 0;
  std::vector<float> metres;
  float at(int u, int v) const { return metres[static_cast<std::size_t>(v) * width + u]; }
};

/// A per-pixel selection (an object's mask), row-major; true where selected.
struct PixelMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> selected;
  bool at(int u, int v) const { return selected[static_cast<std::size_t>(v) * width + u] != 0; }
};

/// Points in the camera frame with the pixel each came from (-1 where unknown, as for a cloud read from a
/// file without intrinsics).
struct CameraPoints {
  core::Points points;
  std::vector<int> pixel;  ///< v * width + u per point, or -1
};

/// The measured pixels (depth > 0 and finite) back-projected, in row-major order; with `mask`, only its
/// selected pixels. InputError when the image's or the mask's size differs from the intrinsics'.
CameraPoints back_project(const DepthImage& depth, const Intrinsics& intrinsics,
                          const PixelMask* mask = nullptr);

/// The pixel index (v * width + u) each point projects to, or -1 outside the image or behind the camera.
std::vector<int> project_to_pixels(const core::Points& points, const Intrinsics& intrinsics);

}  // namespace partreg::scene
