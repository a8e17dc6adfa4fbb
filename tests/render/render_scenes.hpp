#pragma once
/// \file
/// Deterministic shapes for the render tests (no random numbers: the baselines depend on every point).

#include <cmath>

#include "partreg/core/types.hpp"
#include "partreg/render/scene.hpp"

namespace partreg::testing {

inline constexpr double kPi = 3.14159265358979323846;

/// A UV sphere of `radius` around `centre`: `rings` x `segments` quads split in two.
inline core::Mesh uv_sphere(double radius, int rings, int segments,
                            const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  core::Mesh mesh;
  mesh.vertices.resize((rings + 1) * segments, 3);
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = kPi * r / rings, phi = 2.0 * kPi * s / segments;
      mesh.vertices.row(r * segments + s) =
          (centre + radius * Eigen::Vector3d(std::sin(theta) * std::sin(phi), std::cos(theta),
                                             std::sin(theta) * std::cos(phi)))
              .transpose();
    }
  mesh.faces.resize(2 * rings * segments, 3);
  int f = 0;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      mesh.faces.row(f++) << a, c, b;
      mesh.faces.row(f++) << b, c, d;
    }
  return mesh;
}

/// An open cylinder (no caps) about +Y: the inside shows, so it needs two-sided lighting.
inline core::Mesh open_cylinder(double radius, double height, int segments) {
  core::Mesh mesh;
  mesh.vertices.resize(2 * segments, 3);
  for (int s = 0; s < segments; ++s) {
    const double phi = 2.0 * kPi * s / segments;
    mesh.vertices.row(s) << radius * std::sin(phi), -0.5 * height, radius * std::cos(phi);
    mesh.vertices.row(segments + s) << radius * std::sin(phi), 0.5 * height, radius * std::cos(phi);
  }
  mesh.faces.resize(2 * segments, 3);
  for (int s = 0; s < segments; ++s) {
    const int a = s, b = (s + 1) % segments;
    mesh.faces.row(2 * s) << a, b, segments + a;
    mesh.faces.row(2 * s + 1) << b, segments + b, segments + a;
  }
  return mesh;
}

/// A mug as points: a body (part 0, an open-topped cylinder with a bottom) and a handle (part 1, half a
/// torus on the +X side). Rows: body first, then handle.
inline core::Points mug_points(Eigen::VectorXi& part) {
  std::vector<Eigen::RowVector3d> rows;
  std::vector<int> parts;
  for (int h = 0; h < 40; ++h)
    for (int s = 0; s < 90; ++s) {
      const double phi = 2.0 * kPi * s / 90, y = -0.5 + h / 39.0;
      rows.emplace_back(0.4 * std::sin(phi), y, 0.4 * std::cos(phi));
      parts.push_back(0);
    }
  for (int r = 1; r <= 12; ++r)
    for (int s = 0; s < 6 * r; ++s) {
      const double phi = 2.0 * kPi * s / (6 * r), rho = 0.4 * r / 12.0;
      rows.emplace_back(rho * std::sin(phi), -0.5, rho * std::cos(phi));
      parts.push_back(0);
    }
  for (int a = 0; a <= 30; ++a)
    for (int b = 0; b < 16; ++b) {
      const double alpha = -0.5 * kPi + kPi * a / 30, beta = 2.0 * kPi * b / 16;
      const double ring = 0.25 + 0.05 * std::cos(beta);
      rows.emplace_back(0.4 + ring * std::cos(alpha), ring * std::sin(alpha), 0.05 * std::sin(beta));
      parts.push_back(1);
    }
  core::Points points(static_cast<Eigen::Index>(rows.size()), 3);
  part.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    points.row(static_cast<Eigen::Index>(i)) = rows[i];
    part[static_cast<Eigen::Index>(i)] = parts[i];
  }
  return points;
}

}  // namespace partreg::testing
