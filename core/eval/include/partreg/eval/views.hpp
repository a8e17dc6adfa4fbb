#pragma once
/// \file
/// Partial views as a depth camera sees them (paper, section 4): viewpoints on a tessellated sphere around
/// the object, and rays cast from each through a pinhole camera with Embree. A mesh gives the surface
/// points the rays hit; a cloud (no surface) is cast as small spheres and gives the points whose sphere a
/// ray hits first, so its views are subsets of the cloud.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::eval {

/// Unit directions from the object's centre towards the viewpoints: the vertices of an icosahedron
/// subdivided k times (count = 10 * 4^k + 2: 12, 42, 162, 642, ...; 42 is the paper's). Evenly spread; the
/// 12 of the icosahedron come first, so a smaller sphere's directions are a prefix of a larger one's.
/// UsageError for another count.
std::vector<Eigen::Vector3d> sphere_directions(int count);

/// The depth camera.
struct CameraSettings {
  int width = 160;            ///< pixels, 1 to kMaxPixelsPerSide
  int height = 120;           ///< pixels, 1 to kMaxPixelsPerSide
  double fov_degrees = 45.0;  ///< vertical field of view, kMinFovDegrees to kMaxFovDegrees
  double margin = 1.1;        ///< the object's bounding sphere fills 1 / margin of the vertical field of view
                              ///< (1 to kMaxMargin)

  // A field of view of 1e-300 degrees puts the camera 1e300 object sizes away, where Embree asserts: the
  // range below keeps it within 1e4 object sizes, as any real depth camera is.
  static constexpr double kMinFovDegrees = 0.01;
  static constexpr double kMaxFovDegrees = 179.0;
  static constexpr double kMaxMargin = 100.0;
  static constexpr int kMaxPixelsPerSide = 8192;
};

/// UsageError (one line naming the setting) for a camera outside the ranges CameraSettings declares.
void check_camera(const CameraSettings& camera);

/// One partial view, in the object's frame and units.
struct View {
  core::Points points;   ///< what the camera saw
  core::Points normals;  ///< unit surface normal per point (meshes; empty for clouds)
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();   ///< the camera's position
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit, from the object's centre to the camera
};

/// A ray-casting scene of one object. Building it is the expensive part; casting a view is cheap and
/// thread-safe.
class ViewCaster {
 public:
  /// A triangle mesh (any orientation: normals are returned facing the camera). InputError for no faces.
  explicit ViewCaster(const core::Mesh& mesh);
  /// A cloud: each point a sphere of `radius` (data units; 0 = 1.5 x the median nearest-neighbour
  /// spacing: wide enough that the near side hides the far side). InputError for an empty cloud.
  explicit ViewCaster(const core::Points& cloud, double radius = 0.0);
  ~ViewCaster();
  ViewCaster(ViewCaster&&) noexcept;
  ViewCaster& operator=(ViewCaster&&) noexcept;

  /// The view from `direction` (unit, from the object's bounding-box centre), at the distance at which the
  /// object's bounding sphere fits the camera.
  View cast(const Eigen::Vector3d& direction, const CameraSettings& camera = {}) const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace partreg::eval
