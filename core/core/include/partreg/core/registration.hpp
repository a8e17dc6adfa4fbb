#pragma once
/// \file
/// Category-level registration (paper, section 3.2): find the latent vector x of a shape space and a rigid
/// pose that bring the deformed canonical C + G W(x) onto an observed cloud (Eq. 3), with Ceres.
/// Variants: holistic (one space), partwise (every part in its own space, independently, in parallel) and
/// hol+part (holistic first; its pose and, projected into each part's space, its deformation initialise the
/// parts) and coupled (holistic first; then one problem over the object's pose, every part's latent and a
/// small rigid offset per part, with a seam term holding neighbouring parts together). Choices and the
/// measurements behind the defaults: docs/registration.md.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/category_model.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/core/refinement.hpp"
#include "partreg/core/registration_settings.hpp"

namespace partreg::core {

/// Why a space's fit stopped.
enum class StopReason {
  converged,       ///< the cost or the parameters stopped moving (ConvergenceSettings::tolerance)
  max_iterations,  ///< ConvergenceSettings::outer_iterations refreshes ran
  no_pairs         ///< no correspondence was left to fit (nothing visible, or an empty part)
};

template <>
struct EnumNames<StopReason> {
  static constexpr const char* what = "stop reason";
  static constexpr std::array<std::pair<StopReason, const char*>, 3> table{
      {{StopReason::converged, "converged"},
       {StopReason::max_iterations, "max_iterations"},
       {StopReason::no_pairs, "no_pairs"}}};
};

/// The fit of one space.
struct SpaceFit {
  std::string space;
  Eigen::VectorXd latent;
  Eigen::Matrix4d T_observed_canonical =
      Eigen::Matrix4d::Identity();  ///< canonical data frame -> observed frame
  double scale = 1.0;
  double cost = 0.0;
  int iterations = 0;
  StopReason stop_reason = StopReason::max_iterations;
  double seconds = 0.0;
  int hypotheses = 1;            ///< starting poses the search tried
  double score = 0.0;            ///< the winner's selection score (InitialisationSettings::score)
  double runner_up_score = 0.0;  ///< the best other finalist's; infinity when there was none
  /// How far that finalist put the object: RMS closest-point distance between its posed, deformed canonical
  /// points and the winner's (fraction of the model's diagonal; 0 when there was none).
  double runner_up_shift = 0.0;
  /// Mahalanobis distance of `latent` from the space's mean (training standard deviations).
  double latent_distance = 0.0;
};

/// The state after one outer step, for stepping through a registration.
struct HistoryStep {
  std::string space;
  Eigen::VectorXd latent;
  Eigen::Matrix4d T_observed_canonical = Eigen::Matrix4d::Identity();
  double cost = 0.0;
  double seconds = 0.0;  ///< since the start of this space's registration
};

/// How well the result fits the observation: closest-point distances from the deformed canonical points.
struct FitStatistics {
  double mean = 0.0, p90 = 0.0;                        ///< data units
  double mean_normalised = 0.0, p90_normalised = 0.0;  ///< divided by the model's diagonal
  int strays = 0;  ///< observed points left out as strays (SamplingSettings::stray_limit): no part of the fit
};

/// Whether the space fits ended in a Gaussian mixture rather than closest points: the observation's noise,
/// read off the holistic space fit, against ObjectiveSettings::mixture_noise (docs/registration.md, "Noise").
struct MixtureFinish {
  bool applied = false;  ///< the holistic fit, and the coupled joint problem after it, continued in the mixture
  double noise = 0.0;    ///< the noise read, / the model's diagonal (0: not read, as for partwise)
  double sigma = 0.0;    ///< the mixture's final standard deviation per axis after the holistic fit, / the diagonal
};

struct RegistrationResult {
  Variant variant = Variant::holistic;
  std::vector<SpaceFit> fits;        ///< holistic first where it ran, then the parts
  Points deformed;                   ///< deformed canonical points in the observed frame (data units)
  Eigen::VectorXi part;              ///< part per deformed point
  std::vector<HistoryStep> history;  ///< every outer step of every space, in order
  /// The fit beyond the space (observed frame, data units; empty unless RefinementSettings::enabled):
  /// `deformed` holds the space fit moved by it, and deformation.hpp moves meshes, points and frames alike.
  RefinementField refinement;
  MixtureFinish mixture;
  FitStatistics fit;
  TrustFigures figures;   ///< what the result says of itself without the truth (verdict.hpp)
  Assessment assessment;  ///< the verdict on `figures`, with its reasons
  double seconds = 0.0;
};

/// `settings` with what it leaves to the model filled in from `model`: the up axis (CategoryModel::up) and
/// the coupled variant's seam weight (TrainingRecord::seam_weight).
RegistrationSettings with_model_defaults(RegistrationSettings settings, const CategoryModel& model);

/// Registers `model` to `observed` (data units, any frame near the category's). Throws InputError for fewer
/// than 10 finite points or an observation wildly out of scale with the model; UsageError for a part-based
/// variant on a model without parts or settings out of range (validate()). Parallel parts use the calling
/// thread's budget (parallel.hpp). `progress` hears of each space fitted (holistic, then the parts as they
/// finish): 1, P or 1 + P steps for holistic, partwise and hol+part.
RegistrationResult register_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings = {},
                                        const ProgressListener& progress = {});

}  // namespace partreg::core
