#include "partreg/io/registration_outputs.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::io {

PointAttributes fit_attributes(const core::Points& points, const Eigen::VectorXi& part,
                               const std::vector<std::string>& part_names, const core::Points& observed) {
  PointAttributes attributes;
  if (part.size() == points.rows()) {
    attributes.integers["part"] = part;
    attributes.part_names = part_names;
  }
  if (observed.rows() == 0) return attributes;
  std::vector<int> nearest;
  Eigen::VectorXd squared;
  core::KdTree(observed).nearest_all(points, nearest, squared);
  attributes.integers["correspondence"] = Eigen::Map<const Eigen::VectorXi>(nearest.data(), points.rows());
  attributes.reals["residual"] = squared.cwiseSqrt();
  return attributes;
}

core::Points vertex_normals(const core::Mesh& mesh) {
  core::Points normals = core::Points::Zero(mesh.vertices.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::RowVector3d a = mesh.vertices.row(mesh.faces(f, 0)), b = mesh.vertices.row(mesh.faces(f, 1)),
                             c = mesh.vertices.row(mesh.faces(f, 2));
    const Eigen::RowVector3d area_weighted = (b - a).cross(c - a);  // twice the area, along the normal
    for (int k = 0; k < 3; ++k) normals.row(mesh.faces(f, k)) += area_weighted;
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v)
    if (normals.row(v).norm() > 0.0) normals.row(v).normalize();
  return normals;
}

void write_registered_points(const std::filesystem::path& path, const core::CategoryModel& model,
                             const core::RegistrationResult& result, const core::Points& observed) {
  core::Cloud cloud{result.deformed, {}};
  if (model.canonical_mesh.faces.rows() > 0) {  // each point takes its nearest deformed vertex's normal
    const core::Mesh mesh = core::deform_mesh(model, result);
    const core::Points normals = vertex_normals(mesh);
    std::vector<int> on_faces;  // a vertex on no face has no normal to give
    for (Eigen::Index v = 0; v < normals.rows(); ++v)
      if (normals.row(v).squaredNorm() > 0.0) on_faces.push_back(static_cast<int>(v));
    std::vector<int> nearest;
    Eigen::VectorXd squared;
    core::KdTree(mesh.vertices(on_faces, Eigen::all)).nearest_all(result.deformed, nearest, squared);
    cloud.normals.resize(result.deformed.rows(), 3);
    for (Eigen::Index i = 0; i < cloud.normals.rows(); ++i)
      cloud.normals.row(i) = normals.row(on_faces[static_cast<std::size_t>(nearest[static_cast<std::size_t>(i)])]);
  }
  write_cloud(path, cloud, fit_attributes(result.deformed, result.part, model.part_names, observed));
}

void write_registered_mesh(const std::filesystem::path& path, const core::CategoryModel& model,
                           const core::RegistrationResult& result, const core::Points& observed) {
  if (model.canonical_mesh.faces.rows() == 0)
    throw InputError("model '" + model.category + "' has no canonical mesh (it was trained on clouds)");
  core::Mesh mesh = core::deform_mesh(model, result);
  mesh.normals = vertex_normals(mesh);
  write_mesh(path, mesh, fit_attributes(mesh.vertices, model.mesh_vertex_part, model.part_names, observed));
}

}  // namespace partreg::io
