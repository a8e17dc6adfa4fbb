#pragma once
/// \file
/// The viewport's camera as plain data, and picking: the ray under a pixel and the mesh face it hits. The
/// orbit parameters and the eye/target/up they give are the same as partreg::render::OrbitCamera's, so a
/// pixel picked here is the pixel the renderer drew (the app converts with to_render_camera).

#include <Eigen/Core>
#include <optional>
#include <string>

#include "partreg/core/types.hpp"

namespace partreg::ui {

/// The frame the app draws: the whole window; panels cover a column on the left, and the camera shifts the
/// scene so that it is centred in the rest.
struct Viewport {
  int width = 1280;       ///< pixels
  int height = 800;       ///< pixels
  int panel_width = 360;  ///< pixels covered by the panels on the left (0 = none)
};

/// An orbit camera (as render::OrbitCamera): +Y up, azimuth 0 looks from +Z, elevation 90 from above.
struct OrbitView {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< scene units
  double distance = 3.0;                             ///< eye to target (scene units)
  double azimuth_deg = 45.0;
  double elevation_deg = 30.0;
  double fov_y_deg = 30.0;  ///< vertical field of view (degrees)
};

/// Eye, target and up of the camera that draws `view` in `viewport` (target shifted by half the panel
/// column, so the orbit target appears in the middle of the uncovered part).
struct CameraFrame {
  Eigen::Vector3d eye, target, up;
  double fov_y_deg = 30.0;
};
CameraFrame camera_frame(const OrbitView& view, const Viewport& viewport);

/// The orbit of a named view ("front" | "side" | "top" | "iso"; UsageError otherwise) that frames the box
/// [low, high] in the uncovered part of `viewport`.
OrbitView named_view(const std::string& name, const Eigen::Vector3d& low, const Eigen::Vector3d& high,
                     const Viewport& viewport);

/// A ray from the eye through the centre of pixel (x, y) (x right, y down, from the top-left corner).
struct Ray {
  Eigen::Vector3d origin, direction;  ///< direction is unit
};
Ray pixel_ray(const OrbitView& view, const Viewport& viewport, double x, double y);

/// The pixel (x right, y down) where `point` appears, inverse of pixel_ray; NaN behind the eye.
Eigen::Vector2d project(const OrbitView& view, const Viewport& viewport, const Eigen::Vector3d& point);

/// Scene length covered by one pixel at `depth` along the viewing direction.
double pixel_size_at(const OrbitView& view, const Viewport& viewport, double depth);

/// The nearest face a ray hits.
struct Hit {
  int face = -1;
  double distance = 0.0;  ///< along the ray (scene units)
  Eigen::Vector3d point;
};
/// Brute force over every face (Moller-Trumbore, both sides); about 1 ms per 100k faces.
std::optional<Hit> intersect(const core::Mesh& mesh, const Ray& ray);

}  // namespace partreg::ui
