#include "partreg/core/geometry/normalization.hpp"

#include "partreg/core/errors.hpp"

namespace partreg::core {

double bounding_box_diagonal(const Points& points) {
  if (points.rows() == 0) throw InputError("cannot measure the bounding box of an empty point set");
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

Normalization Normalization::fit(const Points& reference) {
  if (reference.rows() == 0) throw InputError("cannot normalise an empty point set");
  if (!reference.allFinite()) throw InputError("cannot normalise a point set holding NaN or infinite values");
  Normalization normalization;
  const Eigen::RowVector3d lower = reference.colwise().minCoeff();
  const Eigen::RowVector3d upper = reference.colwise().maxCoeff();
  normalization.centre = (0.5 * (lower + upper)).transpose();
  normalization.scale = (upper - lower).norm();
  if (!(normalization.scale > 0.0))
    throw InputError("cannot normalise a point set whose points all coincide");
  return normalization;
}

Points Normalization::apply(const Points& data_points) const {
  return (data_points.rowwise() - centre.transpose()) / scale;
}

Points Normalization::undo(const Points& normalised_points) const {
  return (normalised_points * scale).rowwise() + centre.transpose();
}

}  // namespace partreg::core
