#include "partreg/core/space/category_model.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"

namespace partreg::core {

const ShapeSpace& CategoryModel::space(const std::string& name) const {
  std::string known;
  for (const ShapeSpace& candidate : spaces) {
    if (candidate.name == name) return candidate;
    known += (known.empty() ? "" : ", ") + candidate.name;
  }
  throw UsageError("category '" + category + "' has no space '" + name + "' (it has: " + known + ")");
}

Points CategoryModel::training_weight_field(int instance) const {
  if (instance < 0 || instance >= training_weights.rows())
    throw UsageError("model '" + category + "' has no training instance " + std::to_string(instance));
  const Eigen::VectorXd row = training_weights.row(instance).transpose();
  return Eigen::Map<const Points>(row.data(), row.size() / 3, 3);
}

std::vector<int> CategoryModel::part_rows(int part_index) const {
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < canonical_part.size(); ++i)
    if (canonical_part[i] == part_index) rows.push_back(static_cast<int>(i));
  return rows;
}

void CategoryModel::validate() const {
  const Eigen::Index m = canonical.rows();
  auto fail = [&](const std::string& what) { throw InputError("model '" + category + "': " + what); };
  if (m == 0) fail("no canonical points");
  if (!canonical.allFinite()) fail("canonical points are not finite");
  if (!(normalization.scale > 0.0) || !std::isfinite(normalization.scale))
    fail("the normalisation scale must be a positive finite length");
  if (!normalization.centre.allFinite()) fail("the normalisation centre is not finite");
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6) fail("the up axis must be a finite unit vector");
  if (size && !(*size > 0.0 && std::isfinite(*size) && data_size > 0.0 && std::isfinite(data_size)))
    fail("a real size needs a positive finite size and data size");
  if (training.seam_weight && !(*training.seam_weight >= 0.0 && *training.seam_weight <= 1e6))
    fail("the seam weight must lie in [0, 1e6]");
  for (const SeamWeightTrial& trial : training.seam_weight_trials)
    if (!(trial.weight >= 0.0 && trial.weight <= 1e6) || !(trial.error >= 0.0) || !std::isfinite(trial.error))
      fail("a seam weight trial needs a weight in [0, 1e6] and a finite error >= 0");
  if (!canonical_mesh.vertices.allFinite()) fail("mesh vertices are not finite");
  if (canonical_part.size() != m) fail("part labels do not match the canonical points");
  const int parts = static_cast<int>(part_names.size());
  if (canonical_part.size() > 0 &&
      (canonical_part.minCoeff() < 0 || canonical_part.maxCoeff() >= std::max(parts, 1)))
    fail("a canonical point has a part index out of range");
  if (canonical_mesh.faces.size() > 0 && (canonical_mesh.faces.minCoeff() < 0 ||
                                          canonical_mesh.faces.maxCoeff() >= canonical_mesh.vertices.rows()))
    fail("a mesh face refers to a vertex that does not exist");
  if (mesh_vertex_part.size() != canonical_mesh.vertices.rows())
    fail("mesh part labels do not match its vertices");
  if (mesh_vertex_part.size() > 0 &&
      (mesh_vertex_part.minCoeff() < 0 || mesh_vertex_part.maxCoeff() >= std::max(parts, 1)))
    fail("a mesh vertex has a part index out of range");
  if (spaces.empty() || spaces.front().name != "holistic") fail("the first space must be the holistic one");
  if (spaces.size() != static_cast<std::size_t>(parts) + 1)
    fail("there must be one space per part plus holistic");
  const auto instances = static_cast<Eigen::Index>(training.instances.size());
  if (training_weights.rows() != instances || training_weights.cols() != 3 * m)
    fail("the training weight fields do not match the instances and canonical points");
  if (!training_weights.allFinite()) fail("the training weight fields are not finite");
  for (const ShapeSpace& space : spaces) {
    const Eigen::Index rows = space.canonical.rows();
    const Eigen::Index q = space.basis.cols();
    if (static_cast<Eigen::Index>(space.point_indices.size()) != rows)
      fail("space " + space.name + ": bad indices");
    for (int index : space.point_indices)
      if (index < 0 || index >= m) fail("space " + space.name + ": index out of range");
    if (space.mean.size() != 3 * rows || space.basis.rows() != 3 * rows ||
        space.kernel_mean.size() != 3 * rows || space.kernel_basis.rows() != 3 * rows ||
        space.kernel_basis.cols() != q || space.variances.size() != q)
      fail("space " + space.name + ": array sizes do not agree");
    if (space.training_latents.rows() != instances || space.training_latents.cols() != q)
      fail("space " + space.name + ": training latents do not match the instances and dimensions");
    if (!(space.beta > 0.0) || !std::isfinite(space.beta))
      fail("space " + space.name + ": beta must be positive");
    if (!space.mean.allFinite() || !space.basis.allFinite() || !space.kernel_mean.allFinite() ||
        !space.kernel_basis.allFinite() || !space.training_latents.allFinite() ||
        !space.variances.allFinite() || !std::isfinite(space.total_variance))
      fail("space " + space.name + ": an array holds NaN or infinite values");
    if (space.variances.size() > 0 && space.variances.minCoeff() < 0.0)
      fail("space " + space.name + ": a variance is negative");
  }
}

}  // namespace partreg::core
