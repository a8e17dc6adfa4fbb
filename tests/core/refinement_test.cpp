#include "partreg/core/registration/refinement.hpp"

#include <gtest/gtest.h>

#include <random>

#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core {
namespace {

// Synthetic mugs: a model trained on eight, the ninth held out. The held-out mug carries a bump the
// training mugs do not have (a dent of sensor-visible detail on the body), so the space cannot reach it.
struct Setup {
  CategoryModel model;
  Points truth;  ///< the held-out mug with its bump (data units)
  double diagonal = 0.0;
};

// A smooth bump of `height` along the outward radial direction, centred at the body point nearest `centre`.
Points with_bump(const Points& points, const Eigen::Vector3d& centre, double radius, double height) {
  const Eigen::RowVector3d axis_centre = points.colwise().mean();
  Points bumped = points;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double d2 = (points.row(i) - centre.transpose()).squaredNorm();
    Eigen::RowVector3d radial = points.row(i) - axis_centre;
    radial.y() = 0.0;  // the mug's axis is y
    if (radial.norm() < 1e-12) continue;
    bumped.row(i) += height * std::exp(-d2 / (2.0 * radius * radius)) * radial.normalized();
  }
  return bumped;
}

Setup make_setup() {
  const std::vector<SyntheticInstance> mugs = make_synthetic_category(SyntheticCategory::mug, 9, 31);
  std::vector<TrainingInstance> training;
  for (std::size_t i = 0; i + 1 < mugs.size(); ++i) {
    const auto samples = sample_correspondences(SyntheticCategory::mug, mugs[i].shape_parameters, 1500, 5);
    training.push_back({mugs[i].name, samples.points, samples.part, {}, {}});
  }
  TrainingSettings settings;
  settings.canonical_points = 600;
  // The coupled seam weight these figures were measured at, given rather than chosen (training_test covers
  // the choice; choosing it costs every test process registrations, minutes under the sanitizers).
  settings.seam_weight_candidates = {kDefaultSeamWeight};
  Setup setup;
  setup.model = train_category("mugs", training, {"body", "handle"}, settings);
  const Points held_out =
      sample_correspondences(SyntheticCategory::mug, mugs.back().shape_parameters, 3000, 7).points;
  setup.diagonal = truth_diagonal(held_out);
  // The bump faces +x (the camera's side below), a fifth of the diagonal wide and 4% high.
  Eigen::Index front = 0;
  held_out.col(0).maxCoeff(&front);
  setup.truth =
      with_bump(held_out, held_out.row(front).transpose(), 0.1 * setup.diagonal, 0.04 * setup.diagonal);
  return setup;
}

const Setup& setup() {
  static const Setup instance = make_setup();
  return instance;
}

double symmetric_rms(const RegistrationResult& result) {
  return measure_against_truth(result.deformed, result.part, setup().model.part_names, setup().truth,
                               setup().diagonal)
      .symmetric_rms_per_diagonal;
}

RegistrationSettings refined(bool on) {
  RegistrationSettings settings;
  settings.refinement.enabled = on;
  return settings;
}

// The half of the truth facing +x, and a camera far along +x.
struct PartialView {
  Points points;
  Eigen::Vector3d viewpoint;
};

PartialView front_half() {
  const Points& truth = setup().truth;
  const double middle = truth.col(0).mean();
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < truth.rows(); ++i)
    if (truth(i, 0) > middle) rows.push_back(static_cast<int>(i));
  PartialView view;
  view.points = Points(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    view.points.row(static_cast<Eigen::Index>(i)) = truth.row(rows[i]);
  view.viewpoint = truth.colwise().mean().transpose() + Eigen::Vector3d(2.0 * setup().diagonal, 0.0, 0.0);
  return view;
}

// The largest distance (fraction of the diagonal) between two results' points on the far side: more than
// `margin` (fraction of the diagonal) behind the middle of the view.
double far_side_change(const Points& a, const Points& b, double margin) {
  const double middle = setup().truth.col(0).mean() - margin * setup().diagonal;
  double largest = 0.0;
  for (Eigen::Index m = 0; m < a.rows(); ++m)
    if (a(m, 0) < middle) largest = std::max(largest, (a.row(m) - b.row(m)).norm());
  return largest / setup().diagonal;
}

TEST(Refinement, LowersTheErrorOfAFullView) {
  const RegistrationResult space = register_observation(setup().model, setup().truth, refined(false));
  const RegistrationResult fine = register_observation(setup().model, setup().truth, refined(true));
  const double before = symmetric_rms(space), after = symmetric_rms(fine);
  std::cout << "symmetric RMS per diagonal: space fit " << before << ", refined " << after << "\n";
  EXPECT_LT(after, 0.8 * before);
  EXPECT_FALSE(fine.refinement.empty());
  // A full view without a viewpoint: all but the few the space put beyond the gate count as seen.
  EXPECT_GT(fine.refinement.observed, fine.refinement.points * 95 / 100);
  EXPECT_TRUE(space.refinement.empty());
  // The movement it reports is how far it moved the space fit's points (the same space fit in both runs),
  // as a share of the model's diagonal.
  const Eigen::VectorXd moved =
      (fine.deformed - space.deformed).rowwise().norm() / setup().model.normalization.scale;
  EXPECT_NEAR(fine.refinement.mean_movement, moved.mean(), 1e-6 * moved.mean());
  EXPECT_NEAR(fine.refinement.max_movement, moved.maxCoeff(), 1e-6 * moved.maxCoeff());
  EXPECT_GT(fine.refinement.mean_movement, 0.001);
}

TEST(Refinement, KeepsTheUnseenSideOfAPartialViewAtTheSpacesPrediction) {
  const PartialView view = front_half();
  RegistrationSettings space_settings = refined(false), fine_settings = refined(true);
  space_settings.viewpoint = fine_settings.viewpoint = view.viewpoint;
  const RegistrationResult space = register_observation(setup().model, view.points, space_settings);
  const RegistrationResult fine = register_observation(setup().model, view.points, fine_settings);
  // Stated: points more than one gate and one kernel width (15% of the diagonal) behind the view's middle
  // stay within 1.5% of the diagonal of where the space put them. A fitted point up to one gate behind the
  // middle may still be within the gate of the observation, so it counts as seen; the field fades over a
  // kernel width beyond. Measured 0.53% (1.6% at 10% behind; with the earlier gate of 0.05, 0.55-0.90% at
  // 10%); the space fit's own error is 2.5%, plain CPD's change below 52%.
  const RefinementSettings defaults;
  const double margin = defaults.gate + defaults.beta;
  const double change = far_side_change(space.deformed, fine.deformed, margin);
  std::cout << "far side moved at most " << change << " of the diagonal\n";
  EXPECT_LT(change, 0.015);
  EXPECT_LT(fine.refinement.observed, fine.refinement.points * 3 / 4);
  // The refinement did move the seen side: the front reaches the bump.
  EXPECT_LT(symmetric_rms(fine), symmetric_rms(space));
  // Plain non-rigid CPD of the same width (every point in the E-step, no anchor, the classic start) drags
  // the far side: the tolerance above would catch a refinement that ignored what was seen.
  NonrigidCpdSettings plain;
  plain.beta = 0.05;
  plain.lambda = 1.0;
  plain.normalize = false;
  const double scale = setup().model.normalization.scale;
  const Points moved = register_nonrigid(space.deformed / scale, view.points / scale, plain).moved * scale;
  const double plain_change = far_side_change(space.deformed, moved, margin);
  std::cout << "plain CPD moved the far side by " << plain_change << " of the diagonal\n";
  EXPECT_GT(plain_change, 0.02);
}

// The full view with a fifth as many again strays, uniform in a box twice the truth's size (the paper's
// largest outlier level, as eval's sweep adds them).
Points with_strays(const Points& points, double share, unsigned seed) {
  const Eigen::RowVector3d low = points.colwise().minCoeff(), high = points.colwise().maxCoeff();
  const Eigen::RowVector3d centre = 0.5 * (low + high), half = high - low;  // twice the box's half size
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto count = static_cast<Eigen::Index>(share * static_cast<double>(points.rows()));
  Points out(points.rows() + count, 3);
  out.topRows(points.rows()) = points;
  for (Eigen::Index i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) out(points.rows() + i, c) = centre[c] + half[c] * unit(random);
  return out;
}

TEST(Refinement, StraysFarFromTheFitDoNotPullIt) {
  const Points observed = with_strays(setup().truth, 0.2, 3);
  // Every stray reaches the fit (registration would leave them out before it samples the observation): this
  // is the refinement's own rule at work.
  RegistrationSettings space_fit = refined(false), refinement = refined(true);
  space_fit.sampling.stray_limit = refinement.sampling.stray_limit = 0.0;
  const RegistrationResult space = register_observation(setup().model, observed, space_fit);
  const RegistrationResult fine = register_observation(setup().model, observed, refinement);
  const double before = symmetric_rms(space), after = symmetric_rms(fine);
  std::cout << "with 20% strays, symmetric RMS per diagonal: space fit " << before << ", refined " << after
            << "\n";
  // Only observed points within the gate of the fit take part, so the strays are left out and the refinement
  // still reaches the bump. Matching every observed point, as plain CPD does, pulls the fit towards the
  // strays: measured worse than the space fit.
  EXPECT_LT(after, 0.9 * before);
}

TEST(Refinement, WidensItsKernelWithTheObservationsNoise) {
  // Gaussian noise of 5% of the diagonal on every coordinate: the paper's noise sweep goes to 8%.
  const double sigma = 0.05;
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, sigma * setup().diagonal);
  Points observed = setup().truth;
  for (Eigen::Index i = 0; i < observed.rows(); ++i)
    for (int c = 0; c < 3; ++c) observed(i, c) += noise(random);
  // The refinement is judged against the closest-point space fit it was measured on: at this noise the
  // space fit would otherwise end in the Gaussian mixture (mixture_fit.hpp), which on this bumped mug is
  // worse (3.03% against 2.64%, docs/registration.md "Noise").
  const auto closest = [](bool on) {
    RegistrationSettings settings = refined(on);
    settings.objective.mixture_noise = 1e6;
    return settings;
  };
  const RegistrationResult space = register_observation(setup().model, observed, closest(false));
  const RegistrationResult fine = register_observation(setup().model, observed, closest(true));
  RegistrationSettings fixed = closest(true);
  fixed.refinement.noise_width = 0.0;  // the kernel stays at beta
  const RegistrationResult chased = register_observation(setup().model, observed, fixed);
  std::cout << "noisy cloud: noise " << fine.refinement.noise << " (sigma " << sigma << "), width "
            << fine.refinement.width << "; symmetric RMS space fit " << symmetric_rms(space) << ", refined "
            << symmetric_rms(fine) << ", refined at beta " << symmetric_rms(chased) << "\n";
  // The noise is read off the fit along the normal: about sigma, not the 3D spread (sqrt(3) sigma).
  EXPECT_GT(fine.refinement.noise, 0.5 * sigma);  // measured 0.62 sigma: points pushed past a thin wall join its other side
  EXPECT_LT(fine.refinement.noise, 1.3 * sigma);
  EXPECT_DOUBLE_EQ(fine.refinement.width, RefinementSettings{}.noise_width * fine.refinement.noise);
  // At beta the field follows the noise and is worse than the space fit; widened it still improves on it.
  EXPECT_GT(symmetric_rms(chased), 1.1 * symmetric_rms(space));
  EXPECT_LT(symmetric_rms(fine), symmetric_rms(space));
  // A clean full view reads as far quieter and is refined at beta.
  const RegistrationResult clean = register_observation(setup().model, setup().truth, refined(true));
  std::cout << "clean: noise " << clean.refinement.noise << ", width " << clean.refinement.width << "\n";
  EXPECT_LT(clean.refinement.noise, 0.2 * sigma);
  EXPECT_DOUBLE_EQ(clean.refinement.width, RefinementSettings{}.beta);
}

TEST(Refinement, MeshesPointsAndFramesFollowIt) {
  const RegistrationResult fine = register_observation(setup().model, setup().truth, refined(true));
  const Points canonical = setup().model.normalization.undo(setup().model.canonical);
  const Points moved = deform_points(setup().model, fine, canonical);
  EXPECT_LT((moved - fine.deformed).cwiseAbs().maxCoeff(), 1e-9 * setup().diagonal);
  // The refinement moved the points: without it they would not match.
  RegistrationResult without = fine;
  without.refinement = RefinementField();
  EXPECT_GT((deform_points(setup().model, without, canonical) - fine.deformed).rowwise().norm().maxCoeff(),
            0.01 * setup().diagonal);
  // A frame is a material point: it moves with the field's normal part only, never further than the surface.
  const std::vector<Frame> frames = transfer_frames(setup().model, fine, {Frame{"grasp", canonical.row(0)}});
  const Points material = deform_points(setup().model, fine, canonical, {}, Follow::material);
  EXPECT_LT((frames[0].position - material.row(0).transpose()).norm(), 1e-9 * setup().diagonal);
  const Eigen::VectorXd surface_step = (moved - deform_points(setup().model, without, canonical)).rowwise().norm();
  const Eigen::VectorXd material_step = (material - deform_points(setup().model, without, canonical)).rowwise().norm();
  EXPECT_TRUE((material_step.array() <= surface_step.array() + 1e-12).all());
  // ... and not nowhere: the refinement reaches the surface along the normals.
  EXPECT_GT(material_step.maxCoeff(), 0.5 * surface_step.maxCoeff());
  EXPECT_LT((frames[0].rotation.transpose() * frames[0].rotation - Eigen::Matrix3d::Identity()).norm(), 1e-9);
}

// A mug's surface in normalised size (no model: the refinement alone needs none).
Points mug_points() {
  const std::vector<SyntheticInstance> mugs = make_synthetic_category(SyntheticCategory::mug, 1, 31);
  const Points points =
      sample_correspondences(SyntheticCategory::mug, mugs[0].shape_parameters, 600, 5).points;
  return Normalization::fit(points).apply(points);
}

TEST(Refinement, ReachesSurfaceTheSpaceFitMissedByMoreThanHalfAGate) {
  // A space fit that missed one region of a full view by 7% of the diagonal (a bump the space cannot make, a
  // fifth of the diagonal wide). Points within the gate of the observation are the observed ones: at the
  // default gate (0.1) the bump's points take part and follow it; at half of it they count as unseen and are
  // held at the fit, the worst error left where it was (measured on kettles, mugs, drills, bottles:
  // docs/registration.md).
  const Points fitted = mug_points();
  Eigen::Index front = 0;
  fitted.col(0).maxCoeff(&front);
  const Points truth = with_bump(fitted, fitted.row(front).transpose(), 0.1, 0.07);
  const auto bump_error = [&](const RefinementSettings& settings) {
    const Points refined = fitted + refine_fit(fitted, truth, std::nullopt, settings).displacement_at(fitted);
    return (refined.row(front) - truth.row(front)).norm();
  };
  RefinementSettings half_gate;
  half_gate.gate = 0.5 * RefinementSettings{}.gate;
  const double at_default = bump_error(RefinementSettings{}), at_half = bump_error(half_gate);
  std::cout << "bump top off the truth (normalised; 0.07 before): gate " << RefinementSettings{}.gate << " "
            << at_default << ", gate " << half_gate.gate << " " << at_half << "\n";
  EXPECT_LT(at_default, 0.02);
  EXPECT_GT(at_half, 0.04);
}

TEST(Refinement, FollowsTheInsideOfABowlSeenFromAbove) {
  // A bowl seen from above shows its inner floor, which sits 5% higher than the fit put it (a mound a fifth of
  // the bowl wide). Which fitted points were seen is decided by occlusion from the viewpoint: normals turned away
  // from the centroid point down on that floor, and the test they alone made left the mound unrefined (0.05 off).
  const Points fitted = testing::open_bowl(1600);
  Points observed(0, 3);
  for (Eigen::Index i = 0; i < fitted.rows(); ++i)
    if (fitted.row(i).norm() < 0.46) {  // the inner surface: the outer one is behind it from above
      Eigen::RowVector3d p = fitted.row(i);
      p.y() += 0.05 * std::exp(-(p.x() * p.x() + p.z() * p.z()) / (2.0 * 0.1 * 0.1));
      observed.conservativeResize(observed.rows() + 1, 3);
      observed.row(observed.rows() - 1) = p;
    }
  const Eigen::Vector3d viewpoint(0.0, 3.0, 0.0);
  const RefinementField field = refine_fit(fitted, observed, viewpoint, RefinementSettings{});
  Eigen::Index floor = 0;  // the inner floor's lowest point, under the mound's top
  (fitted.rowwise().norm().array() < 0.46).select(fitted.col(1).array(), 1.0).minCoeff(&floor);
  const Eigen::RowVector3d refined = fitted.row(floor) + field.displacement_at(fitted.row(floor));
  const double left = std::abs(refined.y() - (fitted(floor, 1) + 0.05));
  std::cout << "observed " << field.observed << " of " << field.points << "; the mound's top " << left
            << " off (0.05 before)\n";
  EXPECT_GT(field.observed, 0.8 * static_cast<double>(observed.rows())) << "most of the inside counts as seen";
  EXPECT_LT(left, 0.015);
}

TEST(Refinement, NothingObservedNearbyLeavesTheSpaceFit) {
  // Stated fallback: an observation farther than the gate from every fitted point gives an empty field.
  const Points fitted = mug_points();
  const Points far = fitted.rowwise() + Eigen::RowVector3d(5.0, 0.0, 0.0);
  const RefinementField field = refine_fit(fitted, far, std::nullopt, RefinementSettings{});
  EXPECT_TRUE(field.empty());
  EXPECT_EQ(field.observed, 0);
  EXPECT_EQ(field.displacement_at(fitted).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Refinement, BadInputIsRefusedClearly) {
  const Points fitted = mug_points();
  EXPECT_THROW(refine_fit(fitted, fitted.topRows(5), std::nullopt, {}), InputError);
  Points broken = fitted;
  broken(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(refine_fit(broken, fitted, std::nullopt, {}), InputError);
  RefinementSettings settings;
  settings.beta = 0.0;
  EXPECT_THROW(refine_fit(fitted, fitted, std::nullopt, settings), UsageError);
  RegistrationSettings registration;
  EXPECT_THROW(set_registration_option(registration, "refine-beta", "0"), UsageError);
  EXPECT_THROW(set_registration_option(registration, "refine-outliers", "1"), UsageError);
  set_registration_option(registration, "refine", "true");
  EXPECT_TRUE(registration.refinement.enabled);
}

}  // namespace
}  // namespace partreg::core
