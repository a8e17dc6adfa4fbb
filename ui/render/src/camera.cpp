#include "partreg/render/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "partreg/core/errors.hpp"

namespace partreg::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPi / 180.0; }

Bounds unit_box_around(const Eigen::Vector3d& centre) {
  Bounds box;
  box.extend(Eigen::Vector3d(centre - Eigen::Vector3d::Constant(0.5)));
  box.extend(Eigen::Vector3d(centre + Eigen::Vector3d::Constant(0.5)));
  return box;
}

}  // namespace

void Bounds::extend(const Eigen::Vector3d& point) {
  if (!point.allFinite()) return;
  min = min.cwiseMin(point);
  max = max.cwiseMax(point);
}

void Bounds::extend(const core::Points& points) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) extend(Eigen::Vector3d(points.row(i).transpose()));
}

void Bounds::extend(const Bounds& other) {
  if (other.empty()) return;
  extend(other.min);
  extend(other.max);
}

Eigen::Matrix4f Camera::view_matrix() const {
  const Eigen::Vector3d backward = eye - target;
  if (!(backward.norm() > 0.0)) throw UsageError("the camera's eye and target coincide");
  const Eigen::Vector3d z = backward.normalized();
  const Eigen::Vector3d x = up.cross(z);
  if (!(x.norm() > 1e-9 * up.norm())) throw UsageError("the camera's up vector is parallel to its view");
  const Eigen::Vector3d x_unit = x.normalized();
  const Eigen::Vector3d y = z.cross(x_unit);
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = x_unit.transpose();
  view.block<1, 3>(1, 0) = y.transpose();
  view.block<1, 3>(2, 0) = z.transpose();
  view.block<3, 1>(0, 3) = -view.topLeftCorner<3, 3>() * eye;
  return view.cast<float>();
}

Eigen::Matrix4f Camera::projection_matrix(double aspect, double near, double far) const {
  const double f = 1.0 / std::tan(0.5 * radians(fov_y_deg));
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = f / aspect;
  projection(1, 1) = f;
  projection(2, 2) = (far + near) / (near - far);
  projection(2, 3) = 2.0 * far * near / (near - far);
  projection(3, 2) = -1.0;
  return projection.cast<float>();
}

Eigen::Vector3d Camera::right() const { return up.cross(eye - target).normalized(); }

Camera OrbitCamera::camera() const {
  const double azimuth = radians(azimuth_deg);
  const double elevation = radians(std::clamp(elevation_deg, -90.0, 90.0));
  const Eigen::Vector3d direction(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                  std::cos(elevation) * std::cos(azimuth));
  Camera camera;
  camera.target = target;
  camera.eye = target + distance * direction;
  // The derivative of the eye position by elevation: defined even straight above or below.
  camera.up = Eigen::Vector3d(-std::sin(elevation) * std::sin(azimuth), std::cos(elevation),
                              -std::sin(elevation) * std::cos(azimuth));
  camera.fov_y_deg = fov_y_deg;
  return camera;
}

OrbitCamera named_orbit(View view) {
  OrbitCamera orbit;
  orbit.distance = 1.0;
  switch (view) {
    case View::front:
      orbit.azimuth_deg = 180.0, orbit.elevation_deg = 0.0;
      break;
    case View::side:
      orbit.azimuth_deg = 90.0, orbit.elevation_deg = 0.0;
      break;
    case View::top:
      orbit.azimuth_deg = 180.0, orbit.elevation_deg = 90.0;
      break;
    case View::iso:
      orbit.azimuth_deg = 135.0, orbit.elevation_deg = 30.0;
      break;
  }
  return orbit;
}

Camera fit_camera(const core::Points& points, View view, double aspect, double margin, double fov_y_deg) {
  Bounds box;
  box.extend(points);
  if (box.empty() || box.diagonal() == 0.0) {
    const Eigen::Vector3d centre = box.empty() ? Eigen::Vector3d::Zero() : box.centre();
    return fit_camera(unit_box_around(centre), view, aspect, margin, fov_y_deg);
  }
  OrbitCamera orbit = named_orbit(view);
  orbit.fov_y_deg = fov_y_deg;
  const Camera unit = orbit.camera();  // gives the view's axes
  const Eigen::Vector3d backward = (unit.eye - unit.target).normalized();
  const Eigen::Vector3d right = unit.right();
  const Eigen::Vector3d up = backward.cross(right);
  Eigen::Matrix3d axes;
  axes << right.transpose(), up.transpose(), backward.transpose();
  // The points in the view's axes; the target goes to the middle of their extent along each axis.
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) continue;
    const Eigen::Vector3d in_view = axes * points.row(i).transpose();
    low = low.cwiseMin(in_view);
    high = high.cwiseMax(in_view);
  }
  const Eigen::Vector3d middle = 0.5 * (low + high);
  orbit.target = axes.transpose() * middle;
  // The eye at distance d sees a point at (x, y, z) (view axes about the target, z towards the eye) when
  // |x| <= (d - z) tan_x and |y| <= (d - z) tan_y: the nearest d that holds every point.
  const double tan_y = std::tan(0.5 * radians(fov_y_deg)), tan_x = tan_y * aspect;
  double distance = 0.0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) continue;
    const Eigen::Vector3d p = axes * points.row(i).transpose() - middle;
    distance = std::max(
        {distance, p.z() + margin * std::abs(p.x()) / tan_x, p.z() + margin * std::abs(p.y()) / tan_y});
  }
  orbit.distance = std::max(distance, 1e-3 * box.diagonal());
  return orbit.camera();
}

Camera fit_camera(const Bounds& bounds, View view, double aspect, double margin, double fov_y_deg) {
  const Bounds box = bounds.empty() || bounds.diagonal() == 0.0
                         ? unit_box_around(bounds.empty() ? Eigen::Vector3d::Zero() : bounds.centre())
                         : bounds;
  core::Points corners(8, 3);
  for (int corner = 0; corner < 8; ++corner)
    corners.row(corner) << ((corner & 1) ? box.max.x() : box.min.x()),
        ((corner & 2) ? box.max.y() : box.min.y()), ((corner & 4) ? box.max.z() : box.min.z());
  return fit_camera(corners, view, aspect, margin, fov_y_deg);
}

Eigen::Vector2d clip_range(const Camera& camera, const Bounds& bounds) {
  const double distance = (camera.eye - camera.target).norm();
  if (bounds.empty()) return Eigen::Vector2d(distance * 0.01, distance * 100.0);
  const double radius = 0.5 * bounds.diagonal();
  const double centre_distance = (bounds.centre() - camera.eye).norm();
  const double far = centre_distance + radius * 1.01 + 1e-9;
  const double near = std::max(centre_distance - radius * 1.01, far * 1e-4);
  return Eigen::Vector2d(near, far);
}

}  // namespace partreg::render
