#pragma once
/// \file
/// Small synthetic shapes for tests: asymmetric point sets (a wrong pose cannot fit them) and simple meshes.

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::testing {

/// `count` points on an ellipsoid body (0.5 x 0.3 x 0.2) with a ring-shaped handle on its +x side:
/// no symmetry maps it onto itself. About 1.2 units across.
inline core::Points asymmetric_shape(int count, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  core::Points points(count, 3);
  for (int i = 0; i < count; ++i) {
    const double u = 2.0 * M_PI * uniform(generator), v = std::acos(2.0 * uniform(generator) - 1.0);
    if (i % 4 != 3) {
      points.row(i) << 0.5 * std::sin(v) * std::cos(u), 0.3 * std::sin(v) * std::sin(u),
          0.2 * std::cos(v) + 0.05 * std::cos(3 * u);
    } else {  // a handle: a quarter-thick ring in the x-z plane, offset to +x and tilted up
      const double ring = 0.18 + 0.04 * std::cos(v * 2.0);
      points.row(i) << 0.55 + ring * std::cos(u), 0.04 * std::sin(2.0 * v), 0.1 + ring * std::sin(u) * 0.7;
    }
  }
  return points;
}

/// `count` points spread evenly over a sphere of `radius` about the origin (a Fibonacci lattice).
inline core::Points fibonacci_sphere(int count, double radius) {
  core::Points points(count, 3);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(1.0 - y * y);
    points.row(i) << r * std::cos(golden * i), y, r * std::sin(golden * i);
  }
  return radius * points;
}

/// The lower half of a shell about the origin, opening upwards (+y): an inner hemisphere of radius 0.45 and an
/// outer one 0.02 further out, each the lower half of a `count`-point sphere. A concave shape whose inside
/// faces up while normals turned away from its centroid point down.
inline core::Points open_bowl(int count) {
  const core::Points inner = fibonacci_sphere(count, 0.45), outer = fibonacci_sphere(count, 0.47);
  std::vector<Eigen::RowVector3d> kept;
  for (const core::Points* side : {&inner, &outer})
    for (Eigen::Index i = 0; i < side->rows(); ++i)
      if ((*side)(i, 1) < 0.0) kept.push_back(side->row(i));
  core::Points points(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = kept[i];
  return points;
}

/// A proper rotation about `axis` (normalised here) by `angle_rad`.
inline Eigen::Matrix3d rotation(double angle_rad, Eigen::Vector3d axis) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
}

/// Rotation angle between two rotations, degrees.
inline double rotation_error_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cosine = std::clamp(((a.transpose() * b).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

/// Mean Euclidean distance between corresponding rows.
inline double mean_row_distance(const core::Points& a, const core::Points& b) {
  return (a - b).rowwise().norm().mean();
}

/// A UV sphere of `radius` around `centre`: `rings` x `segments` quads split in two.
inline core::Mesh uv_sphere(double radius, int rings, int segments,
                            const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  core::Mesh mesh;
  mesh.vertices.resize((rings + 1) * segments, 3);
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2.0 * M_PI * s / segments;
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

}  // namespace partreg::testing
