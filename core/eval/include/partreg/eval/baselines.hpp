#pragma once
/// \file
/// What partreg's registration is measured against: four baselines scored on the same observation, against
/// the same truth, as the registration's variants (protocol.hpp gives each its own row).
///
/// - oracle template: every training instance of the fold (never the tested one) rigidly aligned to the
///   observation; the one closest to the truth (lowest symmetric RMS) is kept. It uses the truth to choose,
///   so it is the best any rigid template of the training set could do: a strong baseline.
/// - rigid canonical: the canonical instance alone, rigidly aligned the same way.
/// - mean shape: the undeformed mean shape (latent 0 of the holistic space) at partreg's own holistic pose,
///   so that it shows what the latent deformation adds once the pose is found.
/// - true shape: the tested instance itself at its true pose, as M points (farthest-point sampled from a
/// sample
///   of its surface independent of the truth's): what a perfect registration of the canonical's M points
///   would score. Not a rival but the floor under every figure: the spacing of M points on the surface
///   bounds the reverse half (truth to nearest fitted point) and the truth's own spacing the forward half.
///
/// Rigid alignment is a trimmed point-to-point ICP (align_rigidly) from the registration's own starts: the
/// category frame turned about its up axis `restarts` times, centroids aligned; the start with the lowest
/// fitting RMS is kept (the fit, not the truth, chooses among starts; only the oracle's choice of template
/// sees the truth).

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/core/training/training.hpp"

namespace partreg::eval {

/// The evaluation's baselines (not registration variants: core::Variant is the registration's own).
enum class Baseline { oracle_template, rigid_canonical, mean_shape, true_shape };

}  // namespace partreg::eval

namespace partreg::core {
template <>
struct EnumNames<eval::Baseline> {
  static constexpr const char* what = "baseline";
  static constexpr std::array<std::pair<eval::Baseline, const char*>, 4> table{
      {{eval::Baseline::oracle_template, "oracle-template"},
       {eval::Baseline::rigid_canonical, "rigid-canonical"},
       {eval::Baseline::mean_shape, "mean-shape"},
       {eval::Baseline::true_shape, "true-shape"}}};
};
}  // namespace partreg::core

namespace partreg::eval {

/// Trimmed point-to-point ICP: each observed point is paired with its closest template point (so a partial
/// view is matched onto the part of the template it sees), the farthest pairs are dropped as outliers, and
/// the rigid motion of the rest is solved in closed form (Umeyama, no scale).
struct IcpSettings {
  int max_points = 500;        ///< observed points used (every k-th of the observation); 6 dof need few
  int max_iterations = 50;     ///< cap on the pair-and-solve steps per start
  double tolerance = 1e-6;     ///< stop when the trimmed RMS changes by less than this, relatively
  double kept_fraction = 0.9;  ///< share of the pairs kept each step (the closest ones), in (0, 1]
};

/// A rigid alignment of a template onto an observation.
struct RigidAlignment {
  Eigen::Matrix4d T_observed_template = Eigen::Matrix4d::Identity();  ///< template frame -> observed frame
  double rms = 0.0;  ///< trimmed RMS distance of the observed points to the template at the end (data units)
  int iterations = 0;  ///< steps of the start that was kept
};

/// The starting rotations R_observed_template of the registration's pose search: `restarts` (>= 1) turns
/// about `up` (the category's up axis, any length > 0), evenly spaced over 360 degrees, the first the
/// identity.
std::vector<Eigen::Matrix3d> start_rotations(int restarts, const Eigen::Vector3d& up);

/// Aligns the template (points of `template_tree`, data units) to `observed` (data units, observed frame)
/// from each start rotation with the centroids aligned, and keeps the start with the lowest final RMS.
/// InputError for fewer than 3 observed points or no start.
RigidAlignment align_rigidly(const core::KdTree& template_tree, const core::Points& observed,
                             const std::vector<Eigen::Matrix3d>& starts, const IcpSettings& settings = {});

/// A rigid shape the baselines may align: a training instance sampled like the canonical.
struct Template {
  std::string name;
  core::KdTree tree;  ///< its points (category data frame, data units)
  bool is_canonical = false;
};

/// The templates of one fold: the canonical first (the model's own M canonical points, undeformed, in the
/// data frame), then every other training instance of `training` named in the model's training record,
/// sampled to M points by farthest-point sampling as the canonical was (so every template has one density).
std::vector<Template> fold_templates(const core::CategoryModel& model,
                                     const std::vector<core::TrainingInstance>& training);

/// The templates a model alone can give (when its training instances are not at hand, as in `register
/// --truth`): the canonical first, then each training instance as training fitted it, canonical + G(C, C) W_i
/// (M points, data frame). The fits stand in for the instances: their distance to them is training's fit
/// error (`partreg train` reports it), so the oracle over them is a little weaker than over the instances.
std::vector<Template> model_templates(const core::CategoryModel& model);

/// One baseline's score on one observation.
struct BaselineScore {
  Baseline baseline = Baseline::oracle_template;
  core::TruthErrors errors;
  std::string shape;     ///< the template used (the oracle's choice), or "mean" for the mean shape
  double seconds = 0.0;  ///< alignment and scoring time
  /// The rigid canonical's alignment (canonical data frame -> observed frame); identity for the others.
  Eigen::Matrix4d T_observed_shape = Eigen::Matrix4d::Identity();
};

/// What the baselines see of one observation and its truth.
struct BaselineObservation {
  const core::Points* observed = nullptr;  ///< the observed points (data units, observed frame)
  const core::KdTree* truth = nullptr;     ///< the whole true instance, moved into the observed frame
  double diagonal = 0.0;                   ///< D of the true instance (truth_errors.hpp)
  /// Where each canonical point truly lies (rows as the canonical), or null: only the shapes with the
  /// canonical's rows (rigid canonical, mean shape) get a correspondence error.
  const core::Points* truth_of_canonical_row = nullptr;
  /// partreg's holistic pose (SpaceFit::T_observed_canonical): canonical data frame -> observed frame.
  Eigen::Matrix4d T_observed_canonical = Eigen::Matrix4d::Identity();
  /// The tested instance as M points at its true pose (observed frame, data units; true_shape_points), or
  /// null: the true shape is then not scored.
  const core::Points* true_shape = nullptr;
};

/// The undeformed mean shape (latent 0 of the holistic space) in the canonical data frame (M x 3).
core::Points mean_shape(const core::CategoryModel& model);

/// The true shape's points: `surface` (a sample of the tested instance's surface other than the truth's, data
/// frame) farthest-point sampled to the model's M canonical points.
core::Points true_shape_points(const core::CategoryModel& model, const core::Points& surface);

/// Scores the baselines, in Baseline order; the true shape only when the observation carries it.
/// `templates` from fold_templates; `starts` from start_rotations. InputError for no templates or an empty
/// observation.
std::vector<BaselineScore> score_baselines(const core::CategoryModel& model,
                                           const std::vector<Template>& templates,
                                           const BaselineObservation& observation,
                                           const std::vector<Eigen::Matrix3d>& starts,
                                           const IcpSettings& icp = {});

}  // namespace partreg::eval
