#include "moment_cost.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

namespace partreg::core::detail {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The Q_a of the header from three moments of the vectors p_m = vec(P_m) (index b (q + 1) + k): G = sum w p
// p^T and h = sum w p, shared by the three components, and g_a = sum w p o_a, which is not:
//   Q_a = [G, h, -g_a; h^T, sum w, -sum w o_a; -g_a^T, -sum w o_a, sum w o_a^2].
// Many pairs share a canonical row (every observed point has one), so the pairs are first summed per row:
// the moments then cost one outer product per row used instead of one per pair.
std::array<Eigen::MatrixXd, 3> step_moments(const ShapeSpace& space, const std::vector<WeightedPair>& pairs) {
  const int n = space.dimensions() + 1, block = 3 * n, t = block, constant = block + 1;
  Eigen::VectorXd row_weight = Eigen::VectorXd::Zero(space.canonical.rows());
  Points row_targets = Points::Zero(space.canonical.rows(), 3);  // sum of w o over the row's pairs
  Eigen::Vector3d target_squares = Eigen::Vector3d::Zero();
  for (const WeightedPair& pair : pairs) {
    row_weight[pair.row] += pair.weight;
    row_targets.row(pair.row) += pair.weight * pair.target.transpose();
    target_squares += pair.weight * pair.target.cwiseAbs2();
  }
  std::vector<int> rows;
  for (Eigen::Index m = 0; m < row_weight.size(); ++m)
    if (row_weight[m] > 0.0) rows.push_back(static_cast<int>(m));
  RowMajor weighted_p(static_cast<Eigen::Index>(rows.size()), block);     // sqrt(W_m) p_m
  Eigen::MatrixXd weighted_o(static_cast<Eigen::Index>(rows.size()), 3);  // (sum w o) / sqrt(W_m)
  Eigen::VectorXd root(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    const int m = rows[i];
    root[r] = std::sqrt(row_weight[m]);
    for (int b = 0; b < 3; ++b) {
      weighted_p(r, b * n) =
          root[r] * (space.canonical(m, b) + space.kernel_mean[3 * m + b]);  // u_0 = 1: rest
      for (int k = 1; k < n; ++k) weighted_p(r, b * n + k) = root[r] * space.kernel_basis(3 * m + b, k - 1);
    }
    weighted_o.row(r) = row_targets.row(m) / root[r];
  }
  Eigen::MatrixXd shared = Eigen::MatrixXd::Zero(block + 2, block + 2);  // the upper half: Q_a reads no more
  shared.topLeftCorner(block, block).selfadjointView<Eigen::Upper>().rankUpdate(weighted_p.transpose());
  shared.col(t).head(block) = weighted_p.transpose() * root;  // h
  shared(t, t) = row_weight.sum();
  const Eigen::MatrixXd cross = weighted_p.transpose() * weighted_o;  // g, one column per component a
  const Eigen::Vector3d target_sum = row_targets.colwise().sum().transpose();
  std::array<Eigen::MatrixXd, 3> Q;
  for (int a = 0; a < 3; ++a) {
    Eigen::MatrixXd upper = shared;
    upper.col(constant).head(block) = -cross.col(a);
    upper(t, constant) = -target_sum[a];
    upper(constant, constant) = target_squares[a];
    Q[static_cast<std::size_t>(a)] = upper.selfadjointView<Eigen::Upper>();
  }
  return Q;
}

// S with S^T S = Q, from a pivoted LDL^T (Q is only positive semi-definite when pairs are few or
// degenerate): Q = P^T L D L^T P, so S = sqrt(D) L^T P.
Eigen::MatrixXd square_root(const Eigen::MatrixXd& Q) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Q);
  const Eigen::VectorXd root_d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
  // Times P as column swaps (the transpositions themselves), not as a product with a dense permutation
  // matrix.
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

// The first 3 (q + 1) entries of z_a (header) for a matrix M in place of s R: M_ab weights_k at index
// b (q + 1) + k, written into `out`.
void component_row(const Eigen::Matrix3d& M, int a, const Eigen::VectorXd& weights,
                   Eigen::Ref<Eigen::VectorXd> out) {
  const auto n = weights.size();
  for (int b = 0; b < 3; ++b) out.segment(b * n, n) = M(a, b) * weights;
}

}  // namespace

MomentCost::MomentCost(const ShapeSpace& space, const std::vector<WeightedPair>& pairs, double prior_weight)
    : q_(space.dimensions()) {
  const std::array<Eigen::MatrixXd, 3> moments = step_moments(space, pairs);
  for (std::size_t a = 0; a < 3; ++a) factors_[a] = square_root(moments[a]);
  inverse_sd_ = (prior_weight / space.variances.array().max(1e-12)).sqrt().matrix();
  set_num_residuals(3 * static_cast<int>(factors_[0].rows()) + q_);
  *mutable_parameter_block_sizes() = {4, 3, 1, q_};
}

bool MomentCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const Eigen::Map<const Eigen::Quaterniond> rotation(parameters[0]);
  const Eigen::Map<const Eigen::Vector3d> translation(parameters[1]);
  const double scale = parameters[2][0];
  const Eigen::Map<const Eigen::VectorXd> latent(parameters[3], q_);
  const int n = q_ + 1, block = 3 * n, width = block + 2, data = 3 * width;
  Eigen::VectorXd u(n);
  u << 1.0, latent;
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  Eigen::VectorXd z(width);
  for (int a = 0; a < 3; ++a) {
    component_row(scale * R, a, u, z.head(block));
    z.tail<2>() << translation[a], 1.0;
    Eigen::Map<Eigen::VectorXd>(residuals + a * width, width) = factors_[static_cast<std::size_t>(a)] * z;
  }
  Eigen::Map<Eigen::VectorXd>(residuals + data, q_) = inverse_sd_.cwiseProduct(latent);
  if (!jacobians) return true;
  // Parameter block i's Jacobian (rows: the three components' residuals, then the prior's).
  const auto jacobian = [&](int i, Eigen::Index columns) {
    return Eigen::Map<RowMajor>(jacobians[i], num_residuals(), columns);
  };
  // Per component a, the derivatives of z_a's first 3 (q + 1) entries by the rotation (4), the scale (1) and
  // the latent (q), mapped through S_a in one product; the translation enters through S_a's next column.
  const auto derivatives = rotation_derivatives(Eigen::Quaterniond(rotation));
  Eigen::MatrixXd dz(block, 5 + q_), through(width, 5 + q_);
  for (int a = 0; a < 3; ++a) {
    const Eigen::MatrixXd& S = factors_[static_cast<std::size_t>(a)];
    for (int c = 0; c < 4; ++c)
      component_row(scale * derivatives[static_cast<std::size_t>(c)], a, u, dz.col(c));
    component_row(R, a, u, dz.col(4));
    for (int j = 0; j < q_; ++j) component_row(scale * R, a, Eigen::VectorXd::Unit(n, j + 1), dz.col(5 + j));
    through.noalias() = S.leftCols(block) * dz;
    const Eigen::Index rows = a * width;
    if (jacobians[0]) jacobian(0, 4).middleRows(rows, width) = through.leftCols(4);
    if (jacobians[1]) {
      jacobian(1, 3).middleRows(rows, width).setZero();
      jacobian(1, 3).col(a).segment(rows, width) = S.col(block);
    }
    if (jacobians[2]) jacobian(2, 1).middleRows(rows, width) = through.col(4);
    if (jacobians[3]) jacobian(3, q_).middleRows(rows, width) = through.rightCols(q_);
  }
  // The prior's rows depend on the latent only.
  constexpr std::array<int, 3> kPoseColumns = {4, 3, 1};  // rotation, translation, scale
  for (int i = 0; i < 3; ++i)
    if (jacobians[i]) jacobian(i, kPoseColumns[static_cast<std::size_t>(i)]).bottomRows(q_).setZero();
  if (jacobians[3]) jacobian(3, q_).bottomRows(q_) = inverse_sd_.asDiagonal();
  return true;
}

}  // namespace partreg::core::detail
