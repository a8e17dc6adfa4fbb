#pragma once
/// \file
/// How far a registration is from the truth: every error figure partreg reports against a ground-truth
/// instance is computed here, and only here (paper, section 4; `register --truth`, `eval`, the app, Python).
///
/// One normalisation: lengths are divided by the ground-truth instance's bounding-box diagonal D, taken in
/// the instance's own frame (the evaluation's perturbations move the truth rigidly but do not change D).
/// Names carry their units: `_per_diagonal` is a length over D, `_per_diagonal2` a squared length over D^2.

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

/// Points a true instance given as a mesh is sampled to (area-uniform) before registrations are scored
/// against it (`eval`, `register --truth`). The forward half measures against these points, not the surface,
/// so their spacing sets its floor: the kettles' true shapes as the canonical's M points score a forward half
/// of 0.85% of D against 4000 samples and 0.38% against 20000 (docs/evaluation.md, "The truth").
constexpr int kTruthSamples = 20000;

/// The errors of one registration against the whole true instance.
struct TruthErrors {
  double diagonal = 0.0;  ///< D: the truth's bounding-box diagonal (data units)
  double eq5 = 0.0;       ///< the paper's Eq. 5: mean over deformed points of the squared distance to the
                          ///< closest true point (data units squared)
  double eq5_per_diagonal2 = 0.0;  ///< eq5 / D^2
  double reverse_eq5 = 0.0;        ///< Eq. 5 the other way: over the true points (data units squared)
  double symmetric_rms_per_diagonal = 0.0;  ///< (sqrt(eq5) + sqrt(reverse_eq5)) / 2 / D: the headline figure
  double chamfer = 0.0;                     ///< mean closest-point distance each way, halved (data units)
  double chamfer_per_diagonal = 0.0;        ///< chamfer / D
  std::map<std::string, double> part_eq5_per_diagonal2;  ///< Eq. 5 over each part's deformed points / D^2
  std::optional<double> correspondence_per_diagonal;     ///< mean distance to the true correspondent / D
  /// Each part against the same part of the truth (only when the truth has its own parts): the headline's
  /// symmetric RMS between the deformed points of the part and the true points of that part, / D. A part
  /// placed on another part's surface (a handle pressed onto the body) scores well against the whole truth
  /// but not here.
  std::map<std::string, double> own_part_rms_per_diagonal;
  /// The mean of own_part_rms_per_diagonal over the parts (each part counts once, whatever its size).
  std::optional<double> own_part_rms_mean_per_diagonal;

  /// The headline figure's halves, / D (symmetric_rms_per_diagonal is their mean): how close the deformed
  /// points lie to the truth (sqrt Eq. 5), and how closely they cover it. A part that leaves its place for
  /// observed surface lowers the forward half only.
  double forward_rms_per_diagonal() const { return std::sqrt(eq5) / diagonal; }
  double reverse_rms_per_diagonal() const { return std::sqrt(reverse_eq5) / diagonal; }
};

/// The paper's Eq. 5: mean over `deformed` of the squared distance to the closest point of `truth` (squared
/// units of the inputs). InputError for an empty set.
double closest_point_error(const Points& deformed, const Points& truth);

/// Symmetric Chamfer distance: the mean closest-point distance from a to b plus that from b to a, halved
/// (units of the inputs). InputError for an empty set.
double chamfer_distance(const Points& a, const Points& b);

/// The correspondence error: the mean distance from each moved canonical point (`material`, the material
/// points: deform_points with Follow::material) to where it truly is (`truth_of_row`, same rows), over D.
/// InputError for rows that do not match or D <= 0.
double correspondence_error(const Points& material, const Points& truth_of_row, double diagonal);

/// Every figure of `deformed` (deformed canonical points, observed frame, data units; part index per row in
/// `part`, names in `part_names`) against `truth` (a dense sample of the whole true instance, same frame).
/// `diagonal` is D (truth_diagonal() of the instance in its own frame). `truth_of_row` (rows as `deformed`,
/// or null) holds where each canonical point truly is. `truth_part` (one index into `part_names` per truth
/// point, or null) gives the truth's own parts, for own_part_rms_per_diagonal. InputError for empty sets,
/// D <= 0 or rows that do not match.
TruthErrors measure_against_truth(const Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const KdTree& truth,
                                  double diagonal, const Points* truth_of_row = nullptr,
                                  const Eigen::VectorXi* truth_part = nullptr);

/// The same with the truth as points (its KD-tree built here).
TruthErrors measure_against_truth(const Points& deformed, const Eigen::VectorXi& part,
                                  const std::vector<std::string>& part_names, const Points& truth,
                                  double diagonal, const Points* truth_of_row = nullptr,
                                  const Eigen::VectorXi* truth_part = nullptr);

/// D of a true instance given in its own frame: its bounding-box diagonal (data units).
double truth_diagonal(const Points& truth);

}  // namespace partreg::core
