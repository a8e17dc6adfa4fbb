#include "partreg/eval/metrics.hpp"

#include "partreg/core/errors.hpp"
#include "partreg/core/kdtree.hpp"

namespace partreg::eval {

RegistrationErrors measure_errors(const core::Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const core::Points& truth,
                                  double diagonal, const core::Points* truth_of_row) {
  if (truth.rows() == 0) throw InputError("cannot measure errors of an empty set");
  return measure_errors(deformed, part, part_names, core::KdTree(truth), diagonal, truth_of_row);
}

RegistrationErrors measure_errors(const core::Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const core::KdTree& truth,
                                  double diagonal, const core::Points* truth_of_row) {
  if (deformed.rows() == 0 || truth.size() == 0) throw InputError("cannot measure errors of an empty set");
  if (!(diagonal > 0)) throw InputError("the ground truth has no extent");
  RegistrationErrors errors;
  std::vector<int> nearest;
  Eigen::VectorXd squared, reverse_squared;
  truth.nearest_all(deformed, nearest, squared);
  core::KdTree(deformed).nearest_all(truth.points(), nearest, reverse_squared);
  const double diagonal2 = diagonal * diagonal;
  errors.eq5 = squared.mean();
  errors.eq5_normalised = errors.eq5 / diagonal2;
  // Symmetric Chamfer (as core::chamfer_distance) from the distances already found one way.
  errors.chamfer = 0.5 * (squared.cwiseSqrt().mean() + reverse_squared.cwiseSqrt().mean());
  errors.chamfer_normalised = errors.chamfer / diagonal;
  for (std::size_t p = 0; p < part_names.size() && part.size() == deformed.rows(); ++p) {
    double sum = 0.0;
    int count = 0;
    for (Eigen::Index i = 0; i < part.size(); ++i)
      if (part[i] == static_cast<int>(p)) sum += squared[i], ++count;
    if (count > 0) errors.part_eq5_normalised[part_names[p]] = sum / count / diagonal2;
  }
  if (truth_of_row) {
    if (truth_of_row->rows() != deformed.rows())
      throw InputError("ground-truth correspondences do not match the deformed points");
    errors.correspondence_normalised = (deformed - *truth_of_row).rowwise().norm().mean() / diagonal;
  }
  return errors;
}

}  // namespace partreg::eval
