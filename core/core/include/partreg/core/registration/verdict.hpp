#pragma once
/// \file
/// Whether to trust a registration, without the truth: figures a result can compute about itself (how much
/// of the observation the deformed model explains, how unusual its shape is, whether its parts hold together,
/// whether another pose fitted about as well, how far the mesh stretched, which scale it took) and a verdict
/// `good | doubtful | failed` with its reasons, judged from them by thresholds declared once here. Lengths are
/// fractions of the model's diagonal in the observation's units. The thresholds were calibrated on the
/// evaluation, where the truth is known (docs/registration.md, "Verdict").

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

struct CategoryModel;
struct RegistrationResult;
struct RegistrationSettings;

/// How far to trust a registration: worse verdicts compare greater.
enum class Verdict { good, doubtful, failed };

template <>
struct EnumNames<Verdict> {
  static constexpr const char* what = "verdict";
  static constexpr std::array<std::pair<Verdict, const char*>, 3> table{
      {{Verdict::good, "good"}, {Verdict::doubtful, "doubtful"}, {Verdict::failed, "failed"}}};
};

/// The figures a registration reports without the truth. Lengths: fractions of the model's diagonal.
struct TrustFigures {
  /// RMS distance beyond the observation's noise (in quadrature) from the observed points to the deformed
  /// model's surface (the deformed canonical mesh, or its points with their normals for a model trained on
  /// clouds). Only observed points count, without those that stand alone (SamplingSettings::stray_limit):
  /// the side a partial view did not see costs nothing.
  double observed_rms = 0.0;
  /// Those observed points within VerdictSettings::inlier_distance of that surface, or within
  /// noise_multiple times the observation's noise where that is farther.
  double inlier_share = 0.0;
  /// The largest Mahalanobis distance of a fitted latent from its space's mean, over the spaces fitted
  /// (training standard deviations; a training instance lies near sqrt(q)).
  double latent_distance = 0.0;
  /// How far the fit beyond the shape space (the refinement) moved the fitted points, on average: the share
  /// of the shape the space could not explain (0 without the refinement).
  double refinement_movement = 0.0;
  /// The whole object's pose search: the best finalist's score over the winner's, among finalists whose
  /// shape lies elsewhere (VerdictSettings::distinct_pose); infinity when no finalist put it elsewhere.
  /// Near 1: another pose fitted as well.
  double pose_ambiguity = 0.0;
  double seam_gap_mean = 0.0, seam_gap_max = 0.0;  ///< part variants: core::seam_gap (0 for holistic)
  double mesh_stretch = 0.0;  ///< core::mesh_stretch: largest deformed / canonical edge length (0: no mesh)
  double scale = 1.0;         ///< the whole object's fitted scale (1 unless the scale was fitted)
  bool scale_at_bound = false;  ///< the fitted scale ended at ObjectiveSettings::scale_limit's bound
  /// Share of the deformed model's points the camera would have seen in front of the measured depth: in
  /// the image and nearer than the depth measured there by more than its noise allowance, or on a pixel
  /// whose ray met nothing (FreeSpace::violation_share; depth images only, unset without one).
  std::optional<double> free_space_violation;
};

/// The thresholds of the verdict, each with the measurement behind it in docs/registration.md ("Verdict").
/// A figure past its `doubtful` threshold makes the result doubtful, past its `failed` one failed.
struct VerdictSettings {
  double inlier_distance = 0.02;     ///< an observed point this close to the surface is explained (diagonal)
  double noise_multiple = 3.0;       ///< ... or this many times the observation's noise, where that is farther
  double doubtful_inlier_share = 0.85;  ///< fewer inliers than this share: doubtful
  double failed_inlier_share = 0.60;    ///< fewer than this: failed
  double doubtful_observed_rms = 0.08;  ///< observed-to-model RMS beyond the noise above this (diagonal): doubtful
  double failed_observed_rms = 0.15;    ///< above this: failed
  double doubtful_latent_distance = 6.0;  ///< Mahalanobis distance above this (standard deviations): doubtful
  double doubtful_refinement_movement = 0.04;  ///< refinement's mean movement above this (diagonal): doubtful
  double doubtful_pose_ambiguity = 1.05;  ///< a distinct runner-up scoring within this ratio: doubtful
  /// A finalist whose posed shape lies farther than this from the winner's (RMS closest-point distance,
  /// diagonal) puts the object elsewhere; closer ones (a bowl turned about its axis) are the same answer.
  double distinct_pose = 0.05;
  double doubtful_seam_gap = 0.05;  ///< largest seam gap above this (diagonal): doubtful
  double failed_seam_gap = 0.15;    ///< above this: failed
  double doubtful_mesh_stretch = 10.0;  ///< a mesh edge stretched more than this many times: doubtful
  /// More of the model's points in the camera's free space than this share: doubtful; than the failed one:
  /// failed. Correct registrations of held-out ShapeNet mugs on rendered tables read at most 4.7%; a mug
  /// turned to bring its handle where the camera saw the table or the body 7% to 42% (docs/camera.md).
  double doubtful_free_space_violation = 0.08;
  double failed_free_space_violation = 0.20;  ///< see doubtful_free_space_violation
};

/// A verdict and why.
struct Assessment {
  Verdict verdict = Verdict::good;
  std::vector<std::string> reasons;  ///< one line per figure past a threshold; empty when good
};

/// The verdict on `figures` by `settings`: the worst any figure reaches, with a reason for each figure
/// past a threshold (figure, value, threshold). UsageError for settings out of range (shares outside [0, 1],
/// negative lengths, doubtful thresholds past the failed ones).
Assessment judge(const TrustFigures& figures, const VerdictSettings& settings = {});

/// The figures of `result`, a registration of `model` to `observed` (observation units and frame) with
/// `settings` (their verdict thresholds and scale limit). register_observation fills RegistrationResult's
/// figures with it; call it again for a result changed by hand. At most `settings.sampling.observed_points`
/// observed points are measured (a farthest-point subset).
TrustFigures trust_figures(const CategoryModel& model, const Points& observed, const RegistrationResult& result,
                           const RegistrationSettings& settings);

/// Checks `settings` as judge() does.
void validate(const VerdictSettings& settings);

}  // namespace partreg::core
