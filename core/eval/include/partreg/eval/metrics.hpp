#pragma once
/// \file
/// The errors of one registration against the ground truth (paper, section 4): Eq. 5 in data units and
/// normalised by the squared bounding-box diagonal of the ground truth, the symmetric Chamfer distance, Eq. 5
/// per part, and where ground-truth correspondences exist, the correspondence error.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/kdtree.hpp"
#include "partreg/core/types.hpp"

namespace partreg::eval {

struct RegistrationErrors {
  double eq5 = 0.0;                 ///< Eq. 5: mean squared closest-point distance (data units squared)
  double eq5_normalised = 0.0;      ///< Eq. 5 / diagonal^2
  double chamfer = 0.0;             ///< symmetric Chamfer distance (data units)
  double chamfer_normalised = 0.0;  ///< Chamfer / diagonal
  std::map<std::string, double>
      part_eq5_normalised;                          ///< Eq. 5 over each part's canonical points / diagonal^2
  std::optional<double> correspondence_normalised;  ///< mean distance to the true correspondent / diagonal
};

/// Errors of `deformed` (the deformed canonical points, part index per row in `part`, names in `part_names`)
/// against `truth` (a dense sample of the whole true instance). `diagonal` is the truth's bounding-box
/// diagonal. `truth_of_row` (same rows as `deformed`, or null) holds where each canonical point truly is.
RegistrationErrors measure_errors(const core::Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const core::Points& truth,
                                  double diagonal, const core::Points* truth_of_row = nullptr);

/// The same with the truth's KD-tree built once by the caller (several registrations against one truth).
RegistrationErrors measure_errors(const core::Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const core::KdTree& truth,
                                  double diagonal, const core::Points* truth_of_row = nullptr);

}  // namespace partreg::eval
