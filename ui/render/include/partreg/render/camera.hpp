#pragma once
/// \file
/// Cameras: an explicit eye/target/up camera, an orbit camera around a target, and the named views that
/// fit a scene's bounds. partreg's frame has +Y up and the front towards -Z (as the ShapeNet data and the
/// synthetic categories); named views look at it from -Z (front), +X (side), +Y (top, front at the bottom of
/// the image) or from above between the front and the side (iso: azimuth 135, elevation 30 degrees).

#include <Eigen/Core>
#include <limits>
#include <string>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/types.hpp"

namespace partreg::render {

/// An axis-aligned box; empty until something is added.
struct Bounds {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return !(min.array() <= max.array()).all(); }
  void extend(const Eigen::Vector3d& point);
  void extend(const core::Points& points);  ///< non-finite points are skipped
  void extend(const Bounds& other);
  Eigen::Vector3d centre() const { return 0.5 * (min + max); }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
};

enum class View { front, side, top, iso };
}  // namespace partreg::render

template <>
struct partreg::core::EnumNames<partreg::render::View> {
  using E = partreg::render::View;
  static constexpr const char* what = "view";
  static constexpr std::array<std::pair<E, const char*>, 4> table{
      {{E::front, "front"}, {E::side, "side"}, {E::top, "top"}, {E::iso, "iso"}}};
};

namespace partreg::render {

/// A perspective camera given by where it is, what it looks at and which way is up (scene units).
struct Camera {
  Eigen::Vector3d eye = Eigen::Vector3d(0.0, 0.0, 3.0);
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double fov_y_deg = 30.0;  ///< vertical field of view (degrees)

  /// World -> view transform (the camera looks down its -z axis). UsageError when eye == target or up is
  /// parallel to the viewing direction.
  Eigen::Matrix4f view_matrix() const;
  /// Perspective projection for a width/height `aspect` and clip distances (scene units, near > 0).
  Eigen::Matrix4f projection_matrix(double aspect, double near, double far) const;
  /// The camera's right direction (unit) in scene coordinates.
  Eigen::Vector3d right() const;
};

/// An orbit camera: a target, a distance and two angles; what the window's mouse turns.
struct OrbitCamera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double distance = 3.0;        ///< eye to target (scene units)
  double azimuth_deg = 45.0;    ///< about +Y, 0 = looking from +Z, 90 = from +X
  double elevation_deg = 30.0;  ///< above the horizontal plane, in [-90, 90] (90 = from straight above)
  double fov_y_deg = 30.0;      ///< vertical field of view (degrees)

  /// The camera; its up vector is the orbit's, so a view from straight above keeps the far side up.
  Camera camera() const;
};

/// The orbit camera of a named view at unit distance around the origin.
OrbitCamera named_orbit(View view);

/// A camera of `view` that frames `points` tightly for an image of width/height `aspect`: the target is the
/// middle of their extent across the view, and the eye is as close as it can be with every point inside the
/// image, `margin` times further from the image's centre than needed. Non-finite points are ignored; no
/// points (or all in one place) frame the unit box around them.
Camera fit_camera(const core::Points& points, View view, double aspect, double margin = 1.05,
                  double fov_y_deg = 30.0);

/// The camera of `view` that frames the corners of `bounds` (as above).
Camera fit_camera(const Bounds& bounds, View view, double aspect, double margin = 1.05,
                  double fov_y_deg = 30.0);

/// Near and far clip distances that hold all of `bounds` seen from `camera`.
Eigen::Vector2d clip_range(const Camera& camera, const Bounds& bounds);

}  // namespace partreg::render
