// The coupled variant's data term of one part (core/core/src/coupled_solver.hpp): the moment cost at the
// part's effective pose, chained to the object's pose and the part's offset. Its value against the explicit
// sum over the pairs, its Jacobian against central differences.
#include <gtest/gtest.h>

#include <random>

#include "coupled_solver.hpp"

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
  const int residuals = cost->num_residuals();
  const std::vector<int> sizes = {4, 3, 1, 3, 3, 3};
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> pointers;
  for (int size : sizes) {
    jacobians.emplace_back(static_cast<std::size_t>(residuals * size));
    pointers.push_back(jacobians.back().data());
  }
  Eigen::VectorXd r(residuals);
  std::vector<double*> blocks = p.blocks();
  ASSERT_TRUE(cost->Evaluate(blocks.data(), r.data(), pointers.data()));
  const double h = 1e-6;
  for (std::size_t b = 0; b < sizes.size(); ++b)
    for (int c = 0; c < sizes[b]; ++c) {
      Eigen::VectorXd plus(residuals), minus(residuals);
      const double kept = blocks[b][c];
      blocks[b][c] = kept + h;
      cost->Evaluate(blocks.data(), plus.data(), nullptr);
      blocks[b][c] = kept - h;
      cost->Evaluate(blocks.data(), minus.data(), nullptr);
      blocks[b][c] = kept;
      const Eigen::VectorXd numeric = (plus - minus) / (2.0 * h);
      for (int i = 0; i < residuals; ++i)
        EXPECT_NEAR(jacobians[b][static_cast<std::size_t>(i * sizes[b] + c)], numeric[i],
                    1e-5 * (1.0 + std::abs(numeric[i])))
            << "block " << b << " column " << c << " residual " << i;
    }
}

}  // namespace
}  // namespace partreg::core::detail
