#include "partreg/core/geometry/truth_errors.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core {
namespace {

Eigen::VectorXd squared_to_closest(const Points& from, const KdTree& to) {
  if (from.rows() == 0 || to.size() == 0) throw InputError("cannot measure an error with an empty point set");
  std::vector<int> index;
  Eigen::VectorXd squared;
  to.nearest_all(from, index, squared);
  return squared;
}

std::map<std::string, double> per_part_mean(const Eigen::VectorXd& squared, const Eigen::VectorXi& part,
                                            const std::vector<std::string>& part_names, double scale) {
  std::map<std::string, double> means;
  if (part.size() != squared.size()) return means;
  for (std::size_t p = 0; p < part_names.size(); ++p) {
    double sum = 0.0;
    int count = 0;
    for (Eigen::Index i = 0; i < part.size(); ++i)
      if (part[i] == static_cast<int>(p)) sum += squared[i], ++count;
    if (count > 0) means[part_names[p]] = sum / count / scale;
  }
  return means;
}

// The headline's symmetric RMS between two point sets, in their units.
double symmetric_rms(const Points& a, const Points& b) {
  return 0.5 * (std::sqrt(squared_to_closest(a, KdTree(b)).mean()) +
                std::sqrt(squared_to_closest(b, KdTree(a)).mean()));
}

// Each part of the deformed points against the same part of the truth, / D; a part missing from either side
// is left out (a truth whose labels lack a part says nothing about it).
std::map<std::string, double> own_part_rms(const Points& deformed, const Eigen::VectorXi& part,
                                           const std::vector<std::string>& part_names, const Points& truth,
                                           const Eigen::VectorXi& truth_part, double diagonal) {
  if (part.size() != deformed.rows() || truth_part.size() != truth.rows())
    throw InputError("part labels do not match the points they label (" + std::to_string(part.size()) +
                     " for " + std::to_string(deformed.rows()) + " deformed, " +
                     std::to_string(truth_part.size()) + " for " + std::to_string(truth.rows()) + " true)");
  std::map<std::string, double> figures;
  for (std::size_t p = 0; p < part_names.size(); ++p) {
    const Points mine = select_rows(deformed, rows_with(part, static_cast<int>(p)));
    const Points theirs = select_rows(truth, rows_with(truth_part, static_cast<int>(p)));
    if (mine.rows() > 0 && theirs.rows() > 0) figures[part_names[p]] = symmetric_rms(mine, theirs) / diagonal;
  }
  return figures;
}

}  // namespace

double closest_point_error(const Points& deformed, const Points& truth) {
  if (truth.rows() == 0) throw InputError("cannot measure an error with an empty point set");
  return squared_to_closest(deformed, KdTree(truth)).mean();
}

double chamfer_distance(const Points& a, const Points& b) {
  if (a.rows() == 0 || b.rows() == 0) throw InputError("cannot measure an error with an empty point set");
  return 0.5 * (squared_to_closest(a, KdTree(b)).cwiseSqrt().mean() +
                squared_to_closest(b, KdTree(a)).cwiseSqrt().mean());
}

double truth_diagonal(const Points& truth) { return bounding_box_diagonal(truth); }

double correspondence_error(const Points& material, const Points& truth_of_row, double diagonal) {
  if (material.rows() != truth_of_row.rows() || material.rows() == 0)
    throw InputError("ground-truth correspondences do not match the moved points");
  if (!(diagonal > 0.0)) throw InputError("the truth's diagonal must be positive");
  return (material - truth_of_row).rowwise().norm().mean() / diagonal;
}

TruthErrors measure_against_truth(const Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const Points& truth,
                                  double diagonal, const Points* truth_of_row,
                                  const Eigen::VectorXi* truth_part) {
  if (truth.rows() == 0) throw InputError("cannot measure an error with an empty point set");
  return measure_against_truth(deformed, part, part_names, KdTree(truth), diagonal, truth_of_row, truth_part);
}

TruthErrors measure_against_truth(const Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const KdTree& truth,
                                  double diagonal, const Points* truth_of_row,
                                  const Eigen::VectorXi* truth_part) {
  if (deformed.rows() == 0) throw InputError("cannot measure an error with an empty point set");
  if (!(diagonal > 0.0))
    throw InputError("the ground truth has no extent (its diagonal is " + std::to_string(diagonal) + ")");
  const Eigen::VectorXd forward = squared_to_closest(deformed, truth);
  const Eigen::VectorXd reverse = squared_to_closest(truth.points(), KdTree(deformed));
  const double diagonal2 = diagonal * diagonal;
  TruthErrors errors;
  errors.diagonal = diagonal;
  errors.eq5 = forward.mean();
  errors.eq5_per_diagonal2 = errors.eq5 / diagonal2;
  errors.reverse_eq5 = reverse.mean();
  errors.symmetric_rms_per_diagonal =
      0.5 * (errors.forward_rms_per_diagonal() + errors.reverse_rms_per_diagonal());
  errors.chamfer = 0.5 * (forward.cwiseSqrt().mean() + reverse.cwiseSqrt().mean());
  errors.chamfer_per_diagonal = errors.chamfer / diagonal;
  errors.part_eq5_per_diagonal2 = per_part_mean(forward, part, part_names, diagonal2);
  if (truth_of_row) {
    if (truth_of_row->rows() != deformed.rows())
      throw InputError("ground-truth correspondences do not match the deformed points");
    errors.correspondence_per_diagonal = correspondence_error(deformed, *truth_of_row, diagonal);
  }
  if (truth_part && !part_names.empty()) {
    errors.own_part_rms_per_diagonal =
        own_part_rms(deformed, part, part_names, truth.points(), *truth_part, diagonal);
    if (!errors.own_part_rms_per_diagonal.empty()) {
      double sum = 0.0;
      for (const auto& entry : errors.own_part_rms_per_diagonal) sum += entry.second;
      errors.own_part_rms_mean_per_diagonal = sum / errors.own_part_rms_per_diagonal.size();
    }
  }
  return errors;
}

}  // namespace partreg::core
