#pragma once
/// \file
/// The paper's evaluation protocol (section 4) on a category: every tested instance is new to the model
/// (leave-one-out, or k folds), observed fully and from partial views cast from a tessellated sphere, clean
/// and under the four perturbation sweeps, registered with every variant and scored, beside the variants, by
/// the baselines of baselines.hpp on the same observation and truth. One row per registration or baseline,
/// so nothing is lost; tables and plots are made from the rows (report.hpp).

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/core/transfer/grasp.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/eval/views.hpp"

namespace partreg::eval {

/// How the object of a depth-scene row was cut out of its depth image (scene_eval/depth_scenes.hpp).
enum class CutKind {
  scene,  ///< as `register --depth` cuts it: plane removed, clusters, the one nearest the image centre
  hand    ///< by hand: the held-out object's own measured pixels (its true mask)
};

}  // namespace partreg::eval

template <>
struct partreg::core::EnumNames<partreg::eval::CutKind> {
  using C = partreg::eval::CutKind;
  static constexpr const char* what = "cut";
  static constexpr std::array<std::pair<C, const char*>, 2> table{{{C::scene, "scene"}, {C::hand, "hand"}}};
};

namespace partreg::eval {

/// What is observed of each tested instance.
struct Protocol {
  std::string name = "paper";
  int views = 42;       ///< partial views per instance (a tessellated sphere's vertex count; 0 = none)
  int sweep_views = 6;  ///< of those, how many also get the perturbation sweeps (spread evenly, every k-th)
  std::vector<int> levels = {0, 1, 2, 3, 4};  ///< which of the paper's five levels each paper sweep uses
  /// The sweeps run on the swept observations: the paper's four by default; yaw adds a turn about the up
  /// axis at all twelve of its levels (perturbation.hpp).
  std::vector<Perturbation> sweeps = sweep_kinds();
  bool wide_rotation = false;  ///< the rotation sweep goes on past the paper's 0.65 rad, up to pi/2
  int max_test_instances = 0;  ///< 0 = every instance; else that many, evenly spread
  int folds = 0;               ///< 0 = leave-one-out; else k folds
};

/// "paper": 42 views, sweeps on the full view and 6 partial views at all five levels, leave-one-out.
/// "quick": 12 views, sweeps on the full view and 2 partial views at levels 1, 3 and 5, 2 test instances.
/// Both run the paper's four sweeps only.
/// UsageError for another name.
Protocol protocol_by_name(const std::string& name);

/// A category to evaluate, in data units.
struct EvalInput {
  std::string category;
  std::vector<core::TrainingInstance> instances;  ///< each with its mesh where it has one
  std::vector<std::string> part_names;            ///< empty for a category without parts
  std::string fixed_canonical;  ///< the labelled instance that must be canonical (never tested); or empty
  /// Ground-truth correspondences by instance name: the same row is the same semantic point on every
  /// instance (synthetic categories). Optional.
  std::map<std::string, core::Points> correspondences;
};

/// Grasps the evaluation carries and judges (gripper.hpp): every registration row and the rigid canonical's
/// carry the same canonical grasps, and the gripper test runs them on the true mesh.
struct GraspEvaluation {
  core::Gripper gripper;
  /// Grasps on the canonical (category data frame); empty: `count` sampled on each fold's canonical mesh.
  std::vector<core::Grasp> given;
  int count = 30;  ///< grasps sampled per fold when none are given
};

class ExtraObservations;

struct EvalSettings {
  Protocol protocol;
  /// Observations made by a library above eval (the depth scenes of scene_eval/depth_scenes.hpp), run after
  /// each tested instance's own; none by default.
  std::shared_ptr<const ExtraObservations> extra;
  std::optional<GraspEvaluation> grasps;  ///< none: no grasp figures
  std::vector<core::Variant> variants = {core::Variant::holistic, core::Variant::partwise,
                                         core::Variant::hol_part};
  core::TrainingSettings training;
  core::RegistrationSettings registration;  ///< the variant is set per row
  CameraSettings camera;
  bool baselines = true;        ///< also score the baselines (baselines.hpp): one row each per observation
  bool use_viewpoint = true;    ///< partial views tell the registration where the camera was
  int full_view_points = 4000;  ///< surface samples of a mesh's full view (a different sample than the truth)
  /// Surface samples of a mesh instance's truth, drawn apart from the training sample and the full view; 0
  /// scores against the training sample. Cloud data is its own truth.
  int truth_points = core::kTruthSamples;
  int threads = 0;              ///< 0 = all cores
  int shard = 0;                ///< this run's shard, in [0, shard_count)
  int shard_count = 1;          ///< tested instances are dealt to shards round-robin
  std::uint64_t seed = 1;
};

/// How the grasps carried onto one observation fared on the true mesh (gripper.hpp's test).
struct GraspScore {
  int count = 0;  ///< grasps carried
  int held = 0;   ///< of those, held on the true mesh
  std::map<std::string, std::pair<int, int>> by_part;  ///< part -> (held, count); "" for grasps without one
  /// Mean distance from the carried contacts to the true surface (fraction of the truth's diagonal).
  double contact_per_diagonal = 0.0;
  /// Median angle of the carried closing axis to the true contact normals where the fingers touched (degrees).
  double axis_angle_degrees = 0.0;
  /// Synthetic categories (ground-truth correspondences): the carried grasps' rotation against the true
  /// motion of the same canonical region, median and 90th percentile (degrees).
  std::optional<double> frame_error_median_degrees, frame_error_p90_degrees;
};

/// A depth-scene row's cut (scene_eval/depth_scenes.hpp): which cut it registered and how well the cut
/// matched the held-out object's measured pixels (its true mask).
struct SceneCutScore {
  CutKind cut = CutKind::scene;
  /// Intersection over union of the cut's pixels with the object's: 1 for the hand cut, near 1 for a scene
  /// cut of the whole object, lower for a piece of it (or the object merged with a neighbour), 0 for another
  /// object or none.
  double overlap = 0.0;
  /// The share of the cut's pixels that are the object's: near 1 for the whole object or a piece of it, 0
  /// for another object or none.
  double precision = 0.0;
};

/// A scene cut chose the right object when at least this share of its pixels are the object's (precision):
/// a neighbour, or the object merged with a larger neighbour, falls below it.
inline constexpr double kRightObjectPrecision = 0.5;

/// One registration of the protocol, or one baseline on the same observation.
struct EvalRow {
  std::string category, instance, canonical;
  std::string variant;  ///< a core::Variant's name, or a Baseline's (baselines.hpp)
  int fold = 0;
  int view = -1;  ///< -1: the full view; else the partial view's direction index (or the depth scene's)
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< unit direction to the camera (zero for full)
  Perturbation perturbation = Perturbation::none;
  int level_index = -1;      ///< which of the paper's levels (0-4), -1 without perturbation
  double paper_level = 0.0;  ///< the level in the paper's units (m for a 0.3 m object, ratio, rad)
  double level = 0.0;        ///< the level applied: relative to the diagonal for lengths
  double diagonal = 0.0;     ///< the instance's bounding-box diagonal (data units)
  int observed_points = 0;
  core::TruthErrors errors;
  double seconds = 0.0;  ///< registration time (a baseline's: its alignment and scoring)
  /// Part variants only: how far apart neighbouring parts put the same boundary points (core::seam_gap,
  /// mean and largest, fractions of the model's diagonal); empty for holistic and the baselines.
  std::optional<core::SeamGap> seam;
  /// Registrations of a model with a canonical mesh: how far the registration stretched it
  /// (core::mesh_stretch, deformed / canonical edge length, the largest over the edges); empty for the
  /// baselines.
  std::optional<double> mesh_stretch;
  /// With EvalSettings::grasps, for the variants and the rigid canonical: the carried grasps on the truth.
  std::optional<GraspScore> grasps;
  /// Registrations: what the result said of itself without the truth (core::TrustFigures) and its verdict;
  /// empty for the baselines. The report sets them against the truth (verdict_report.hpp).
  std::optional<core::TrustFigures> figures;
  std::optional<core::Verdict> verdict;
  /// Depth-scene rows only: the cut. Such rows have `view` the scene's index and `direction` the camera's
  /// direction from the object in its own frame; the tables of full and partial views leave them out.
  std::optional<SceneCutScore> scene;
};

/// Whether a row belongs to the point-sampled views' tables: full views (`partial` false) or partial views.
/// Depth-scene rows belong to neither.
inline bool in_views(const EvalRow& row, bool partial) { return !row.scene && (row.view >= 0) == partial; }

/// One tested instance as ExtraObservations sees it (its own frame and units).
struct TestedInstance {
  std::size_t index = 0;  ///< into EvalInput::instances
  int fold = 0;
  const core::Points* truth = nullptr;          ///< what its registrations are scored against
  const Eigen::VectorXi* truth_part = nullptr;  ///< the truth's own part per point; null or empty: none
  double diagonal = 0.0;                        ///< D of the truth (truth_errors.hpp)
  std::vector<std::size_t> training;            ///< the fold's training instances (into EvalInput::instances)
  const core::Points* correspondents = nullptr;  ///< where each canonical point truly lies; null: unknown
};

/// Observations of a tested instance that a library above eval makes: eval links the core only, and the
/// depth scenes need partreg_scene (PCL, the io layer), so they plug in here rather than eval linking them.
/// run_evaluation trains each fold once and hands its model to both.
class ExtraObservations {
 public:
  virtual ~ExtraObservations() = default;
  /// How many jobs `tested` gets (0: none, e.g. an instance without a mesh).
  virtual int jobs(const EvalInput& input, const TestedInstance& tested) const = 0;
  /// Rows each job fills, for this many variants.
  virtual std::size_t rows_per_job(std::size_t variants) const = 0;
  /// Runs job `job` of `tested` on the fold's `model`, filling rows_per_job(variants.size()) rows. Called
  /// from several threads at once.
  virtual void run(const EvalInput& input, const EvalSettings& settings, const core::CategoryModel& model,
                   const TestedInstance& tested, int job, const std::vector<core::Variant>& variants,
                   EvalRow* rows) const = 0;
};

/// A seed that depends only on `seed` and `value` (a splitmix64 step): what the protocol derives every job's
/// seed with, so that rows do not depend on threads or shards.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t value);

/// Progress (core/progress.hpp): rows done, rows planned, and a line worth logging (empty when there is
/// none). The report after a fold's training has `aside` set: time-left estimates leave training out.
using EvalProgress = core::ProgressListener;

/// The level indices (into sweep_levels(kind)) the protocol runs for a sweep of `kind`.
std::vector<int> planned_levels(Perturbation kind, const Protocol& protocol);

/// Which instances are tested (shard applied), in order; InputError when the category has too few instances
/// for the protocol (fewer than 3, or fewer than 2 left to train on in a fold); UsageError for a fold count,
/// a shard or a sample count (full view, truth) out of range.
std::vector<std::string> tested_instances(const EvalInput& input, const EvalSettings& settings);

/// Runs the protocol. Variants that need parts are dropped for a category without parts (reported through
/// `progress`). Each observation gives its variants' rows, then (with `baselines`) its baselines' rows in
/// Baseline order. Rows are in a fixed order, independent of threads and shards.
std::vector<EvalRow> run_evaluation(const EvalInput& input, const EvalSettings& settings,
                                    const EvalProgress& progress = {});

}  // namespace partreg::eval
