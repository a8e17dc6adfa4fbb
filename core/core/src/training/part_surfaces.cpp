#include "part_surfaces.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "partreg/core/geometry/kdtree.hpp"

namespace partreg::core::detail {
namespace {

double point_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double normal2 = normal.squaredNorm();
  if (normal2 > 0.0) {
    // The foot of the perpendicular lies inside when it is on the inner side of every edge; then the distance
    // is the height above the plane, otherwise the nearest point is on an edge.
    const Eigen::Vector3d foot = p - (p - a).dot(normal) / normal2 * normal;
    const bool inside = (b - a).cross(foot - a).dot(normal) >= 0.0 &&
                        (c - b).cross(foot - b).dot(normal) >= 0.0 &&
                        (a - c).cross(foot - c).dot(normal) >= 0.0;
    if (inside) return (p - foot).norm();
  }
  return std::min(
      {point_segment_distance(p, a, b), point_segment_distance(p, b, c), point_segment_distance(p, c, a)});
}

PartsThrough parts_through_points(const Mesh& mesh, const Eigen::VectorXi& vertex_part, int part_count,
                                  const Points& points, double tolerance) {
  PartsThrough through = PartsThrough::Constant(points.rows(), part_count, false);
  if (points.rows() == 0 || vertex_part.size() != mesh.vertices.rows()) return through;
  const KdTree tree(points);
  std::vector<std::pair<int, double>> near;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2));
    // Every point within `tolerance` of the face lies within its centroid's reach plus the tolerance.
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const double reach = std::max({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()});
    tree.radius(centroid, reach + tolerance, near);
    for (const auto& hit : near) {
      const int row = hit.first;
      bool needed = false;
      for (int corner = 0; corner < 3; ++corner) {
        const int part = vertex_part[mesh.faces(f, corner)];
        needed |= part >= 0 && part < part_count && !through(row, part);
      }
      if (!needed || point_triangle_distance(points.row(row).transpose(), a, b, c) > tolerance) continue;
      for (int corner = 0; corner < 3; ++corner) {
        const int part = vertex_part[mesh.faces(f, corner)];
        if (part >= 0 && part < part_count) through(row, part) = true;
      }
    }
  }
  return through;
}

}  // namespace partreg::core::detail
