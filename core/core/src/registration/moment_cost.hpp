#pragma once
// The cost of one outer registration step in constant time per evaluation (internal to partreg_core).
//
// With the correspondences and their weights fixed for the step, the step minimises
//   E = sum_i w_i |s R (a_i + K_i x) + t - o_i|^2        (a_i: canonical + mean displacement, K_i: 3 x q)
// The a-th component of a residual is linear in z_a = [vec(row a of s R times [1; x]^T) ; t_a ; 1]
// (3 (q + 1) + 2 numbers): it is sum_bk (s R)_ab u_k P_i(b, k) + t_a - o_ia with P_i = [a_i K_i], u = [1; x].
// So E = sum_a z_a^T Q_a z_a, each Q_a built once per step from moments of the pairs (the three share all
// but their last column), and the factors S_a of Q_a (S_a^T S_a = Q_a) give residuals S_a z_a whose squared
// norm is E exactly. Ceres then works on 3 (3 (q + 1) + 2) residuals instead of three per pair: the same
// Gauss-Newton steps in exact arithmetic, at a cost that no longer grows with the number of pairs.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "partreg/core/space/shape_space.hpp"

namespace partreg::core::detail {

/// One weighted correspondence: canonical row `row` of the space to the observed point `target`.
struct WeightedPair {
  int row;
  Eigen::Vector3d target;  ///< normalised observed frame
  double weight;           ///< robust (IRLS) weight times the direction's 1 / count
};

/// Parameter blocks: rotation (Eigen quaternion coefficients x, y, z, w), translation (3), scale (1), latent
/// (q). Residuals: per component a, the factor of its moments (3 (q + 1) + 2 each), then the prior
/// sqrt(lambda) x_k / sd_k.
class MomentCost : public ceres::CostFunction {
 public:
  MomentCost(const ShapeSpace& space, const std::vector<WeightedPair>& pairs, double prior_weight);

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  int q_;
  std::array<Eigen::MatrixXd, 3> factors_;  // S_a, with S_a^T S_a = Q_a
  Eigen::VectorXd inverse_sd_;
};

}  // namespace partreg::core::detail
