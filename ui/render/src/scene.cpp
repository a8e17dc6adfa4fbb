#include "partreg/render/scene.hpp"

#include <Eigen/Geometry>

#include "partreg/core/errors.hpp"

namespace partreg::render {

bool Scene::empty() const {
  for (const PointSet& set : point_sets)
    if (set.positions.rows() > 0) return false;
  for (const MeshItem& item : meshes)
    if (item.mesh.faces.rows() > 0) return false;
  for (const LineSet& set : line_sets)
    if (set.starts.rows() > 0) return false;
  return true;
}

Bounds Scene::bounds() const {
  Bounds bounds;
  for (const PointSet& set : point_sets) bounds.extend(set.positions);
  for (const MeshItem& item : meshes) bounds.extend(item.mesh.vertices);
  for (const LineSet& set : line_sets) {
    bounds.extend(set.starts);
    bounds.extend(set.ends);
  }
  return bounds;
}

core::Points Scene::all_points() const {
  Eigen::Index count = 0;
  for (const PointSet& set : point_sets) count += set.positions.rows();
  for (const MeshItem& item : meshes) count += item.mesh.vertices.rows();
  for (const LineSet& set : line_sets) count += set.starts.rows() + set.ends.rows();
  core::Points points(count, 3);
  Eigen::Index row = 0;
  const auto append = [&](const core::Points& block) {
    points.middleRows(row, block.rows()) = block;
    row += block.rows();
  };
  for (const PointSet& set : point_sets) append(set.positions);
  for (const MeshItem& item : meshes) append(item.mesh.vertices);
  for (const LineSet& set : line_sets) {
    append(set.starts);
    append(set.ends);
  }
  return points;
}

Colors part_colors(const Eigen::VectorXi& part) {
  Colors colors(part.size(), 3);
  for (Eigen::Index i = 0; i < part.size(); ++i) colors.row(i) = part_color(part[i]).transpose();
  return colors;
}

LineSet make_triad(const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation, double length,
                   float width_pixels) {
  LineSet triad;
  triad.starts = position.transpose().replicate(3, 1);
  triad.ends = triad.starts + length * rotation.transpose();  // row k: position + length * axis k
  triad.colors.resize(3, 3);
  triad.colors << 0.9f, 0.1f, 0.1f, 0.1f, 0.7f, 0.1f, 0.1f, 0.25f, 0.95f;
  triad.width_pixels = width_pixels;
  return triad;
}

LineSet make_correspondences(const core::Points& from, const core::Points& to, Color color,
                             float width_pixels) {
  if (from.rows() != to.rows())
    throw UsageError("correspondences need as many start points as end points (" +
                     std::to_string(from.rows()) + " and " + std::to_string(to.rows()) + ")");
  LineSet lines;
  lines.starts = from;
  lines.ends = to;
  lines.color = color;
  lines.width_pixels = width_pixels;
  return lines;
}

core::Points vertex_normals(const core::Mesh& mesh) {
  // Face normals (length: twice the area) and, per vertex, the largest one as the reference orientation.
  // Each face counts with the sign that agrees with the reference: double-sided meshes (every face twice,
  // once per winding, as many ShapeNet exports) and inconsistently wound ones then do not cancel out.
  core::Points face_normals(mesh.faces.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::RowVector3d a = mesh.vertices.row(mesh.faces(f, 0));
    face_normals.row(f) =
        (mesh.vertices.row(mesh.faces(f, 1)) - a).cross(mesh.vertices.row(mesh.faces(f, 2)) - a);
  }
  core::Points reference = core::Points::Zero(mesh.vertices.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (face_normals.row(f).squaredNorm() > reference.row(mesh.faces(f, k)).squaredNorm())
        reference.row(mesh.faces(f, k)) = face_normals.row(f);
  core::Points normals = core::Points::Zero(mesh.vertices.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = mesh.faces(f, k);
      normals.row(v) += face_normals.row(f).dot(reference.row(v)) < 0.0
                            ? Eigen::RowVector3d(-face_normals.row(f))
                            : Eigen::RowVector3d(face_normals.row(f));
    }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    const double length = normals.row(i).norm();
    normals.row(i) = length > 0.0 ? Eigen::RowVector3d(normals.row(i) / length) : Eigen::RowVector3d::UnitZ();
  }
  return normals;
}

}  // namespace partreg::render
