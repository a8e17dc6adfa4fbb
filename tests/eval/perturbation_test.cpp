// Each perturbation at a known level moves points by the stated amount (fixed seeds, statistical bounds).
#include "partreg/eval/perturbation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "partreg/core/errors.hpp"

namespace partreg {
namespace {

core::Points random_box(int count, const Eigen::Vector3d& size) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  core::Points points(count, 3);
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) points(i, k) = unit(random) * size[k];
  return points;
}

TEST(Perturbation, PaperLevelsScaleWithTheDiagonal) {
  EXPECT_DOUBLE_EQ(eval::relative_level(eval::Perturbation::noise, 0.015), 0.05);
  EXPECT_DOUBLE_EQ(eval::relative_level(eval::Perturbation::rotation, 0.39), 0.39);
  EXPECT_EQ(eval::paper_levels(eval::Perturbation::translation).back(), 0.1);
  EXPECT_EQ(eval::paper_levels(eval::Perturbation::outliers).front(), 0.04);
}

TEST(Perturbation, NoiseHasTheStatedStandardDeviation) {
  const core::Points points = random_box(20000, {1, 2, 2});  // diagonal 3
  const eval::Perturbed noisy = eval::perturb(points, eval::Perturbation::noise, 0.02, 3.0, 11);
  const core::Points shift = noisy.points - points;
  const double sigma = std::sqrt(shift.squaredNorm() / double(shift.size()));
  EXPECT_NEAR(sigma, 0.06, 0.06 * 0.02);            // 0.02 x 3, within 2% (60000 samples)
  EXPECT_LT(shift.colwise().mean().norm(), 0.003);  // zero mean
  EXPECT_TRUE(noisy.T_perturbed_original.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(Perturbation, OutliersAreAddedInTheBoundingBoxAndThePointsStay) {
  const core::Points points = random_box(5000, {1, 1, 3});
  const eval::Perturbed result = eval::perturb(points, eval::Perturbation::outliers, 0.2, 3.3, 3);
  ASSERT_EQ(result.points.rows(), 6000);
  EXPECT_EQ(result.points.topRows(5000), points);
  const core::Points added = result.points.bottomRows(1000);
  const Eigen::RowVector3d low = points.colwise().minCoeff(), high = points.colwise().maxCoeff();
  for (Eigen::Index i = 0; i < added.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(added(i, k), low[k]);
      EXPECT_LE(added(i, k), high[k]);
    }
  // Uniform: the mean of the outliers is the box centre (within 3 standard errors).
  EXPECT_NEAR(added.col(2).mean(), (low[2] + high[2]) / 2, 3 * 3 / std::sqrt(12.0 * 1000));
}

TEST(Perturbation, RotationTurnsAboutEachAxisByTheSameAngleAroundTheCentre) {
  const core::Points points = random_box(500, {1, 2, 3});
  const double angle = 0.39;
  int negative_x = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const eval::Perturbed rotated = eval::perturb(points, eval::Perturbation::rotation, angle, 1.0, seed);
    const Eigen::Matrix3d R = rotated.T_perturbed_original.linear();
    // R = Rz(+-a) Ry(+-a) Rx(+-a): recover the signs and check the composition exactly.
    bool matched = false;
    for (int signs = 0; signs < 8 && !matched; ++signs) {
      const double sx = signs & 1 ? -1 : 1, sy = signs & 2 ? -1 : 1, sz = signs & 4 ? -1 : 1;
      const Eigen::Matrix3d expected = (Eigen::AngleAxisd(sz * angle, Eigen::Vector3d::UnitZ()) *
                                        Eigen::AngleAxisd(sy * angle, Eigen::Vector3d::UnitY()) *
                                        Eigen::AngleAxisd(sx * angle, Eigen::Vector3d::UnitX()))
                                           .toRotationMatrix();
      if ((expected - R).norm() < 1e-12) matched = true, negative_x += sx < 0;
    }
    EXPECT_TRUE(matched) << "seed " << seed;
    // The box centre stays put, and the points moved with the returned transform.
    const Eigen::Vector3d box_centre =
        (points.colwise().minCoeff() + points.colwise().maxCoeff()).transpose() / 2;
    EXPECT_LT((rotated.T_perturbed_original * box_centre - box_centre).norm(), 1e-12);
    EXPECT_LT(
        (rotated.points.row(7).transpose() - rotated.T_perturbed_original * points.row(7).transpose()).norm(),
        1e-12);
  }
  EXPECT_GT(negative_x, 5);  // the signs are random
  EXPECT_LT(negative_x, 35);
}

TEST(Perturbation, TranslationMovesEveryAxisByTheLevelTimesTheDiagonal) {
  const core::Points points = random_box(100, {1, 1, 1});
  const eval::Perturbed moved = eval::perturb(points, eval::Perturbation::translation, 0.1, 2.0, 5);
  const Eigen::RowVector3d shift = moved.points.row(0) - points.row(0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(std::abs(shift[k]), 0.2, 1e-12);
  EXPECT_LT(((moved.points - points).rowwise() - shift).norm(), 1e-12);
}

TEST(Perturbation, YawTurnsAboutTheUpAxisAfterASmallTilt) {
  const core::Points points = random_box(300, {1, 2, 3});
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  for (const double yaw : eval::sweep_levels(eval::Perturbation::yaw)) {
    const eval::Perturbed turned = eval::perturb(points, eval::Perturbation::yaw, yaw, 1.0, 3, up);
    const Eigen::Matrix3d R = turned.T_perturbed_original.linear();
    // The up axis leans by exactly the tilt; undoing the tilt leaves a turn about up by the yaw.
    EXPECT_NEAR(std::acos(std::clamp((R * up).dot(up), -1.0, 1.0)), eval::kYawTilt, 1e-9) << yaw;
    const Eigen::Vector3d tilt_axis = up.cross(R * up).normalized();
    const Eigen::Matrix3d untilted = Eigen::AngleAxisd(-eval::kYawTilt, tilt_axis) * R;
    EXPECT_LT((untilted - Eigen::AngleAxisd(yaw, up).toRotationMatrix()).norm(), 1e-9) << yaw;
    EXPECT_LT(
        (turned.points.row(5).transpose() - turned.T_perturbed_original * points.row(5).transpose()).norm(),
        1e-12);
  }
  EXPECT_EQ(eval::sweep_levels(eval::Perturbation::yaw).size(), 12u);
  EXPECT_NEAR(eval::shown_level(eval::Perturbation::yaw, eval::sweep_levels(eval::Perturbation::yaw)[11]),
              330, 1e-9);
}

TEST(Perturbation, TheRotationSweepWidensPastThePapersLevels) {
  const std::vector<double>& levels = eval::sweep_levels(eval::Perturbation::rotation);
  ASSERT_GT(levels.size(), std::size_t(eval::kFirstWideRotationLevel));
  for (int i = 0; i < eval::kFirstWideRotationLevel; ++i)
    EXPECT_EQ(levels[i], eval::paper_levels(eval::Perturbation::rotation)[i]);
  for (std::size_t i = 1; i < levels.size(); ++i) EXPECT_GT(levels[i], levels[i - 1]);
  EXPECT_GT(levels[eval::kFirstWideRotationLevel], 0.65);
  EXPECT_LE(levels.back(), M_PI / 2 + 1e-3);
}

TEST(Perturbation, LevelsOutOfRangeAreRefused) {
  const core::Points points = random_box(10, {1, 1, 1});
  EXPECT_THROW(eval::perturb(points, eval::Perturbation::noise, -0.1, 1.0, 1), UsageError);
  EXPECT_THROW(eval::perturb(points, eval::Perturbation::rotation, 4.0, 1.0, 1), UsageError);
  EXPECT_THROW(eval::perturb(points, eval::Perturbation::outliers, std::nan(""), 1.0, 1), UsageError);
  EXPECT_THROW(core::parse_enum<eval::Perturbation>("shear"), UsageError);
  EXPECT_THROW(eval::perturb(points, eval::Perturbation::yaw, 2 * M_PI, 1.0, 1), UsageError);
  EXPECT_THROW(eval::perturb(points, eval::Perturbation::yaw, 0.5, 1.0, 1, Eigen::Vector3d::Zero()),
               UsageError);
}

}  // namespace
}  // namespace partreg
