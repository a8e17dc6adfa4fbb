#include "partreg/ui/view.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "partreg/core/errors.hpp"

namespace partreg::ui {
namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPi / 180.0; }

double aspect_of(const Viewport& viewport) {
  return static_cast<double>(std::max(1, viewport.width)) / std::max(1, viewport.height);
}

}  // namespace

CameraFrame camera_frame(const OrbitView& view, const Viewport& viewport) {
  // The same eye and up as render::OrbitCamera::camera().
  const double azimuth = radians(view.azimuth_deg);
  const double elevation = radians(std::clamp(view.elevation_deg, -90.0, 90.0));
  const Eigen::Vector3d direction(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                  std::cos(elevation) * std::cos(azimuth));
  CameraFrame frame;
  frame.up = Eigen::Vector3d(-std::sin(elevation) * std::sin(azimuth), std::cos(elevation),
                             -std::sin(elevation) * std::cos(azimuth));
  frame.fov_y_deg = view.fov_y_deg;
  // Shift eye and target together to the left by half the panel column: the target then appears in the
  // middle of the part of the frame the panels leave free.
  const Eigen::Vector3d right = frame.up.cross(direction).normalized();
  const double shift = 0.5 * viewport.panel_width * pixel_size_at(view, viewport, view.distance);
  frame.target = view.target - shift * right;
  frame.eye = frame.target + view.distance * direction;
  return frame;
}

OrbitView named_view(const std::string& name, const Eigen::Vector3d& low, const Eigen::Vector3d& high,
                     const Viewport& viewport) {
  OrbitView view;
  if (name == "front") {
    view.azimuth_deg = 0.0, view.elevation_deg = 0.0;
  } else if (name == "side") {
    view.azimuth_deg = 90.0, view.elevation_deg = 0.0;
  } else if (name == "top") {
    view.azimuth_deg = 0.0, view.elevation_deg = 90.0;
  } else if (name == "iso") {
    view.azimuth_deg = 45.0, view.elevation_deg = 30.0;
  } else {
    throw UsageError("unknown view '" + name + "' (front | side | top | iso)");
  }
  view.target = 0.5 * (low + high);
  // The bounding sphere fits the free part of the frame in both directions, with a 10% margin.
  const double radius = std::max(0.5 * (high - low).norm(), 1e-9);
  const double free_width = std::max(1, viewport.width - viewport.panel_width);
  const double tan_y = std::tan(0.5 * radians(view.fov_y_deg));
  const double tan_x = tan_y * free_width / std::max(1, viewport.height);
  view.distance = 1.1 * radius / std::sin(std::atan(std::min(tan_x, tan_y)));
  return view;
}

Ray pixel_ray(const OrbitView& view, const Viewport& viewport, double x, double y) {
  const CameraFrame frame = camera_frame(view, viewport);
  const Eigen::Vector3d backward = (frame.eye - frame.target).normalized();
  const Eigen::Vector3d right = frame.up.cross(backward).normalized();
  const Eigen::Vector3d up = backward.cross(right);
  const double tan_y = std::tan(0.5 * radians(view.fov_y_deg));
  const double ndc_x = 2.0 * (x + 0.5) / std::max(1, viewport.width) - 1.0;
  const double ndc_y = 1.0 - 2.0 * (y + 0.5) / std::max(1, viewport.height);
  Ray ray;
  ray.origin = frame.eye;
  ray.direction = (ndc_x * tan_y * aspect_of(viewport) * right + ndc_y * tan_y * up - backward).normalized();
  return ray;
}

Eigen::Vector2d project(const OrbitView& view, const Viewport& viewport, const Eigen::Vector3d& point) {
  const CameraFrame frame = camera_frame(view, viewport);
  const Eigen::Vector3d backward = (frame.eye - frame.target).normalized();
  const Eigen::Vector3d right = frame.up.cross(backward).normalized();
  const Eigen::Vector3d up = backward.cross(right);
  const Eigen::Vector3d offset = point - frame.eye;
  const double depth = -offset.dot(backward);
  if (depth <= 0.0) return Eigen::Vector2d::Constant(std::nan(""));
  const double tan_y = std::tan(0.5 * radians(view.fov_y_deg));
  const double ndc_x = offset.dot(right) / (depth * tan_y * aspect_of(viewport));
  const double ndc_y = offset.dot(up) / (depth * tan_y);
  return Eigen::Vector2d(0.5 * (ndc_x + 1.0) * viewport.width - 0.5,
                         0.5 * (1.0 - ndc_y) * viewport.height - 0.5);
}

double pixel_size_at(const OrbitView& view, const Viewport& viewport, double depth) {
  return 2.0 * depth * std::tan(0.5 * radians(view.fov_y_deg)) / std::max(1, viewport.height);
}

std::optional<Hit> intersect(const core::Mesh& mesh, const Ray& ray) {
  std::optional<Hit> best;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const Eigen::Vector3d e1 = Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, 1))) - a;
    const Eigen::Vector3d e2 = Eigen::Vector3d(mesh.vertices.row(mesh.faces(f, 2))) - a;
    const Eigen::Vector3d p = ray.direction.cross(e2);
    const double determinant = e1.dot(p);
    if (std::abs(determinant) < 1e-14) continue;  // parallel to the face
    const double inverse = 1.0 / determinant;
    const Eigen::Vector3d s = ray.origin - a;
    const double u = s.dot(p) * inverse;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = ray.direction.dot(q) * inverse;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = e2.dot(q) * inverse;
    if (t <= 0.0 || (best && t >= best->distance)) continue;
    best = Hit{static_cast<int>(f), t, ray.origin + t * ray.direction};
  }
  return best;
}

}  // namespace partreg::ui
