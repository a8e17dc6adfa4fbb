#pragma once
/// \file
/// Deterministic shapes for the render tests (no random numbers: the baselines depend on every point).

#include <cmath>

#include "partreg/core/types.hpp"
#include "partreg/render/scene.hpp"
#include "support/test_shapes.hpp"

namespace partreg::testing {

inline constexpr double kPi = 3.14159265358979323846;

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
