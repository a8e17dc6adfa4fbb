// The coupled variant's terms (core/core/src/registration/coupled_solver.hpp): one part's data term (the
// moment cost at the part's effective pose, chained to the object's pose and the part's offset) and the seam
// term of two parts. Their values against the definitions, their Jacobians against central differences.
#include <gtest/gtest.h>

#include <random>

#include "registration/coupled_solver.hpp"
#include "support/jacobian_check.hpp"

namespace partreg::core::detail {
namespace {

struct Fixture {
  ShapeSpace space;
  std::vector<WeightedPair> pairs;
  Eigen::Vector3d centre = Eigen::Vector3d(0.2, -0.1, 0.3);
};

Fixture random_part(int points, int q, int pairs, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  const auto fill = [&](auto& matrix) {
    for (Eigen::Index i = 0; i < matrix.size(); ++i) matrix.data()[i] = normal(random);
  };
  Fixture f;
  f.space.canonical.resize(points, 3);
  f.space.kernel_mean.resize(3 * points);
  f.space.kernel_basis.resize(3 * points, q);
  f.space.basis.resize(3 * points, q);
  fill(f.space.canonical);
  fill(f.space.kernel_mean);
  fill(f.space.kernel_basis);
  f.space.variances = Eigen::VectorXd::LinSpaced(q, 2.0, 0.5);
  std::uniform_int_distribution<int> row(0, points - 1);
  for (int i = 0; i < pairs; ++i) {
    Eigen::Vector3d target;
    fill(target);
    f.pairs.push_back({row(random), target, 0.5 + 0.01 * i});
  }
  return f;
}

struct Parameters {
  Eigen::Quaterniond rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  Eigen::Vector3d translation = Eigen::Vector3d(0.3, -0.1, 0.8);
  double scale = 1.15;
  Eigen::Vector3d offset_rotation = Eigen::Vector3d(0.05, -0.08, 0.03);  // angle-axis (rad)
  Eigen::Vector3d offset_translation = Eigen::Vector3d(0.02, 0.01, -0.03);
  Eigen::VectorXd latent = Eigen::Vector3d(0.5, -0.3, 0.2);
  std::vector<double*> blocks() {
    return {rotation.coeffs().data(), translation.data(),        &scale,
            offset_rotation.data(),   offset_translation.data(), latent.data()};
  }
};

// sum_i w_i |s R0 (R_p (y_i - c) + c + d) + t0 - o_i|^2: the definition, point by point (no prior).
double explicit_cost(const Fixture& f, const Parameters& p) {
  const double angle = p.offset_rotation.norm();
  const Eigen::Matrix3d R_p = Eigen::AngleAxisd(angle, p.offset_rotation / angle).toRotationMatrix();
  double sum = 0.0;
  for (const WeightedPair& pair : f.pairs) {
    const Eigen::Index row = 3 * pair.row;
    const Eigen::Vector3d y = f.space.canonical.row(pair.row).transpose() +
                              f.space.kernel_mean.segment<3>(row) +
                              f.space.kernel_basis.middleRows<3>(row) * p.latent;
    const Eigen::Vector3d moved =
        p.scale * (p.rotation * (R_p * (y - f.centre) + f.centre + p.offset_translation)) + p.translation;
    sum += pair.weight * (moved - pair.target).squaredNorm();
  }
  return sum;
}

TEST(CoupledPartCost, EqualsTheSumOverPairsAtTheOffsetPose) {
  const Fixture f = random_part(30, 3, 120, 7);
  const auto cost = make_part_data_cost(f.space, f.pairs, 0.0, f.centre);
  Parameters p;
  Eigen::VectorXd r(cost->num_residuals());
  std::vector<double*> blocks = p.blocks();
  ASSERT_TRUE(cost->Evaluate(blocks.data(), r.data(), nullptr));
  const double expected = explicit_cost(f, p);
  EXPECT_NEAR(r.squaredNorm(), expected, 1e-9 * expected);
  // A wrong pivot (the offset turning about the origin) gives another cost: the test would see it.
  Fixture other = f;
  other.centre.setZero();
  EXPECT_GT(std::abs(explicit_cost(other, p) - expected), 1e-3 * expected);
}

TEST(CoupledPartCost, JacobianMatchesCentralDifferences) {
  const Fixture f = random_part(30, 3, 120, 11);
  const auto cost = make_part_data_cost(f.space, f.pairs, 0.05, f.centre);
  Parameters p;
  testing::expect_jacobian_matches_central_differences(*cost, p.blocks());
}

// Part p's motion of z before the object pose, from the definition: R_p (z + G(z, C_p) W(x_p) - c_p) + c_p + d_p.
Eigen::Vector3d seam_motion(const Fixture& f, const Eigen::Vector3d& z, const Eigen::Vector3d& angle_axis,
                            const Eigen::Vector3d& offset, const Eigen::VectorXd& latent) {
  Eigen::Vector3d field = Eigen::Vector3d::Zero();
  const Eigen::VectorXd weights = f.space.mean + f.space.basis * latent;
  for (Eigen::Index m = 0; m < f.space.canonical.rows(); ++m) {
    const double g =
        std::exp(-(f.space.canonical.row(m).transpose() - z).squaredNorm() / (2.0 * f.space.beta * f.space.beta));
    field += g * weights.segment<3>(3 * m);
  }
  const double angle = angle_axis.norm();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, angle_axis / angle).toRotationMatrix();
  return R * (z + field - f.centre) + f.centre + offset;
}

struct SeamFixture {
  Fixture a = random_part(25, 3, 0, 21), b = random_part(20, 2, 0, 22);
  Points z = Points::Random(12, 3);
  SeamFixture() {
    b.centre = Eigen::Vector3d(-0.3, 0.4, 0.1);
    for (Fixture* f : {&a, &b}) {
      f->space.beta = 0.8;
      f->space.mean = 0.1 * Eigen::VectorXd::Random(f->space.basis.rows());
    }
  }
};

TEST(CoupledSeamCost, IsTheGapBetweenTheTwoPartsMotions) {
  const SeamFixture f;
  const double root_weight = 0.7;
  const auto cost = make_seam_cost(f.a.space, f.a.centre, f.b.space, f.b.centre, f.z, root_weight);
  ASSERT_EQ(cost->num_residuals(), 3 * f.z.rows());
  Eigen::Vector3d ra(0.05, -0.08, 0.03), da(0.02, 0.01, -0.03), rb(-0.02, 0.04, 0.1), db(0.0, -0.02, 0.05);
  Eigen::VectorXd xa = Eigen::Vector3d(0.5, -0.3, 0.2), xb = Eigen::Vector2d(-0.4, 0.6);
  std::vector<double*> blocks = {ra.data(), da.data(), xa.data(), rb.data(), db.data(), xb.data()};
  Eigen::VectorXd r(cost->num_residuals());
  ASSERT_TRUE(cost->Evaluate(blocks.data(), r.data(), nullptr));
  for (Eigen::Index i = 0; i < f.z.rows(); ++i) {
    const Eigen::Vector3d z = f.z.row(i).transpose();
    const Eigen::Vector3d gap = seam_motion(f.a, z, ra, da, xa) - seam_motion(f.b, z, rb, db, xb);
    EXPECT_LT((r.segment<3>(3 * i) - root_weight * gap).norm(), 1e-9 * (1.0 + gap.norm())) << "point " << i;
  }
}

TEST(CoupledSeamCost, JacobianMatchesCentralDifferences) {
  const SeamFixture f;
  const auto cost = make_seam_cost(f.a.space, f.a.centre, f.b.space, f.b.centre, f.z, 0.7);
  // At a turned offset and at zero (where the solve starts: angle-axis derivatives are special there).
  for (const double turn : {1.0, 0.0}) {
    Eigen::Vector3d ra = turn * Eigen::Vector3d(0.3, -0.2, 0.1), da(0.02, 0.01, -0.03);
    Eigen::Vector3d rb = turn * Eigen::Vector3d(-0.1, 0.25, 0.05), db(0.0, -0.02, 0.05);
    Eigen::VectorXd xa = Eigen::Vector3d(0.5, -0.3, 0.2), xb = Eigen::Vector2d(-0.4, 0.6);
    testing::expect_jacobian_matches_central_differences(
        *cost, {ra.data(), da.data(), xa.data(), rb.data(), db.data(), xb.data()}, "turn " + std::to_string(turn));
  }
}

// Each part's prior weighs against its own data as a single space's prior weighs against the whole
// observation: the setting times the part's share of the step's pair weights (robust weights included).
TEST(CoupledPartPrior, IsTheSettingTimesThePartsShareOfThePairWeights) {
  const auto pair = [](double weight) { return WeightedPair{0, Eigen::Vector3d::Zero(), weight}; };
  // A body with 0.9 of the weight (one pair down-weighted by the robust loss), a handle with 0.1, a hidden
  // lid.
  const std::vector<std::vector<WeightedPair>> pairs = {{pair(0.5), pair(0.3), pair(0.1)}, {pair(0.1)}, {}};
  const std::vector<double> weights = part_prior_weights(pairs, 2e-5);
  ASSERT_EQ(weights.size(), 3u);
  EXPECT_NEAR(weights[0], 0.9 * 2e-5, 1e-15);
  EXPECT_NEAR(weights[1], 0.1 * 2e-5, 1e-15);
  EXPECT_EQ(weights[2], 0.0);  // no data: the seams and its start hold it
  // The shares sum to one: the parts together weigh their latents as a single space does.
  EXPECT_NEAR(weights[0] + weights[1] + weights[2], 2e-5, 1e-15);
  // No pairs in any part: the setting for every part, not a division by zero.
  for (const double weight : part_prior_weights({{}, {}}, 2e-5)) EXPECT_EQ(weight, 2e-5);
}

}  // namespace
}  // namespace partreg::core::detail
