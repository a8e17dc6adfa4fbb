#pragma once
/// \file
/// The Gaussian kernel of CPD and of the shape spaces: g(a, b) = exp(-|a - b|^2 / (2 beta^2)).

#include <Eigen/Core>

#include "partreg/core/types.hpp"

namespace partreg::core {

/// The dense kernel matrix G(a, b), a.rows() x b.rows(). Use for sets of up to a few thousand points.
Eigen::MatrixXd gaussian_kernel(const Points& a, const Points& b, double beta);

/// G(queries, centres) * weights without forming the full matrix: rows are processed in blocks on all
/// cores, so memory stays O(block x centres). With weights = W (M x 3) this is the deformation field
/// v(z) = sum_m G(z, c_m) w_m at every query z (paper Eq. 4).
Eigen::MatrixXd apply_kernel(const Points& queries, const Points& centres,
                             const Eigen::Ref<const Eigen::MatrixXd>& weights, double beta);

/// Jacobian of the field v(z) = sum_m G(z, c_m) w_m at z (3 x 3, d v_i / d z_j). Frames attached to the
/// canonical rotate with I + this Jacobian.
Eigen::Matrix3d kernel_field_jacobian(const Eigen::Vector3d& z, const Points& centres, const Points& weights,
                                      double beta);

}  // namespace partreg::core
