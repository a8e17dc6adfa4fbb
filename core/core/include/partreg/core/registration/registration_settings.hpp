#pragma once
/// \file
/// What a registration is asked to do, grouped by concern: the objective it minimises, where it starts, when
/// it stops and how much of the observation it looks at. Every front end (the `register`, `eval` and
/// `figure compare` commands, the app's `register` verb, the Python module) sets these through one table of
/// named options (registration_options.hpp). Lengths are in normalised units: the model's canonical diagonal
/// is 1. Choices and the measurements behind the defaults: docs/registration.md.

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "partreg/core/geometry/free_space.hpp"
#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/registration/verdict.hpp"

namespace partreg::core {

/// The coupled variant's seam weight where neither the request nor the model names one: kettles' full views
/// measured best at 10 (docs/registration.md).
inline constexpr double kDefaultSeamWeight = 10.0;

/// Which shape spaces are fitted, and how (paper, section 3.2).
enum class Variant {
  holistic,  ///< one space for the whole object
  partwise,  ///< every part in its own space and pose, independently
  hol_part,  ///< holistic first; its pose and deformation initialise the parts
  /// holistic first; then one problem over the object's pose, every part's latent and a small rigid offset
  /// per part, with a seam term that holds neighbouring parts together (docs/registration.md)
  coupled
};

/// Which closest points the objective sums over.
enum class Direction {
  canonical_to_observed,  ///< the paper's Eq. 3: every canonical point to its closest observed point
  observed_to_canonical,  ///< every observed point to its closest deformed canonical point
  symmetric               ///< both, each normalised by its point count
};

/// The robust loss on each closest-point distance.
enum class Loss { squared, huber, cauchy, trimmed };

/// How the pose search picks among its finished hypotheses (docs/registration.md has the measurements).
enum class SelectionScore {
  cost,       ///< the fit's own final cost (its direction and loss)
  canonical,  ///< mean robust distance from the visible posed canonical points to the observation
  observed,   ///< mean robust distance from the observation to the visible posed canonical points
  symmetric   ///< the mean of both
};

/// The objective: what a pose and latent are scored by.
struct ObjectiveSettings {
  /// Both directions measured best on full and partial views of mugs, bowls and drills, with and without the
  /// refinement (docs/registration.md).
  Direction direction = Direction::symmetric;
  Loss loss = Loss::huber;
  double loss_scale = 0.02;    ///< Huber/Cauchy scale (normalised length)
  double trim_fraction = 0.1;  ///< trimmed loss: share of the worst correspondences dropped each step, [0, 1)
  /// Weight of the Gaussian prior sum_k x_k^2 / var_k against the data term (a mean squared distance). In a
  /// fit to a noisy view's mixture it grows as (sigma / mixture_noise)^2 (noisy_prior_weight; measured:
  /// docs/registration.md, "The prior").
  double prior_weight = 3e-5;
  /// The partwise variant's prior weight: each part is fitted alone from the category frame, matched by its
  /// own points only, and the prior is all that keeps its shape plausible (at 1e-5 kettles' partial views
  /// read 3.98% of the diagonal against 3.10% at 1e-4: docs/registration.md, "The prior").
  double partwise_prior_weight = 1e-4;
  bool estimate_scale = false;  ///< also fit a uniform scale, within scale_limit
  /// A fitted scale stays within [1 / scale_limit, scale_limit] of the model's size (the canonical at the
  /// category's real size with `train --size`); one that ends at a bound says so in the verdict's reasons.
  /// 3 covers the 0.5x to 2x a category's real objects span, with room for the shape space's own spread.
  double scale_limit = 3.0;
  /// An observation whose noise reads above this (normalised length, read off the holistic fit as the
  /// refinement reads it) ends its space fits with EM over a Gaussian mixture instead of closest points,
  /// which a noisy cloud biases (docs/registration.md, "Noise"). 0.03 lies above every clean view of the six
  /// real categories (at most 0.027, a drill's scan) and below the paper's third noise level (about 0.035).
  double mixture_noise = 0.03;
  /// Coupled variant: weight of the prior that keeps each part's rigid offset from the object's pose near
  /// zero, per squared normalised length the offset moves the part by (its translation, and its rotation
  /// in radians times the part's RMS radius), against the data term's mean squared distance.
  double offset_weight = 1.0;
  /// Coupled variant: weight of the seam term, the mean squared distance between the two parts' positions
  /// of the canonical points near a part boundary (normalised length squared), against the data term. Unset:
  /// the model's own, which training chose for its category (TrainingRecord::seam_weight), or
  /// kDefaultSeamWeight for a model that has none.
  std::optional<double> seam_weight;
  /// Coupled variant: canonical points of a part within this of another part's are seam points (normalised
  /// length; 0.03 is about one canonical spacing at M = 1000, the radius seam_gap measures at).
  double seam_radius = 0.03;
};

/// Where the search starts and how it prunes: every combination of a base rotation (the category frame, and
/// with align_principal_axes the 4 principal-axis alignments; or with any_rotation the 24 rotations of the
/// cube), a tilt of the up axis (none, or 8 up to max_tilt) and a yaw about the up axis (`restarts` evenly
/// spaced) is a hypothesis. All get screening_iterations outer steps; the better half by `score` goes on with
/// twice as many, until `finalists` remain, which run to convergence; the lowest score wins.
struct InitialisationSettings {
  int restarts = 12;  ///< yaws about the up axis, evenly spaced (measured: docs/registration.md)
  bool align_principal_axes = false;  ///< also start from the 4 rotations aligning principal axes
  /// Tilts of the up axis tried, up to this (radians, [0, pi]; 0 = none). 1 rad keeps the rotation sweep
  /// flat up to the paper's 0.65 rad turns about every axis, which tilt the up axis by up to 0.9 rad.
  double max_tilt = 1.0;
  bool any_rotation = false;  ///< an unknown up axis: base rotations spread over SO(3)
  /// The category's up axis (canonical frame, any length > 0); unset: the model's own (CategoryModel::up,
  /// given to `partreg train --up`).
  std::optional<Eigen::Vector3d> up;
  int screening_iterations = 3;  ///< outer steps every hypothesis gets before the first cut
  /// The screening rounds match farthest-point subsets of this many canonical and observed points; the
  /// finalists then run on all of them (0 = screen on all). Measured: docs/registration.md.
  int screening_points = 300;
  /// Before the screening every start gets the cheapest look (a few rigid closest-point steps of its shape on
  /// the screening's points, scored both ways); starts that land on one pose are merged and only this many
  /// of the best are screened (0 = every start). Measured: docs/speed.md.
  int survivors = 0;
  int finalists = 2;                            ///< hypotheses run to convergence
  SelectionScore score = SelectionScore::cost;  ///< what picks the winner
  /// A warm start (registration.hpp's WarmStart) holds while its fit's symmetric selection score stays
  /// below this (normalised length) or within kWarmScoreGrowth of the score of the result it came from;
  /// else the object moved beyond what the local fit recovers and the search runs. A held-out mug's partial
  /// view read 0.023 at the right pose, 0.029 half a turn off (docs/speed.md).
  double warm_limit = 0.02;
  /// With free space (RegistrationSettings::free_space) a hypothesis's score is multiplied by 1 + this times
  /// the share of its posed model points the camera would have seen in front of the measured depth
  /// (FreeSpace::violation_share; 0 = free space does not score). A multiple rather than a sum: the score is
  /// a length or a cost by `score`, the share a number in [0, 1]. On a rendered synthetic mug whose handle
  /// the camera could not see, 2 still kept a pose with 4% of its points in free space and the handle 0.11 m
  /// off; 10 hid it (0.5%). On 24 views of two held-out ShapeNet mugs, all registered correctly without it,
  /// 10 left 19 unchanged, moved 3 by at most 0.0004 of the diagonal and made 2 worse (0.017 to 0.030 and
  /// 0.027): a correct pose's few per cent in free space can tip nearly equal finalists (docs/camera.md). Off
  /// by default: on real mugs it helped no view and hurt two, and a model of the wrong size is pushed off.
  double free_space_weight = 0.0;
};

/// When a space's fit stops.
struct ConvergenceSettings {
  int outer_iterations = 25;  ///< correspondence refreshes at most
  int inner_iterations = 4;   ///< Ceres iterations per refresh
  /// Stop when the cost changes by less than this, relatively, or nothing moves. 1e-4 rather than 1e-5: the
  /// last steps before 1e-5 creep (a few pairs change each step) without moving the fit
  /// (docs/registration.md).
  double tolerance = 1e-4;
};

/// How much of the observation each step matches.
struct SamplingSettings {
  int observed_points = 2000;  ///< farthest-point subset of the observation (measured: docs/registration.md)
  /// Voxel pre-pass before the farthest-point subset (normalised length; 0 = none): a 1M-point depth image
  /// shrinks to one point per voxel in O(N) first. 0.004 is about a fifth of the spacing of 2000 points on
  /// a unit object, so it changes the subset little (docs/benchmarks.md, registration subsampling).
  double voxel_size = 0.004;
  /// An observed point whose second nearest neighbour is farther than this many times the median such
  /// distance over the observation stands alone: it is kept out of the farthest-point subset and matched only
  /// while the fit passes within 0.03 of it (0 = every point always). Farthest-point sampling favoured such
  /// points, and each pulled the fit at every step: at the paper's 20% outliers the deformed canonical was
  /// worse than the rigid one (docs/registration.md, "Strays").
  double stray_limit = 3.0;
};

/// A fit beyond the shape space (refinement.hpp): after the space fit, a non-rigid CPD whose field lives on
/// the fitted canonical points, started at the fit and pulled back to it where nothing was observed. A
/// canonical point is observed when it faces the viewpoint (if one is known) and an observed point lies
/// within `gate` of it. Measurements behind the defaults: docs/registration.md.
struct RefinementSettings {
  /// Off: the result is the space fit. On by default: it measures better on full and partial views of mugs,
  /// bowls and drills (docs/registration.md).
  bool enabled = true;
  double beta = 0.05;   ///< width of the refinement's Gaussian kernel (normalised length): the finest detail
  double lambda = 1.0;  ///< motion coherence: weight of the field's smoothness against the data (unitless)
  /// Pull of an unobserved canonical point back to the space's prediction, in units of an observed point's
  /// mean posterior mass (so 1 holds it as firmly as data holds an observed point).
  double anchor = 1.0;
  /// Farther than this from every observed point is unobserved (normalised length). Twice the kernel width:
  /// a point the space fit left 5-10% off a surface the sensor saw is the worst error there, and the
  /// refinement is there to reach it (docs/registration.md).
  double gate = 0.1;
  /// CPD's w in [0, 1): the least share of the observation explained by uniform noise; the share the stray
  /// screen left out raises it (RefinementField::outlier_weight).
  double outlier_weight = 1e-5;
  int iterations = 20;          ///< EM iterations at most
  /// The kernel is at least this many times the observation's noise wide (RefinementField::noise; 0 = always
  /// beta): detail finer than the noise cannot be told from it. Measured: docs/registration.md.
  double noise_width = 4.0;
};

/// One registration request.
struct RegistrationSettings {
  Variant variant = Variant::holistic;
  ObjectiveSettings objective;
  InitialisationSettings initialisation;
  ConvergenceSettings convergence;
  SamplingSettings sampling;
  RefinementSettings refinement;
  VerdictSettings verdict;  ///< the thresholds the result's verdict is judged by (verdict.hpp)
  /// Camera position (observed frame, data units): only canonical points facing it are matched. Unknown when
  /// empty.
  std::optional<Eigen::Vector3d> viewpoint;
  /// The depth image the observation came from, where it came from one: the space the camera saw empty,
  /// scoring the pose search (InitialisationSettings::free_space_weight) and the verdict
  /// (TrustFigures::free_space_violation). Its T_camera_observed maps the observation's frame into the
  /// camera's. Shared, not copied: settings are copied per hypothesis.
  std::shared_ptr<const FreeSpace> free_space;
};

template <>
struct EnumNames<Variant> {
  static constexpr const char* what = "variant";
  static constexpr std::array<std::pair<Variant, const char*>, 4> table{{{Variant::holistic, "holistic"},
                                                                         {Variant::partwise, "partwise"},
                                                                         {Variant::hol_part, "hol+part"},
                                                                         {Variant::coupled, "coupled"}}};
};

template <>
struct EnumNames<Direction> {
  static constexpr const char* what = "direction";
  static constexpr std::array<std::pair<Direction, const char*>, 3> table{
      {{Direction::canonical_to_observed, "canonical"},
       {Direction::observed_to_canonical, "observed"},
       {Direction::symmetric, "symmetric"}}};
};

template <>
struct EnumNames<SelectionScore> {
  static constexpr const char* what = "selection score";
  static constexpr std::array<std::pair<SelectionScore, const char*>, 4> table{
      {{SelectionScore::cost, "cost"},
       {SelectionScore::canonical, "canonical"},
       {SelectionScore::observed, "observed"},
       {SelectionScore::symmetric, "symmetric"}}};
};

template <>
struct EnumNames<Loss> {
  static constexpr const char* what = "loss";
  static constexpr std::array<std::pair<Loss, const char*>, 4> table{{{Loss::squared, "squared"},
                                                                      {Loss::huber, "huber"},
                                                                      {Loss::cauchy, "cauchy"},
                                                                      {Loss::trimmed, "trimmed"}}};
};

}  // namespace partreg::core
