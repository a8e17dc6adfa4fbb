#include "partreg/core/registration/registration.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "registration/mixture_fit.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "registration/pose_search.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core {
namespace {

constexpr int kSamples = 1500;

// Synthetic mugs whose points are ground-truth samples: row i is the same semantic point on every mug.
struct SyntheticSetup {
  std::vector<SyntheticInstance> mugs;
  std::vector<TrainingInstance> training;
  SurfaceSamples held_out;
  CategoryModel model;
  std::vector<int> canonical_rows;  ///< ground-truth row of each canonical point
};

SyntheticSetup make_setup() {
  SyntheticSetup setup;
  setup.mugs = make_synthetic_category(SyntheticCategory::mug, 10, 21);
  for (std::size_t i = 0; i + 1 < setup.mugs.size(); ++i) {
    const auto gt =
        sample_correspondences(SyntheticCategory::mug, setup.mugs[i].shape_parameters, kSamples, 5);
    setup.training.push_back({setup.mugs[i].name, gt.points, gt.part, {}, {}});
  }
  setup.held_out =
      sample_correspondences(SyntheticCategory::mug, setup.mugs.back().shape_parameters, kSamples, 5);
  TrainingSettings settings;
  settings.canonical_points = 600;
  // The frame measurement below was made without the floor of points per part. With the default floor the
  // handle's 150 points improve hol+part's correspondences (0.018 -> 0.017 of the diagonal) and the frame's
  // position (2.1% -> 1.7%) but turn its rotation further off (12 -> 17.5 degrees): docs/training.md.
  settings.min_part_points = 0;
  // The coupled seam weight these figures were measured at, given rather than chosen (training_test covers
  // the choice; choosing it costs every test process registrations, minutes under the sanitizers).
  settings.seam_weight_candidates = {kDefaultSeamWeight};
  setup.model = train_category("mugs", setup.training, {"body", "handle"}, settings);
  // Canonical points are rows of the canonical instance's samples: find which.
  const auto canonical = std::find_if(setup.training.begin(), setup.training.end(), [&](const auto& t) {
    return t.name == setup.model.training.canonical;
  });
  const KdTree tree(canonical->points);
  for (Eigen::Index m = 0; m < setup.model.canonical.rows(); ++m)
    setup.canonical_rows.push_back(
        tree.nearest(setup.model.normalization.undo(setup.model.canonical.row(m)).row(0).transpose()).first);
  return setup;
}

const SyntheticSetup& setup() {
  static const SyntheticSetup instance = make_setup();
  return instance;
}

// The held-out mug moved by a known pose (0.3 rad about a tilted axis, 3% of the diagonal).
Eigen::Matrix4d known_pose() {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = testing::rotation(0.3, {1.0, 1.0, 1.0});
  T.topRightCorner<3, 1>() = Eigen::Vector3d(0.004, -0.003, 0.002);
  return T;
}

Points transform(const Points& points, const Eigen::Matrix4d& T) {
  return (points * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
}

double correspondence_error(const Points& deformed) {
  const Points truth = transform(setup().held_out.points, known_pose());
  double total = 0.0;
  for (Eigen::Index m = 0; m < deformed.rows(); ++m)
    total += (deformed.row(m) - truth.row(setup().canonical_rows[static_cast<std::size_t>(m)])).norm();
  return total / static_cast<double>(deformed.rows()) / setup().model.normalization.scale;
}

TEST(Registration, EveryVariantFindsTheCorrespondencesOfAHeldOutMug) {
  const Points observed = transform(setup().held_out.points, known_pose());
  std::map<Variant, double> errors;
  for (Variant variant : {Variant::holistic, Variant::partwise, Variant::hol_part}) {
    RegistrationSettings settings;
    settings.variant = variant;
    const RegistrationResult result = register_observation(setup().model, observed, settings);
    errors[variant] = correspondence_error(result.deformed);
    std::cerr << enum_name(variant) << ": correspondence error " << errors[variant] << " of the diagonal\n";
    // The undeformed canonical at the same pose is the reference a wrong (or no) deformation would give.
    const Points undeformed = transform(setup().model.normalization.undo(setup().model.canonical),
                                        result.fits.front().T_observed_canonical);
    const double undeformed_error = correspondence_error(undeformed);
    // Every variant lies on the held-out surface (Eq. 5 in normalised units, measured 1-2% here).
    EXPECT_LT(result.fit.mean_normalised, 0.03) << enum_name(variant);
    if (variant == Variant::holistic) continue;
    // Correspondences: the part-based variants beat the undeformed canonical at their pose. The holistic
    // space does not (measured 0.15 against 0.04): holistic CPD slides points around the rotationally
    // symmetric body during training, and its space inherits the slide. Known limitation, see the notes.
    EXPECT_LT(errors[variant], variant == Variant::hol_part ? 0.02 : 0.05) << enum_name(variant);
    EXPECT_LT(errors[variant], undeformed_error) << enum_name(variant);
  }
  // Parts help on full views. (With the default search over yaws and tilts for every part, partwise's
  // correspondences are the closest here: measured 0.005 against hol+part's 0.008.)
  EXPECT_LT(errors[Variant::hol_part], errors[Variant::holistic]);
  EXPECT_LT(errors[Variant::partwise], errors[Variant::holistic]);
}

TEST(Registration, TheDeformedMeshFollowsTheDeformedPoints) {
  const Points observed = transform(setup().held_out.points, known_pose());
  RegistrationSettings settings;
  settings.variant = Variant::hol_part;
  const RegistrationResult result = register_observation(setup().model, observed, settings);
  // Eq. 4 applied to the canonical points themselves gives the registered points where one part moves them
  // alone (farther than the seam band from the other part's points) ...
  const CategoryModel& model = setup().model;
  const Points again = deform_points(model, result, model.normalization.undo(model.canonical));
  const double diagonal = model.normalization.scale;
  const KdTree body(model.space("body").canonical), handle(model.space("handle").canonical);
  const double band = SeamBlend{}.band;
  int alone = 0;
  for (Eigen::Index i = 0; i < model.canonical.rows(); ++i) {
    const KdTree& other = model.canonical_part[i] == 0 ? handle : body;
    if (std::sqrt(other.nearest(model.canonical.row(i).transpose()).second) <= band) continue;
    ++alone;
    EXPECT_LT((again.row(i) - result.deformed.row(i)).norm(), 1e-9 * diagonal) << "canonical point " << i;
  }
  EXPECT_GT(alone, model.canonical.rows() / 4);
  // ... and within the band, where both parts' motions blend, close to them (measured 1.56% on average;
  // 0.7% with training's seam band 0: the band carries the holistic field into each part's field near the
  // other part, so across the blend's wider band the two parts' motions differ more on this small model).
  EXPECT_LT((again - result.deformed).rowwise().norm().mean(), 0.02 * diagonal);
  // The held-out surface is close to the points: they are on it, not merely near the canonical.
  const KdTree surface(observed);
  std::vector<int> index;
  Eigen::VectorXd squared;
  surface.nearest_all(again, index, squared);
  EXPECT_LT(squared.cwiseSqrt().mean(), 0.02 * diagonal);
}

TEST(Registration, TheSeamGapMeasuresHowFarThePartsCameApart) {
  const Points observed = transform(setup().held_out.points, known_pose());
  const CategoryModel& model = setup().model;
  std::map<Variant, SeamGap> gaps;
  for (Variant variant : {Variant::holistic, Variant::partwise, Variant::hol_part}) {
    RegistrationSettings settings;
    settings.variant = variant;
    gaps[variant] = seam_gap(model, register_observation(model, observed, settings));
    std::cerr << enum_name(variant) << ": seam gap max " << gaps[variant].max << ", mean "
              << gaps[variant].mean << " of the diagonal over " << gaps[variant].points
              << " boundary points\n";
  }
  EXPECT_EQ(gaps[Variant::holistic].points, 0);  // one field: no seam
  EXPECT_GT(gaps[Variant::hol_part].points, 0);
  // Moving the handle's pose by 10% of the diagonal opens every boundary point by that much, give or take
  // the gap it had (triangle inequality).
  RegistrationSettings settings;
  settings.variant = Variant::hol_part;
  RegistrationResult shifted = register_observation(model, observed, settings);
  const SeamGap before = seam_gap(model, shifted);
  for (SpaceFit& fit : shifted.fits)
    if (fit.space == "handle") fit.T_observed_canonical(0, 3) += 0.1 * model.normalization.scale;
  const SeamGap after = seam_gap(model, shifted);
  EXPECT_GE(after.mean, 0.1 - before.max - 1e-12);
  EXPECT_LE(after.max, 0.1 + before.max + 1e-12);
}

TEST(Registration, AFrameOnTheHandleLandsOnTheHeldOutHandle) {
  const Points observed = transform(setup().held_out.points, known_pose());
  RegistrationSettings settings;
  settings.variant = Variant::hol_part;
  const RegistrationResult result = register_observation(setup().model, observed, settings);
  const auto& canonical_mug = *std::find_if(setup().mugs.begin(), setup().mugs.end(), [&](const auto& m) {
    return m.name == setup().model.training.canonical;
  });
  // A grasp frame on the outer middle of the handle (u = 0.5, v = 0.25), axes from the surface tangents.
  auto frame_on = [](const std::vector<double>& shape) {
    const Eigen::Vector3d p = evaluate_surface(SyntheticCategory::mug, shape, 1, 0.5, 0.25);
    const Eigen::Vector3d du = evaluate_surface(SyntheticCategory::mug, shape, 1, 0.51, 0.25) - p;
    const Eigen::Vector3d dv = evaluate_surface(SyntheticCategory::mug, shape, 1, 0.5, 0.26) - p;
    Frame frame;
    frame.position = p;
    frame.rotation.col(0) = du.normalized();
    frame.rotation.col(2) = du.cross(dv).normalized();
    frame.rotation.col(1) = frame.rotation.col(2).cross(frame.rotation.col(0));
    return frame;
  };
  const Frame moved =
      transfer_frames(setup().model, result, {frame_on(canonical_mug.shape_parameters)}).front();
  Frame truth = frame_on(setup().mugs.back().shape_parameters);
  truth.position = transform(Points(truth.position.transpose()), known_pose()).row(0).transpose();
  truth.rotation = known_pose().topLeftCorner<3, 3>() * truth.rotation;
  const double diagonal = setup().model.normalization.scale;
  const Frame unmoved = frame_on(canonical_mug.shape_parameters);
  std::cerr << "frame transfer: position error " << (moved.position - truth.position).norm() / diagonal
            << " of the diagonal (untransferred " << (unmoved.position - truth.position).norm() / diagonal
            << "), rotation error " << testing::rotation_error_deg(moved.rotation, truth.rotation)
            << " degrees (untransferred " << testing::rotation_error_deg(unmoved.rotation, truth.rotation)
            << ")\n";
  // Measured: 2.2% of the diagonal and 12 degrees. The position is no better than leaving the frame where it
  // was (1.8%, the pose is small at the handle): the handle's space places this point about 4 mm off.
  EXPECT_LT((moved.position - truth.position).norm(), 0.06 * diagonal);
  EXPECT_LT(testing::rotation_error_deg(moved.rotation, truth.rotation), 15.0);
  // Left as it was on the canonical, the frame is turned by the pose: transfer must undo that.
  EXPECT_LT(testing::rotation_error_deg(moved.rotation, truth.rotation),
            testing::rotation_error_deg(unmoved.rotation, truth.rotation));
}

// Three points far off the held-out mug (a speck of dust, two stray returns) are counted and left out. The
// mug's own samples are spread unevenly (uniform in its parameters, not its area): the sparsest of them stand
// alone too, and those the fit misses by more than kStrayReach count as strays as well. With the limit at 0
// every point is matched.
TEST(Registration, LeavesStrayPointsOutAndCountsThem) {
  const double diagonal = setup().model.normalization.scale;
  Points observed(setup().held_out.points.rows() + 3, 3);
  observed.topRows(setup().held_out.points.rows()) = setup().held_out.points;
  observed.bottomRows(3) << 0.6, 0.0, 0.0, 0.0, -0.7, 0.1, 0.3, 0.5, -0.5;
  observed.bottomRows(3) *= diagonal;
  RegistrationSettings settings;
  settings.refinement.enabled = false;
  settings.initialisation.restarts = 1;
  // The counts below were measured at this weight. At the default 3e-5 the mug alone leaves 36 out and with
  // the three far points 37: those points move the lighter-prior fit, which then misses fewer of the mug's
  // own.
  settings.objective.prior_weight = 1e-4;
  const int mug_alone = register_observation(setup().model, setup().held_out.points, settings).fit.strays;
  const int with_three = register_observation(setup().model, observed, settings).fit.strays;
  std::cout << "strays: the mug's 1500 samples " << mug_alone << ", with three far points " << with_three << "\n";
  EXPECT_LT(mug_alone, 1500 / 20);  // 27 measured
  EXPECT_GE(with_three, mug_alone + 3);
  EXPECT_LE(with_three, mug_alone + 6);  // the fit moves a little: 31 measured
  settings.sampling.stray_limit = 0.0;
  EXPECT_EQ(register_observation(setup().model, observed, settings).fit.strays, 0);
}

// Gaussian noise of 8% of the diagonal on every coordinate (the paper's largest level): closest points
// inflate the fit (each noisy point pulls its nearest canonical point, whichever side it fell on), the
// mixture explains every point by all canonical points near it (mixture_fit.hpp).
TEST(Registration, ANoisyCloudIsFittedInAGaussianMixture) {
  const double diagonal = setup().model.normalization.scale;
  const Points truth = transform(setup().held_out.points, known_pose());
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.08 * diagonal);
  Points observed = truth;
  for (Eigen::Index i = 0; i < observed.rows(); ++i)
    for (int c = 0; c < 3; ++c) observed(i, c) += noise(random);
  const auto error = [&](const RegistrationResult& result) {
    return measure_against_truth(result.deformed, result.part, setup().model.part_names, truth, diagonal)
        .symmetric_rms_per_diagonal;
  };
  for (Variant variant : {Variant::holistic, Variant::coupled}) {
    RegistrationSettings mixture;
    mixture.variant = variant;
    mixture.refinement.enabled = false;
    RegistrationSettings closest = mixture;
    closest.objective.mixture_noise = 1e6;  // never
    const RegistrationResult in_mixture = register_observation(setup().model, observed, mixture);
    const RegistrationResult by_closest = register_observation(setup().model, observed, closest);
    const double with = error(in_mixture), without = error(by_closest);
    std::cout << enum_name(variant) << ": symmetric RMS closest points " << without << ", mixture " << with
              << "; noise read " << in_mixture.mixture.noise << ", mixture sigma " << in_mixture.mixture.sigma
              << "\n";
    // Measured at the defaults: holistic 0.025 against 0.039; coupled 0.0335 against 0.0343 (0.92x before the
    // prior grew with the noise: the joint problem's closest-point fit gained from the lighter prior more
    // than its mixture did, docs/registration.md "The prior").
    EXPECT_LT(with, (variant == Variant::holistic ? 0.92 : 0.99) * without) << enum_name(variant);
    // The result says what ran, and on what: both fits read the view as noisy (against different search
    // results: with the mixture's limit at 1e6 the search's prior does not grow either), and the mixture's
    // final sigma is the noise's own scale (0.08 per axis), not a fraction or a multiple of it.
    EXPECT_TRUE(in_mixture.mixture.applied);
    EXPECT_FALSE(by_closest.mixture.applied);
    EXPECT_GT(in_mixture.mixture.noise, mixture.objective.mixture_noise);
    EXPECT_GT(by_closest.mixture.noise, mixture.objective.mixture_noise);
    EXPECT_GT(in_mixture.mixture.sigma, 0.8 * 0.08);
    EXPECT_LT(in_mixture.mixture.sigma, 1.25 * 0.08);
    EXPECT_EQ(by_closest.mixture.sigma, 0.0);
  }
  // A clean view reads far below the limit: its fit is the closest-point fit, unchanged.
  RegistrationSettings always;
  always.refinement.enabled = false;
  RegistrationSettings never = always;
  never.objective.mixture_noise = 1e6;
  const RegistrationResult clean = register_observation(setup().model, truth, always);
  EXPECT_TRUE(clean.deformed.isApprox(register_observation(setup().model, truth, never).deformed, 0.0));
  EXPECT_FALSE(clean.mixture.applied);
  EXPECT_GT(clean.mixture.noise, 0.0);
  EXPECT_LT(clean.mixture.noise, always.objective.mixture_noise);
  EXPECT_EQ(clean.mixture.sigma, 0.0);
}

// The prior's weight in a mixture follows the noise's variance from the noise where the mixture starts
// (mixture_fit.hpp): the data term is a mean squared distance, so the weight that keeps the prior's share of
// the posterior grows as sigma^2.
TEST(Registration, ThePriorGrowsWithTheNoisesVarianceInAMixture) {
  ObjectiveSettings objective;
  objective.prior_weight = 2e-5;
  objective.mixture_noise = 0.03;
  EXPECT_EQ(detail::noisy_prior_weight(0.01, objective), 2e-5);  // below the limit: as set
  EXPECT_EQ(detail::noisy_prior_weight(0.03, objective), 2e-5);
  EXPECT_NEAR(detail::noisy_prior_weight(0.09, objective), 9 * 2e-5, 1e-12);
  objective.mixture_noise = 0.0;  // a mixture always: no noise to start from, the weight as set
  EXPECT_EQ(detail::noisy_prior_weight(0.09, objective), 2e-5);
}

// The pose search weighs the prior by the noise the observation reads against its first round's best fit
// (pose_search.hpp): the settings' weight on a clean view, grown as the noise's variance on a noisy one.
TEST(Registration, TheSearchWeighsThePriorByTheNoiseItReads) {
  const ShapeSpace& space = setup().model.holistic();
  detail::SpaceSolution mean_shape;
  mean_shape.latent = Eigen::VectorXd::Zero(space.dimensions());
  const Points clean = space.deformed(mean_shape.latent);
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0,
                                         0.08);  // per axis, normalised length: the paper's largest level
  Points noisy = clean;
  for (Eigen::Index i = 0; i < noisy.rows(); ++i)
    for (int c = 0; c < 3; ++c) noisy(i, c) += noise(random);
  const auto observation_of = [](const Points& points) {
    detail::Observation observation;
    observation.points = points;
    observation.tree = std::make_unique<KdTree>(points);
    return observation;
  };
  RegistrationSettings settings;
  EXPECT_EQ(detail::search_prior_weight(space, observation_of(clean), mean_shape, settings.objective),
            settings.objective.prior_weight);
  // The read saturates below the noise (0.04-0.06 at 0.08, point_normals.hpp): (read / 0.03)^2 is 2-4.
  const double grown =
      detail::search_prior_weight(space, observation_of(noisy), mean_shape, settings.objective);
  std::cout << "search prior at noise 0.08: " << grown / settings.objective.prior_weight
            << " x the setting\n";
  EXPECT_GT(grown, 1.5 * settings.objective.prior_weight);
  EXPECT_LT(grown, 8.0 * settings.objective.prior_weight);
  settings.objective.mixture_noise = 1e6;  // a limit no view reaches: the weight as set
  EXPECT_EQ(detail::search_prior_weight(space, observation_of(noisy), mean_shape, settings.objective),
            settings.objective.prior_weight);
}

// Partwise fits each part alone from the category frame and weighs its prior by partwise_prior_weight; the
// other variants' spaces by prior_weight. An overwhelming weight pins a space's latent at the mean.
TEST(Registration, PartwiseWeighsItsPartsPriorsByItsOwnSetting) {
  const Points observed = transform(setup().held_out.points, known_pose());
  const auto largest_part_latent = [&](const RegistrationSettings& settings) {
    const RegistrationResult result = register_observation(setup().model, observed, settings);
    double largest = 0.0;
    for (const SpaceFit& fit : result.fits) largest = std::max(largest, fit.latent.cwiseAbs().maxCoeff());
    return largest;
  };
  RegistrationSettings partwise;
  partwise.variant = Variant::partwise;
  partwise.refinement.enabled = false;
  const double free_latent = largest_part_latent(partwise);
  RegistrationSettings pinned = partwise;
  pinned.objective.partwise_prior_weight = 1e6;
  RegistrationSettings other_prior = partwise;
  other_prior.objective.prior_weight = 1e6;
  // The held-out mug is not the mean mug: free, some part latent is well away from zero.
  EXPECT_GT(free_latent, 0.01);
  EXPECT_LT(largest_part_latent(pinned), 1e-3 * free_latent);
  EXPECT_EQ(largest_part_latent(other_prior), free_latent);
}

TEST(Registration, RefusesBadObservations) {
  EXPECT_THROW(register_observation(setup().model, Points::Random(5, 3)), InputError);
  Points with_nan = setup().held_out.points;
  with_nan(0, 0) = std::nan("");
  EXPECT_THROW(register_observation(setup().model, with_nan), InputError);
  EXPECT_THROW(register_observation(setup().model, Points(setup().held_out.points * 1000.0)), InputError);
  EXPECT_THROW(parse_enum<Variant>("bogus"), UsageError);
}

}  // namespace
}  // namespace partreg::core

namespace partreg::core {
namespace {

double surface_error(const RegistrationResult& result, const Points& truth) {
  const KdTree tree(truth);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(result.deformed, index, squared);
  return squared.mean() / (setup().model.normalization.scale * setup().model.normalization.scale);
}

TEST(Registration, AFarOffPoseIsFoundFromPrincipalAxesAndRestarts) {
  Eigen::Matrix4d far = Eigen::Matrix4d::Identity();
  far.topLeftCorner<3, 3>() = testing::rotation(2.5, {1.0, 0.3, 0.0});  // 143 degrees
  const Points observed = transform(setup().held_out.points, far);
  auto rotation_error = [&](const RegistrationResult& result) {
    return testing::rotation_error_deg(result.fits.front().T_observed_canonical.topLeftCorner<3, 3>(),
                                       far.topLeftCorner<3, 3>());
  };
  const RegistrationResult naive = register_observation(setup().model, observed, {});
  RegistrationSettings aligned;
  aligned.initialisation.align_principal_axes = true;
  aligned.initialisation.restarts = 4;
  const RegistrationResult result = register_observation(setup().model, observed, aligned);
  std::cerr << "far-off pose: rotation error " << rotation_error(result)
            << " degrees with alignment and restarts, " << rotation_error(naive) << " without; Eq. 5 "
            << surface_error(result, observed) << "\n";
  EXPECT_LT(rotation_error(result), 10.0);
  EXPECT_LT(surface_error(result, observed), 1e-3);
  ASSERT_GT(rotation_error(naive), 30.0);  // starting from the category frame alone does not get there
}

TEST(Registration, AViewpointHelpsOnAPartialView) {
  // The half of the held-out mug facing -z, seen from a camera on the -z side.
  const Points full = transform(setup().held_out.points, known_pose());
  std::vector<int> rows;
  const double middle = full.col(2).mean();
  for (Eigen::Index i = 0; i < full.rows(); ++i)
    if (full(i, 2) < middle) rows.push_back(static_cast<int>(i));
  const Points partial = full(rows, Eigen::all);
  RegistrationSettings settings;
  settings.variant = Variant::hol_part;
  settings.objective.direction =
      Direction::canonical_to_observed;  // the direction that needs visibility most
  const double without = surface_error(register_observation(setup().model, partial, settings), full);
  settings.viewpoint = Eigen::Vector3d(0.0, 0.05, -0.5);
  const double with = surface_error(register_observation(setup().model, partial, settings), full);
  std::cerr << "partial view, Eq. 3 direction: Eq. 5 " << with << " with the viewpoint, " << without
            << " without\n";
  EXPECT_LT(with, without);
}

}  // namespace
}  // namespace partreg::core
