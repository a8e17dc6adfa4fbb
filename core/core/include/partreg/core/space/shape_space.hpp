#pragma once
/// \file
/// A shape space: a low-dimensional linear space of CPD deformation fields of one canonical point set
/// (paper, section 3.1). Training registers the canonical C to each instance, T_i = C + G W_i; PCA-EM over
/// the vectorised W_i gives the space. All lengths are in the category's normalised units.
///
/// Vectorisation: a W (M x 3, one row per canonical point) becomes a 3M vector row by row,
/// (w_1x, w_1y, w_1z, w_2x, ...), which is exactly the memory of a row-major Points.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core {

/// The learned space of one canonical point set (the whole object, or one part).
struct ShapeSpace {
  std::string name;  ///< "holistic", or the part's name
  std::vector<int>
      point_indices;      ///< rows of the holistic canonical this space deforms (all rows for holistic)
  Points canonical;       ///< C: those canonical points (normalised units)
  double beta = 0.0;      ///< width of the Gaussian kernel G(C, C) used in training (normalised units)
  Eigen::VectorXd mean;   ///< mean of the vectorised training W (3M)
  Eigen::MatrixXd basis;  ///< 3M x q weight fields W of the principal directions (G * basis = kernel_basis)
  Eigen::VectorXd variances;    ///< variance of the training latents along each direction (descending)
  double total_variance = 0.0;  ///< total variance of the training displacements (normalised length squared)
  Eigen::VectorXd kernel_mean;  ///< vec(G * mean W): the canonical's mean displacement (3M, normalised units)
  /// Column k is vec(G * basis_k): displacement per unit of latent k (3M x q). Orthonormal, ordered by
  /// variance: PCA-EM runs on the displacements, where shape lives (see learn_shape_space).
  Eigen::MatrixXd kernel_basis;
  /// Row i is the latent of training instance i (K x q, training order): kernel_basis^T (vec D_i -
  /// kernel_mean), the coordinates PCA gave its displacement. Divide by sqrt(variances) for standard
  /// deviations.
  Eigen::MatrixXd training_latents;

  int dimensions() const { return static_cast<int>(basis.cols()); }
  int point_count() const { return static_cast<int>(canonical.rows()); }
  /// Share of the total training variance that each dimension explains (q values, in [0, 1]).
  Eigen::VectorXd explained_fraction() const;
  /// W(x) = mean + basis x, as an M x 3 matrix of kernel weights.
  Points weights(const Eigen::VectorXd& latent) const;
  /// C + G W(x): the deformed canonical, computed from kernel_mean/kernel_basis (no M x M kernel).
  Points deformed(const Eigen::VectorXd& latent) const;
  /// Least-squares latent of a weight field.
  Eigen::VectorXd project_weights(const Points& weights) const;
  /// Latent of a displacement field D (M x 3, D = G W): kernel_basis^T (vec D - kernel_mean).
  Eigen::VectorXd project_displacement(const Points& displacement) const;
};

/// PCA-EM (Roweis 1998) settings. The EM iterations find the principal subspace without forming the
/// 3M x 3M covariance; an eigen-decomposition inside that subspace then orders and orthonormalises it.
struct PcaEmSettings {
  int dimensions = 5;        ///< q, the latent dimension; clamped to K - 1 for K training fields
  int max_iterations = 500;  ///< EM iteration cap
  double tolerance = 1e-10;  ///< stop when the subspace moves less than this (1 - |cos| of principal angles)
  std::uint64_t seed = 1;    ///< seed of the random initial subspace
};

/// Principal subspace of the columns of `centred` (D x K, mean already removed) by PCA-EM.
/// Returns the D x q orthonormal basis ordered by variance and writes the variances (divided by K - 1).
Eigen::MatrixXd pca_em(const Eigen::MatrixXd& centred, const PcaEmSettings& settings,
                       Eigen::VectorXd& variances);

/// Learns the space of the given training weight fields (each M x 3 for the canonical `canonical`).
/// Throws InputError for fewer than two fields or fields whose size does not match the canonical.
ShapeSpace learn_shape_space(const std::string& name, const std::vector<int>& point_indices,
                             const Points& canonical, double beta,
                             const std::vector<Points>& training_weights, const PcaEmSettings& settings = {});

}  // namespace partreg::core
