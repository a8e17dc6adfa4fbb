#pragma once
// The cost of one outer registration step in constant time per evaluation (internal to partreg_core).
//
// With the correspondences and their weights fixed for the step, the step minimises
//   E = sum_i w_i |s R (a_i + K_i x) + t - o_i|^2        (a_i: canonical + mean displacement, K_i: 3 x q)
// Every residual is linear in y = [vec(s R [1; x]^T) ; t ; 1] (9 (q + 1) + 4 numbers): the a-th component of
// s R P_i u (P_i = [a_i K_i], u = [1; x]) is sum_bk (s R)_ab u_k P_i(b, k). So E = y^T Q y with Q built once
// per step from moments of the pairs, and the factor S of Q (S^T S = Q) gives residuals S y whose squared
// norm is E exactly. Ceres then works on 9 (q + 1) + 4 residuals instead of three per pair: the same
// Gauss-Newton steps in exact arithmetic, at a cost that no longer grows with the number of pairs.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

#include "partreg/core/shape_space.hpp"

namespace partreg::core::detail {

/// One weighted correspondence: canonical row `row` of the space to the observed point `target`.
struct WeightedPair {
  int row;
  Eigen::Vector3d target;  ///< normalised observed frame
  double weight;           ///< robust (IRLS) weight times the direction's 1 / count
};

/// Parameter blocks: rotation (Eigen quaternion coefficients x, y, z, w), translation (3), scale (1), latent
/// (q). Residuals: the factor of the step's moments (9 (q + 1) + 4), then the prior sqrt(lambda) x_k / sd_k.
class MomentCost : public ceres::CostFunction {
 public:
  MomentCost(const ShapeSpace& space, const std::vector<WeightedPair>& pairs, double prior_weight);

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  int q_;
  Eigen::MatrixXd factor_;  // S, with S^T S = Q
  Eigen::VectorXd inverse_sd_;
};

}  // namespace partreg::core::detail
