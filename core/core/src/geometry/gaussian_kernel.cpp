#include "partreg/core/geometry/gaussian_kernel.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"

namespace partreg::core {
namespace {

// Squared distances between every row of a and every row of b, via |a|^2 + |b|^2 - 2 a.b (one GEMM).
Eigen::MatrixXd squared_distances(const Points& a, const Points& b) {
  Eigen::MatrixXd d = -2.0 * (a * b.transpose());
  d.colwise() += a.rowwise().squaredNorm();
  d.rowwise() += b.rowwise().squaredNorm().transpose();
  return d.cwiseMax(0.0);
}

void check_beta(double beta) {
  if (!(beta > 0.0)) throw UsageError("the Gaussian kernel width beta must be positive");
}

}  // namespace

Eigen::MatrixXd gaussian_kernel(const Points& a, const Points& b, double beta) {
  check_beta(beta);
  return (squared_distances(a, b) * (-0.5 / (beta * beta))).array().exp();
}

Eigen::MatrixXd apply_kernel(const Points& queries, const Points& centres,
                             const Eigen::Ref<const Eigen::MatrixXd>& weights, double beta) {
  check_beta(beta);
  if (weights.rows() != centres.rows())
    throw UsageError("apply_kernel: one weight row per centre is required");
  Eigen::MatrixXd result(queries.rows(), weights.cols());
  constexpr Eigen::Index kBlock = 256;
  const Eigen::Index blocks = (queries.rows() + kBlock - 1) / kBlock;
  parallel_for(
      blocks,
      [&](Eigen::Index first, Eigen::Index last) {
        for (Eigen::Index block = first; block < last; ++block) {
          const Eigen::Index begin = block * kBlock;
          const Eigen::Index rows = std::min(kBlock, queries.rows() - begin);
          const Points slice = queries.middleRows(begin, rows);
          result.middleRows(begin, rows).noalias() = gaussian_kernel(slice, centres, beta) * weights;
        }
      },
      0, 1);
  return result;
}

Eigen::Matrix3d kernel_field_jacobian(const Eigen::Vector3d& z, const Points& centres, const Points& weights,
                                      double beta) {
  check_beta(beta);
  // d/dz g(z, c) = -g(z, c) (z - c) / beta^2, so J = sum_m w_m (d g_m / d z)^T.
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
  const double inverse = 1.0 / (beta * beta);
  for (Eigen::Index m = 0; m < centres.rows(); ++m) {
    const Eigen::Vector3d offset = z - centres.row(m).transpose();
    const double g = std::exp(-0.5 * inverse * offset.squaredNorm());
    jacobian.noalias() -= (g * inverse) * weights.row(m).transpose() * offset.transpose();
  }
  return jacobian;
}

}  // namespace partreg::core
