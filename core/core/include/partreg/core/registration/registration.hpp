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

#include "partreg/core/progress.hpp"
#include "partreg/core/registration/refinement.hpp"
#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/core/space/category_model.hpp"

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

/// How well the result fits the observation: closest-point distances from the deformed canonical points (to a
/// cloud of more than 4 x SamplingSettings::observed_points: to its representatives at voxel_size).
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

/// A start from what is already known: the previous frame of a stream, or a guess. The holistic space's fit
/// starts there instead of searching poses; the search runs only when that fit's symmetric selection score
/// says the object moved beyond what a local fit recovers (InitialisationSettings::warm_limit).
struct WarmStart {
  /// Canonical data frame -> observed frame; a uniform scale in it is kept as the fit's starting scale.
  Eigen::Matrix4d T_observed_canonical = Eigen::Matrix4d::Identity();
  Eigen::VectorXd latent;  ///< the holistic space's latent; empty = the mean shape
  /// The pose score of the registration it comes from (RegistrationResult::pose_score; 0 = unknown): a warm
  /// fit that scores no worse than kWarmScoreGrowth times it holds whatever warm_limit says.
  double score = 0.0;
};

/// How much worse than the frame before a warm fit may score and still hold: on a held-out mug's partial view
/// the right start read 0.023 and a start half a turn off 0.029 after the same local fit (docs/speed.md).
inline constexpr double kWarmScoreGrowth = 1.15;

/// How the pose was found.
enum class StartOutcome {
  searched,   ///< the pose search (no warm start)
  warm,       ///< the warm start held: no search ran
  warm_lost   ///< the warm start's fit scored above warm_limit: the search ran as without it
};

template <>
struct EnumNames<StartOutcome> {
  static constexpr const char* what = "start outcome";
  static constexpr std::array<std::pair<StartOutcome, const char*>, 3> table{
      {{StartOutcome::searched, "searched"}, {StartOutcome::warm, "warm"}, {StartOutcome::warm_lost, "warm_lost"}}};
};

/// Where a registration's time went: wall seconds of each stage (steady clock, read once at each stage's end),
/// summing to RegistrationResult::seconds. The front ends add the stages around it (reading the observation,
/// writing what it transfers) in their own reports.
struct StageSeconds {
  double prepare = 0.0;     ///< checks, the voxel pass, strays, the farthest-point subset and its KD-tree
  double search = 0.0;      ///< the holistic pose search (or the warm start), its winner run to convergence
  double fits = 0.0;        ///< the mixture finish and the part fits (coupled: its joint problem)
  double refinement = 0.0;  ///< the fit beyond the space
  double statistics = 0.0;  ///< the fit statistics and the strays counted
  double sum() const { return prepare + search + fits + refinement + statistics; }
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
  StartOutcome start = StartOutcome::searched;
  /// The warm start's fit's symmetric selection score (normalised length; 0 without a warm start).
  double warm_score = 0.0;
  /// The holistic fit's symmetric selection score (normalised length; 0 for partwise): what a warm start from
  /// this result is held to (WarmStart::score).
  double pose_score = 0.0;
  StageSeconds stages;  ///< where `seconds` went
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

/// The same, started at `start` (WarmStart). Throws UsageError for a pose that is not a scaled rotation
/// and translation or a latent of the wrong size.
RegistrationResult register_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings, const WarmStart& start,
                                        const ProgressListener& progress = {});

/// Where a registration that follows `result` starts: its first fit's pose (the holistic space's where it
/// ran), unless the result is partwise that fit's latent, and its pose score.
WarmStart warm_start_of(const RegistrationResult& result);

/// Registers the frames of a stream in order: the first from `start` (or the search, without one), every
/// later one warm from the frame before (warm_start_of). Each result's `seconds`, `start` and `warm_score`
/// say what the frame cost and whether the warm start held.
std::vector<RegistrationResult> register_sequence(const CategoryModel& model, const std::vector<Points>& frames,
                                                  const RegistrationSettings& settings,
                                                  const std::optional<WarmStart>& start = std::nullopt);

}  // namespace partreg::core
