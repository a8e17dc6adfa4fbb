// The verdict on a registration without the truth (core/registration/verdict.hpp): good on a correct
// registration of a held-out synthetic mug, not good when the answer is wrong (a pose forced off, another
// category's object, a table plane left in); and the units a model with a real size takes observations in.
#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/registration/verdict.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core {
namespace {

struct Setup {
  CategoryModel model;
  Points held_out;  ///< a mug the model was not trained on, in the category frame
  Points drill;     ///< an object of another category, about the mugs' size
};

Setup make_setup() {
  Setup setup;
  const std::vector<SyntheticInstance> mugs = make_synthetic_category(SyntheticCategory::mug, 8, 21);
  std::vector<TrainingInstance> training;
  for (std::size_t i = 0; i + 1 < mugs.size(); ++i) {
    const SurfaceSamples samples = sample_correspondences(SyntheticCategory::mug, mugs[i].shape_parameters, 1500, 5);
    training.push_back({mugs[i].name, samples.points, samples.part, {}, {}});
  }
  TrainingSettings settings;
  settings.canonical_points = 600;
  settings.seam_weight_candidates = {kDefaultSeamWeight};
  setup.model = train_category("mugs", training, {"body", "handle"}, settings);
  setup.held_out = sample_correspondences(SyntheticCategory::mug, mugs.back().shape_parameters, 1500, 5).points;
  const SyntheticInstance drill = make_synthetic_category(SyntheticCategory::drill, 1, 3).front();
  const Points drill_points = sample_correspondences(SyntheticCategory::drill, drill.shape_parameters, 1500, 5).points;
  // The drill brought to the mugs' size and place: only its shape is wrong.
  const double ratio = bounding_box_diagonal(setup.held_out) / bounding_box_diagonal(drill_points);
  const Eigen::RowVector3d drill_centre = drill_points.colwise().mean(), mug_centre = setup.held_out.colwise().mean();
  setup.drill = ((drill_points.rowwise() - drill_centre) * ratio).rowwise() + mug_centre;
  return setup;
}

const Setup& setup() {
  static const Setup instance = make_setup();
  return instance;
}

Points turned(const Points& points, double angle, const Eigen::Vector3d& axis) {
  const Eigen::RowVector3d centre = points.colwise().mean();
  return ((points.rowwise() - centre) * testing::rotation(angle, axis).transpose()).rowwise() + centre;
}

// Symmetric RMS distance to the truth, / the model's diagonal.
double truth_error(const RegistrationResult& result, const Points& truth) {
  std::vector<int> index;
  Eigen::VectorXd to_truth, to_result;
  KdTree(truth).nearest_all(result.deformed, index, to_truth);
  KdTree(result.deformed).nearest_all(truth, index, to_result);
  return std::sqrt(0.5 * (to_truth.mean() + to_result.mean())) / setup().model.normalization.scale;
}

// The figures, for a failure's message.
std::string describe(const RegistrationResult& result) {
  const TrustFigures& f = result.figures;
  std::string text = enum_name(result.assessment.verdict) + ": inliers " + std::to_string(f.inlier_share) +
                     ", rms " + std::to_string(f.observed_rms) + ", latent " + std::to_string(f.latent_distance) +
                     ", ambiguity " + std::to_string(f.pose_ambiguity) + ", refinement " +
                     std::to_string(result.refinement.mean_movement) + "/" +
                     std::to_string(result.refinement.max_movement) + ", seam " + std::to_string(f.seam_gap_max);
  for (const std::string& reason : result.assessment.reasons) text += "; " + reason;
  return text;
}

bool mentions(const Assessment& assessment, const std::string& word) {
  for (const std::string& reason : assessment.reasons)
    if (reason.find(word) != std::string::npos) return true;
  return false;
}

TEST(Verdict, JudgesEachFigureAgainstItsThresholds) {
  TrustFigures figures;
  figures.inlier_share = 0.97, figures.observed_rms = 0.01, figures.latent_distance = 2.0;
  figures.pose_ambiguity = std::numeric_limits<double>::infinity(), figures.mesh_stretch = 2.0;
  EXPECT_EQ(judge(figures).verdict, Verdict::good);
  EXPECT_TRUE(judge(figures).reasons.empty());
  TrustFigures fewer = figures;
  fewer.inlier_share = 0.8;
  EXPECT_EQ(judge(fewer).verdict, Verdict::doubtful);
  fewer.inlier_share = 0.5;
  EXPECT_EQ(judge(fewer).verdict, Verdict::failed);
  EXPECT_TRUE(mentions(judge(fewer), "50%"));
  TrustFigures ambiguous = figures;
  ambiguous.pose_ambiguity = 1.01;
  EXPECT_EQ(judge(ambiguous).verdict, Verdict::doubtful);
  EXPECT_TRUE(mentions(judge(ambiguous), "ambiguous"));
  TrustFigures at_bound = figures;
  at_bound.scale_at_bound = true, at_bound.scale = 3.0;
  EXPECT_TRUE(mentions(judge(at_bound), "bound"));
  VerdictSettings crossed;
  crossed.failed_inlier_share = 0.95;  // above the doubtful share
  EXPECT_THROW(judge(figures, crossed), UsageError);
}

TEST(Verdict, GoodOnACorrectRegistrationOfAHeldOutMug) {
  const Points observed = turned(setup().held_out, 0.3, {1.0, 1.0, 1.0});
  const RegistrationResult result = register_observation(setup().model, observed);
  EXPECT_EQ(result.assessment.verdict, Verdict::good) << describe(result);
  EXPECT_GT(result.figures.inlier_share, 0.95);
  EXPECT_LT(truth_error(result, observed), 0.03);  // the truth agrees: a good registration
}

// A correct registration turned by `angle` about the x axis through the observation's centroid: the pose
// forced wrong, the shape as it was.
RegistrationResult with_pose_turned(RegistrationResult result, const Points& observed, double angle) {
  const Eigen::Matrix3d Q = testing::rotation(angle, {1.0, 0.0, 0.0});
  const Eigen::Vector3d centre = observed.colwise().mean().transpose();
  Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
  turn.topLeftCorner<3, 3>() = Q;
  turn.topRightCorner<3, 1>() = centre - Q * centre;
  for (SpaceFit& fit : result.fits) fit.T_observed_canonical = turn * fit.T_observed_canonical;
  result.deformed = ((result.deformed.rowwise() - centre.transpose()) * Q.transpose()).rowwise() + centre.transpose();
  result.refinement = RefinementField();  // its field lives where the right pose put the points
  return result;
}

TEST(Verdict, NotGoodWhenAWrongPoseIsForced) {
  const Points observed = turned(setup().held_out, 0.3, {1.0, 1.0, 1.0});
  const RegistrationSettings settings;
  const RegistrationResult right = register_observation(setup().model, observed, settings);
  for (double angle : {0.5, M_PI / 2, M_PI}) {
    RegistrationResult wrong = with_pose_turned(right, observed, angle);
    wrong.figures = trust_figures(setup().model, observed, wrong, settings);
    wrong.assessment = judge(wrong.figures, settings.verdict);
    EXPECT_NE(wrong.assessment.verdict, Verdict::good) << angle << " rad: " << describe(wrong);
    EXPECT_GT(truth_error(wrong, observed), 2.0 * truth_error(right, observed)) << angle;  // it is wrong
  }
  // The figures recomputed for the right pose give the registration's own verdict.
  EXPECT_EQ(judge(trust_figures(setup().model, observed, right, settings)).verdict, Verdict::good);
}

TEST(Verdict, NotGoodOnAnotherCategorysObject) {
  const RegistrationResult result = register_observation(setup().model, setup().drill);
  EXPECT_NE(result.assessment.verdict, Verdict::good) << describe(result);
  EXPECT_GT(truth_error(result, setup().drill), 0.03);
}

TEST(Verdict, FailsWithATablePlaneLeftIn) {
  const Points& mug = setup().held_out;
  const double diagonal = bounding_box_diagonal(mug);
  const Eigen::Vector3d lowest = mug.colwise().minCoeff().transpose(), centre = mug.colwise().mean().transpose();
  Points plane(1500, 3);
  for (Eigen::Index i = 0; i < plane.rows(); ++i) {  // a table twice the mug's diagonal wide, under its base
    const double u = (static_cast<double>(i % 39) / 38.0 - 0.5) * 2.0 * diagonal;
    const double v = (static_cast<double>(i / 39) / 38.0 - 0.5) * 2.0 * diagonal;
    plane.row(i) << centre.x() + u, lowest.y(), centre.z() + v;
  }
  Points scene(mug.rows() + plane.rows(), 3);
  scene << mug, plane;
  const RegistrationResult result = register_observation(setup().model, scene);
  EXPECT_EQ(result.assessment.verdict, Verdict::failed) << describe(result);
  EXPECT_LT(result.figures.inlier_share, 0.7);
}

TEST(Verdict, AModelWithARealSizeTakesObservationsInMetres) {
  CategoryModel metric = setup().model;
  metric.size = 0.12;  // metres: the mugs' mean diagonal
  const double metres_per_unit = *metric.size / metric.data_size;
  ASSERT_GT(metric.data_size, 0.0);
  const Points observed = turned(setup().held_out, 0.3, {1.0, 1.0, 1.0});
  const RegistrationResult in_units = register_observation(setup().model, observed);
  const RegistrationResult in_metres = register_observation(metric, Points(observed * metres_per_unit));
  // The same registration, in metres: a model that ignored its size would not reach the metric cloud.
  EXPECT_LT((in_metres.deformed / metres_per_unit - in_units.deformed).cwiseAbs().maxCoeff(),
            1e-6 * setup().model.normalization.scale);
  EXPECT_EQ(in_metres.assessment.verdict, Verdict::good);
  EXPECT_NEAR(in_metres.figures.inlier_share, in_units.figures.inlier_share, 2.0 / 1500);  // a point at the edge
  // Millimetres against a model in metres: refused, with both sizes.
  try {
    register_observation(metric, Points(observed * metres_per_unit * 1000.0));
    FAIL() << "a cloud in millimetres was taken for metres";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find(std::to_string(metric.observed_diagonal())), std::string::npos) << what;
    EXPECT_NE(what.find("metres"), std::string::npos) << what;
  }
}

TEST(Verdict, TheFittedScaleCoversRealSizesAndNamesItsBound) {
  RegistrationSettings scaled;
  scaled.objective.estimate_scale = true;
  const Points larger = Points(setup().held_out * 1.6);
  const RegistrationResult fitted = register_observation(setup().model, larger, scaled);
  EXPECT_NEAR(fitted.figures.scale, 1.6, 0.16);
  EXPECT_FALSE(fitted.figures.scale_at_bound);
  const RegistrationResult bounded = register_observation(setup().model, Points(setup().held_out * 0.2), scaled);
  EXPECT_TRUE(bounded.figures.scale_at_bound);
  EXPECT_NEAR(bounded.figures.scale, 1.0 / scaled.objective.scale_limit, 1e-3);
  EXPECT_NE(bounded.assessment.verdict, Verdict::good);
  EXPECT_TRUE(mentions(bounded.assessment, "bound"));
}

}  // namespace
}  // namespace partreg::core
