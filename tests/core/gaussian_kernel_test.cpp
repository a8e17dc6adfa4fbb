// The Gaussian kernel: the dense matrix against its formula, the blocked matrix-free product
// apply_kernel against the dense product, and the field's Jacobian against finite differences.
#include "partreg/core/geometry/gaussian_kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "partreg/core/errors.hpp"

namespace partreg::core {
namespace {

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd matrix(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) matrix(i, j) = uniform(generator);
  return matrix;
}

Points random_points(Eigen::Index count, std::uint64_t seed) { return random_matrix(count, 3, seed); }

TEST(GaussianKernel, DenseMatrixFollowsTheFormula) {
  const Points a = random_points(40, 1), b = random_points(30, 2);
  for (const double beta : {0.1, 0.7, 3.0}) {
    const Eigen::MatrixXd kernel = gaussian_kernel(a, b, beta);
    ASSERT_EQ(kernel.rows(), 40);
    ASSERT_EQ(kernel.cols(), 30);
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      for (Eigen::Index j = 0; j < b.rows(); ++j) {
        const double expected = std::exp(-(a.row(i) - b.row(j)).squaredNorm() / (2.0 * beta * beta));
        ASSERT_NEAR(kernel(i, j), expected, 1e-12) << "beta " << beta << ", entry " << i << "," << j;
      }
  }
  // A point against itself is exactly 1, at any width.
  EXPECT_DOUBLE_EQ(gaussian_kernel(a.topRows(1), a.topRows(1), 0.01)(0, 0), 1.0);
}

TEST(GaussianKernel, MatrixFreeProductEqualsTheDenseProduct) {
  // More queries than one block (256) and not a multiple of it, so the last block is partial; weights
  // with 3 columns (a CPD field) and with 7 (a shape basis).
  const Points queries = random_points(1000, 3), centres = random_points(300, 4);
  for (const Eigen::Index columns : {3, 7}) {
    const Eigen::MatrixXd weights = random_matrix(centres.rows(), columns, 5 + columns);
    for (const double beta : {0.05, 0.3, 2.0}) {
      SCOPED_TRACE("beta " + std::to_string(beta) + ", " + std::to_string(columns) + " columns");
      const Eigen::MatrixXd kernel = gaussian_kernel(queries, centres, beta);
      const Eigen::MatrixXd dense = kernel * weights;
      const Eigen::MatrixXd product = apply_kernel(queries, centres, weights, beta);
      ASSERT_EQ(product.rows(), dense.rows());
      ASSERT_EQ(product.cols(), dense.cols());
      // The header promises the product itself, no approximation: only round-off may differ, bounded per
      // entry relative to sum_m |g_m| |w_m| (the sum's own scale, which cancellation cannot shrink).
      const Eigen::MatrixXd scale = kernel.cwiseAbs() * weights.cwiseAbs();
      const Eigen::ArrayXXd excess = (product - dense).cwiseAbs().array() - 1e-12 * scale.array() - 1e-300;
      Eigen::Index row = 0, column = 0;
      EXPECT_LE(excess.maxCoeff(&row, &column), 0.0)
          << "entry " << row << "," << column << ": " << product(row, column) << " vs " << dense(row, column);
    }
  }
}

TEST(GaussianKernel, MatrixFreeProductChecksItsArguments) {
  const Points centres = random_points(10, 6);
  EXPECT_THROW(apply_kernel(centres, centres, Eigen::MatrixXd::Ones(9, 3), 1.0), UsageError);
  EXPECT_THROW(apply_kernel(centres, centres, Eigen::MatrixXd::Ones(10, 3), 0.0), UsageError);
  EXPECT_THROW(gaussian_kernel(centres, centres, -1.0), UsageError);
  EXPECT_EQ(apply_kernel(Points(0, 3), centres, Eigen::MatrixXd::Ones(10, 3), 1.0).rows(), 0);
}

TEST(GaussianKernel, FieldJacobianMatchesFiniteDifferences) {
  const Points centres = random_points(50, 7);
  const Points weights = 0.1 * random_points(50, 8);
  const double beta = 0.6, step = 1e-6;
  for (const Eigen::Vector3d z : {Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(1.5, 0.0, -0.5)}) {
    const Eigen::Matrix3d jacobian = kernel_field_jacobian(z, centres, weights, beta);
    Eigen::Matrix3d numeric;
    for (int j = 0; j < 3; ++j) {
      Points plus = z.transpose(), minus = z.transpose();
      plus(0, j) += step;
      minus(0, j) -= step;
      numeric.col(j) =
          ((apply_kernel(plus, centres, weights, beta) - apply_kernel(minus, centres, weights, beta)) /
           (2.0 * step))
              .transpose();
    }
    EXPECT_LT((jacobian - numeric).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, numeric.norm()))
        << "analytic\n"
        << jacobian << "\nnumeric\n"
        << numeric;
    ASSERT_GT(numeric.norm(), 1e-3) << "a field this flat would let a wrong Jacobian pass";
  }
}

}  // namespace
}  // namespace partreg::core
