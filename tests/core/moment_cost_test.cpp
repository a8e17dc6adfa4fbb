// The registration step's cost in moments (core/core/src/registration/moment_cost.hpp) against the sum it
// replaces: sum_i w_i |s R (a_i + K_i x) + t - o_i|^2 plus the prior, and its Jacobian against central
// differences.
#include "registration/moment_cost.hpp"

#include <gtest/gtest.h>

#include <random>

#include "support/jacobian_check.hpp"

namespace partreg::core::detail {
namespace {

struct Fixture {
  ShapeSpace space;
  std::vector<WeightedPair> pairs;
};

Fixture random_step(int points, int q, int pairs, unsigned seed) {
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
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  for (int i = 0; i < pairs; ++i) {
    Eigen::Vector3d target;
    fill(target);
    f.pairs.push_back({row(random), target, weight(random)});
  }
  return f;
}

// The parameters in Ceres' blocks: quaternion (x, y, z, w), translation, scale, latent.
struct Parameters {
  Eigen::Quaterniond rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  Eigen::Vector3d translation = Eigen::Vector3d(0.3, -0.1, 0.8);
  double scale = 1.15;
  Eigen::VectorXd latent;
  std::vector<double*> blocks() {
    return {rotation.coeffs().data(), translation.data(), &scale, latent.data()};
  }
};

double explicit_cost(const Fixture& f, const Parameters& p, double prior_weight) {
  double sum = 0.0;
  for (const WeightedPair& pair : f.pairs) {
    const Eigen::Index row = 3 * pair.row;
    const Eigen::Vector3d point = f.space.canonical.row(pair.row).transpose() +
                                  f.space.kernel_mean.segment<3>(row) +
                                  f.space.kernel_basis.middleRows<3>(row) * p.latent;
    sum += pair.weight * (p.scale * (p.rotation * point) + p.translation - pair.target).squaredNorm();
  }
  return sum + prior_weight * (p.latent.array().square() / f.space.variances.array()).sum();
}

double moment_cost(const MomentCost& cost, Parameters& p) {
  Eigen::VectorXd residuals(cost.num_residuals());
  const std::vector<double*> blocks = p.blocks();
  EXPECT_TRUE(cost.Evaluate(blocks.data(), residuals.data(), nullptr));
  return residuals.squaredNorm();
}

TEST(MomentCost, EqualsTheSumOverThePairs) {
  const Fixture f = random_step(60, 5, 400, 7);
  const MomentCost cost(f.space, f.pairs, 0.01);
  EXPECT_EQ(cost.num_residuals(), 3 * (3 * 6 + 2) + 5);  // whatever the number of pairs
  Parameters p;
  p.latent = Eigen::VectorXd::LinSpaced(5, -1.0, 1.5);
  const double expected = explicit_cost(f, p, 0.01);
  EXPECT_NEAR(moment_cost(cost, p), expected, 1e-9 * expected);
  p.latent.setZero();
  p.scale = 0.9;
  EXPECT_NEAR(moment_cost(cost, p), explicit_cost(f, p, 0.01), 1e-9 * expected);
}

TEST(MomentCost, FewDegeneratePairsStillGiveTheirCost) {
  // Two pairs on the same row: the moments are far from full rank (the factor comes from a pivoted LDL^T).
  Fixture f = random_step(10, 3, 2, 11);
  f.pairs[1].row = f.pairs[0].row;
  const MomentCost cost(f.space, f.pairs, 0.0);
  Parameters p;
  p.latent = Eigen::Vector3d(0.2, -0.4, 0.1);
  const double expected = explicit_cost(f, p, 0.0);
  EXPECT_NEAR(moment_cost(cost, p), expected, 1e-9 * std::max(expected, 1.0));
}

TEST(MomentCost, JacobianMatchesCentralDifferences) {
  const Fixture f = random_step(40, 4, 200, 3);
  const MomentCost cost(f.space, f.pairs, 0.05);
  Parameters p;
  p.latent = Eigen::Vector4d(0.5, -0.3, 0.2, 1.0);
  testing::expect_jacobian_matches_central_differences(cost, p.blocks());
}

}  // namespace
}  // namespace partreg::core::detail
