#include "moment_cost.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

namespace partreg::core::detail {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Q = sum_i w_i sum_a f_ia f_ia^T over the pairs' rows f_ia (see the header), built from three moments of the
// vectors p_i = vec(P_i) (index b (q + 1) + k): G = sum w p p^T, h = sum w p and g = sum w p o^T.
Eigen::MatrixXd step_moments(const ShapeSpace& space, const std::vector<WeightedPair>& pairs) {
  const int n = space.dimensions() + 1, block = 3 * n, size = 9 * n + 4;
  RowMajor weighted_p(static_cast<Eigen::Index>(pairs.size()), block);  // rows sqrt(w_i) p_i
  Eigen::MatrixXd weighted_o(static_cast<Eigen::Index>(pairs.size()), 3);
  Eigen::VectorXd root(static_cast<Eigen::Index>(pairs.size()));
  double total = 0.0, target_norms = 0.0;
  Eigen::Vector3d target_sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const WeightedPair& pair = pairs[i];
    const auto r = static_cast<Eigen::Index>(i);
    const Eigen::Index row = 3 * pair.row;
    root[r] = std::sqrt(pair.weight);
    for (int b = 0; b < 3; ++b) {
      weighted_p(r, b * n) =
          root[r] * (space.canonical(pair.row, b) + space.kernel_mean[row + b]);  // u_0 = 1: the rest shape
      for (int k = 1; k < n; ++k) weighted_p(r, b * n + k) = root[r] * space.kernel_basis(row + b, k - 1);
    }
    weighted_o.row(r) = root[r] * pair.target.transpose();
    total += pair.weight;
    target_sum += pair.weight * pair.target;
    target_norms += pair.weight * pair.target.squaredNorm();
  }
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(block, block);           // G, its upper half: Q reads no more
  gram.selfadjointView<Eigen::Upper>().rankUpdate(weighted_p.transpose());
  const Eigen::VectorXd sum_p = weighted_p.transpose() * root;        // h
  const Eigen::MatrixXd cross = weighted_p.transpose() * weighted_o;  // g, one column per component a
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(size, size);
  const int t = 9 * n, constant = 9 * n + 3;
  for (int a = 0; a < 3; ++a) {
    Q.block(a * block, a * block, block, block) = gram;
    Q.block(a * block, t + a, block, 1) = sum_p;
    Q.block(a * block, constant, block, 1) = -cross.col(a);
    Q(t + a, t + a) = total;
    Q(t + a, constant) = -target_sum[a];
  }
  Q(constant, constant) = target_norms;
  return Q.selfadjointView<Eigen::Upper>();
}

// S with S^T S = Q, from a pivoted LDL^T (Q is only positive semi-definite when pairs are few or
// degenerate): Q = P^T L D L^T P, so S = sqrt(D) L^T P.
Eigen::MatrixXd square_root(const Eigen::MatrixXd& Q) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Q);
  const Eigen::VectorXd root_d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
  // Times P as column swaps (the transpositions themselves), not as a product with a dense permutation matrix.
  return (root_d.asDiagonal() * Eigen::MatrixXd(ldlt.matrixU())) * ldlt.transpositionsP().transpose();
}

// d R / d(x, y, z, w) for R = I + 2 w [v]x + 2 [v]x^2 (a unit quaternion's matrix, as Eigen computes it).
std::array<Eigen::Matrix3d, 4> rotation_derivatives(const Eigen::Quaterniond& rotation) {
  const Eigen::Vector3d v = rotation.vec();
  const double w = rotation.w();
  const auto skew = [](const Eigen::Vector3d& e) {
    Eigen::Matrix3d m;
    m << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
    return m;
  };
  std::array<Eigen::Matrix3d, 4> derivatives;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
    derivatives[static_cast<std::size_t>(j)] =
        2.0 * w * skew(e) +
        2.0 * (e * v.transpose() + v * e.transpose() - 2.0 * v[j] * Eigen::Matrix3d::Identity());
  }
  derivatives[3] = 2.0 * skew(v);
  return derivatives;
}

}  // namespace

MomentCost::MomentCost(const ShapeSpace& space, const std::vector<WeightedPair>& pairs, double prior_weight)
    : q_(space.dimensions()), factor_(square_root(step_moments(space, pairs))) {
  inverse_sd_ = (prior_weight / space.variances.array().max(1e-12)).sqrt().matrix();
  set_num_residuals(static_cast<int>(factor_.rows()) + q_);
  *mutable_parameter_block_sizes() = {4, 3, 1, q_};
}

bool MomentCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Eigen::Map<const Eigen::Quaterniond> rotation(parameters[0]);
  const Eigen::Map<const Eigen::Vector3d> translation(parameters[1]);
  const double scale = parameters[2][0];
  const Eigen::Map<const Eigen::VectorXd> latent(parameters[3], q_);
  const int n = q_ + 1, size = 9 * n + 4, t = 9 * n;
  Eigen::VectorXd u(n);
  u << 1.0, latent;
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  // y = [vec(s R u^T) ; t ; 1], the index of (s R)_ab u_k being a 3n + b n + k.
  const auto fill = [&](const Eigen::Matrix3d& M, const Eigen::VectorXd& weights, double* out) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k < n; ++k) out[a * 3 * n + b * n + k] = M(a, b) * weights[k];
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size);
  fill(scale * R, u, y.data());
  y.segment<3>(t) = translation;
  y[size - 1] = 1.0;
  Eigen::Map<Eigen::VectorXd>(residuals, factor_.rows()) = factor_ * y;
  Eigen::Map<Eigen::VectorXd>(residuals + factor_.rows(), q_) = inverse_sd_.cwiseProduct(latent);
  if (!jacobians) return true;
  const Eigen::Index data = factor_.rows();
  // Each parameter's column of dy/dtheta, mapped through S; the prior rows depend on the latent only.
  const auto block = [&](int index, int columns) {
    Eigen::Map<RowMajor> J(jacobians[index], num_residuals(), columns);
    J.setZero();
    return J;
  };
  Eigen::VectorXd column(size);
  if (jacobians[0]) {
    Eigen::Map<RowMajor> J = block(0, 4);
    const auto derivatives = rotation_derivatives(Eigen::Quaterniond(rotation));
    for (int c = 0; c < 4; ++c) {
      column.setZero();
      fill(scale * derivatives[static_cast<std::size_t>(c)], u, column.data());
      J.col(c).head(data) = factor_ * column;
    }
  }
  if (jacobians[1]) {
    Eigen::Map<RowMajor> J = block(1, 3);
    J.topRows(data) = factor_.middleCols(t, 3);
  }
  if (jacobians[2]) {
    Eigen::Map<RowMajor> J = block(2, 1);
    column.setZero();
    fill(R, u, column.data());
    J.col(0).head(data) = factor_ * column;
  }
  if (jacobians[3]) {
    Eigen::Map<RowMajor> J = block(3, q_);
    for (int j = 0; j < q_; ++j) {
      column.setZero();
      fill(scale * R, Eigen::VectorXd::Unit(n, j + 1), column.data());
      J.col(j).head(data) = factor_ * column;
    }
    J.bottomRows(q_) = inverse_sd_.asDiagonal();
  }
  return true;
}

}  // namespace partreg::core::detail
