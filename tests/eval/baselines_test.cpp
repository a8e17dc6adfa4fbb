// The evaluation's baselines: the rigid alignment they share, and the oracle's choice of template.
#include "partreg/eval/baselines.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/core/training/training.hpp"

namespace partreg {
namespace {

constexpr int kSamples = 1200;

core::Points mug_points(const core::SyntheticInstance& mug) {
  return core::sample_correspondences(core::SyntheticCategory::mug, mug.shape_parameters, kSamples, 5).points;
}

Eigen::Matrix4d pose(double angle_rad, const Eigen::Vector3d& axis, const Eigen::Vector3d& translation) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = translation;
  return T;
}

core::Points moved(const core::Points& points, const Eigen::Matrix4d& T) {
  return (points * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
}

double rotation_error_rad(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.topLeftCorner<3, 3>().transpose() * b.topLeftCorner<3, 3>()))
      .angle();
}

TEST(RigidAlignment, RecoversAKnownPoseOfAMugFromAFullAndAHalfView) {
  const core::Points mug = mug_points(core::make_synthetic_instance(core::SyntheticCategory::mug, 3, 0));
  const core::KdTree tree(mug);
  const Eigen::Matrix4d T_observed_mug =
      pose(0.3, Eigen::Vector3d(1, 2, 0.5), Eigen::Vector3d(0.05, -0.02, 0.01));
  const core::Points observed = moved(mug, T_observed_mug);
  const std::vector<Eigen::Matrix3d> identity = eval::start_rotations(1, Eigen::Vector3d::UnitY());
  const eval::RigidAlignment full = eval::align_rigidly(tree, observed, identity);
  EXPECT_LT(rotation_error_rad(full.T_observed_template, T_observed_mug), 0.01);
  EXPECT_LT((full.T_observed_template.topRightCorner<3, 1>() - T_observed_mug.topRightCorner<3, 1>()).norm(),
            0.002);
  // The start (identity, centroids aligned) is 0.3 rad off: the tolerance above would catch no alignment.
  ASSERT_GT(rotation_error_rad(Eigen::Matrix4d::Identity(), T_observed_mug), 0.25);

  // Half the mug (the points with x > 0 before moving), as a partial view sees it: each observed point
  // finds its place on the whole template.
  std::vector<int> half;
  for (Eigen::Index i = 0; i < mug.rows(); ++i)
    if (mug(i, 0) > 0.0) half.push_back(static_cast<int>(i));
  const core::Points seen = moved(core::select_rows(mug, half), T_observed_mug);
  ASSERT_GT(seen.rows(), kSamples / 4);
  const eval::RigidAlignment partial = eval::align_rigidly(tree, seen, identity);
  EXPECT_LT(rotation_error_rad(partial.T_observed_template, T_observed_mug), 0.02);
  EXPECT_LT(partial.rms, 1e-3);
}

TEST(RigidAlignment, StartsTurnAboutTheUpAxisAndBadInputIsRefused) {
  const std::vector<Eigen::Matrix3d> starts = eval::start_rotations(4, Eigen::Vector3d(0, 2, 0));
  ASSERT_EQ(starts.size(), 4u);
  EXPECT_TRUE(starts[0].isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE((starts[1] * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitZ()));  // 90 deg about y
  EXPECT_TRUE((starts[2] * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitY()));
  const core::KdTree tree(core::Points::Random(20, 3));
  EXPECT_THROW(eval::align_rigidly(tree, core::Points::Random(2, 3), starts), InputError);
  EXPECT_THROW(eval::align_rigidly(tree, core::Points::Random(20, 3), {}), InputError);
}

// Every mug but the last, sampled for training (the last is the one observed).
std::vector<core::TrainingInstance> all_but_the_last(const std::vector<core::SyntheticInstance>& mugs) {
  std::vector<core::TrainingInstance> training;
  for (std::size_t i = 0; i + 1 < mugs.size(); ++i)
    training.push_back({mugs[i].name, mug_points(mugs[i]), {}, {}, {}});
  return training;
}

// Four synthetic mugs train the model; a fifth is observed. The oracle keeps the template closest to the
// truth, which is never worse than the canonical alone; the mean shape at the true pose is close to the
// truth, and far from it at a wrong pose.
TEST(Baselines, TheOracleKeepsTheTemplateClosestToTheTruth) {
  const std::vector<core::SyntheticInstance> mugs =
      core::make_synthetic_category(core::SyntheticCategory::mug, 5, 11);
  const std::vector<core::TrainingInstance> training = all_but_the_last(mugs);
  core::TrainingSettings settings;
  settings.canonical_points = 400;
  const core::CategoryModel model = core::train_category("mugs", training, {}, settings);
  const std::vector<eval::Template> templates = eval::fold_templates(model, training);
  ASSERT_EQ(templates.size(), 4u);
  EXPECT_TRUE(templates[0].is_canonical);
  EXPECT_EQ(templates[0].name, model.training.canonical);
  for (const eval::Template& shape : templates) EXPECT_EQ(shape.tree.size(), 400);

  const core::Points truth_points = mug_points(mugs.back());
  const Eigen::Matrix4d T_observed_truth = pose(0.2, Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.1, 0, 0));
  const core::KdTree truth(moved(truth_points, T_observed_truth));
  const core::Points observed = moved(truth_points, T_observed_truth);
  eval::BaselineObservation seen{&observed, &truth, core::truth_diagonal(truth_points), nullptr,
                                 T_observed_truth};
  const std::vector<eval::BaselineScore> scores =
      eval::score_baselines(model, templates, seen, eval::start_rotations(1, Eigen::Vector3d::UnitY()));
  ASSERT_EQ(scores.size(), 3u);
  EXPECT_EQ(scores[0].baseline, eval::Baseline::oracle_template);
  EXPECT_EQ(scores[1].baseline, eval::Baseline::rigid_canonical);
  EXPECT_EQ(scores[2].baseline, eval::Baseline::mean_shape);
  EXPECT_EQ(scores[1].shape, model.training.canonical);
  // The oracle's choice is the minimum over every template, each aligned alone.
  double best = std::numeric_limits<double>::infinity();
  for (const eval::Template& shape : templates) {
    const eval::RigidAlignment alignment =
        eval::align_rigidly(shape.tree, observed, eval::start_rotations(1, Eigen::Vector3d::UnitY()));
    best =
        std::min(best, core::measure_against_truth(moved(shape.tree.points(), alignment.T_observed_template),
                                                   {}, {}, truth, seen.diagonal)
                           .symmetric_rms_per_diagonal);
  }
  EXPECT_DOUBLE_EQ(scores[0].errors.symmetric_rms_per_diagonal, best);
  EXPECT_LE(scores[0].errors.symmetric_rms_per_diagonal, scores[1].errors.symmetric_rms_per_diagonal);
  // Aligned mugs of one family are close (a few % of the diagonal), not exact.
  EXPECT_LT(scores[0].errors.symmetric_rms_per_diagonal, 0.05);
  EXPECT_GT(scores[0].errors.symmetric_rms_per_diagonal, 1e-4);

  // The mean shape where the pose says: at the truth's pose it lies on the mug; turned half round it does
  // not.
  EXPECT_LT(scores[2].errors.symmetric_rms_per_diagonal, 0.05);
  seen.T_observed_canonical =
      T_observed_truth * pose(M_PI, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  const double turned =
      eval::score_baselines(model, templates, seen, eval::start_rotations(1, Eigen::Vector3d::UnitY()))[2]
          .errors.symmetric_rms_per_diagonal;
  EXPECT_GT(turned, 2 * scores[2].errors.symmetric_rms_per_diagonal);
}

// The true shape is the tested mug itself as M points from a sample other than the truth's, at the truth's
// pose: the floor under every figure. Below every other baseline, above zero (its points are not the
// truth's), and its reverse half grows as M shrinks (the truth is farther from the nearest of fewer points).
TEST(Baselines, TheTrueShapeIsTheFloorAndFallsWithMorePoints) {
  const std::vector<core::SyntheticInstance> mugs =
      core::make_synthetic_category(core::SyntheticCategory::mug, 5, 11);
  const std::vector<core::TrainingInstance> training = all_but_the_last(mugs);
  const auto reverse_of = [&](int canonical_points, std::vector<eval::BaselineScore>* out) {
    core::TrainingSettings settings;
    settings.canonical_points = canonical_points;
    const core::CategoryModel model = core::train_category("mugs", training, {}, settings);
    const core::Points truth_points =
        core::sample_correspondences(core::SyntheticCategory::mug, mugs.back().shape_parameters, 4000, 5)
            .points;
    const core::Points other_sample =  // the same mug's surface, another seed
        core::sample_correspondences(core::SyntheticCategory::mug, mugs.back().shape_parameters, 4000, 9)
            .points;
    const core::Points floor = eval::true_shape_points(model, other_sample);
    EXPECT_EQ(floor.rows(), canonical_points);
    const Eigen::Matrix4d T_observed_truth = pose(0.2, Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.1, 0, 0));
    const core::KdTree truth(moved(truth_points, T_observed_truth));
    const core::Points observed = moved(truth_points, T_observed_truth),
                       floor_posed = moved(floor, T_observed_truth);
    const eval::BaselineObservation seen{&observed, &truth,           core::truth_diagonal(truth_points),
                                         nullptr,   T_observed_truth, &floor_posed};
    *out = eval::score_baselines(model, eval::fold_templates(model, training), seen,
                                 eval::start_rotations(1, Eigen::Vector3d::UnitY()));
    return out->size() == 4 ? (*out)[3].errors.reverse_eq5 : 0.0;
  };
  std::vector<eval::BaselineScore> dense, sparse;
  const double dense_reverse = reverse_of(800, &dense), sparse_reverse = reverse_of(200, &sparse);
  ASSERT_EQ(dense.size(), 4u);
  EXPECT_EQ(dense[3].baseline, eval::Baseline::true_shape);
  const double floor = dense[3].errors.symmetric_rms_per_diagonal;
  EXPECT_GT(floor, 1e-4);
  for (std::size_t b = 0; b < 3; ++b) EXPECT_LT(floor, dense[b].errors.symmetric_rms_per_diagonal) << b;
  EXPECT_GT(sparse_reverse, 2.0 * dense_reverse);  // 4x fewer points: about 4x the mean squared distance
}

}  // namespace
}  // namespace partreg
