#include "partreg/core/shape_space.hpp"

#include <Eigen/Dense>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/gaussian_kernel.hpp"

namespace partreg::core {
namespace {

Eigen::Map<const Points> as_points(const Eigen::VectorXd& vectorised) {
  return {vectorised.data(), vectorised.size() / 3, 3};
}

Eigen::MatrixXd orthonormal_columns(const Eigen::MatrixXd& matrix) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(matrix);
  return qr.householderQ() * Eigen::MatrixXd::Identity(matrix.rows(), matrix.cols());
}

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd matrix(rows, cols);
  for (Eigen::Index i = 0; i < matrix.size(); ++i) matrix.data()[i] = normal(generator);
  return matrix;
}

// 0 when two orthonormal bases span the same subspace, up to q when they are orthogonal.
double subspace_distance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return static_cast<double>(a.cols()) - (a.transpose() * b).squaredNorm();
}

}  // namespace

Eigen::MatrixXd pca_em(const Eigen::MatrixXd& centred, const PcaEmSettings& settings, Eigen::VectorXd& variances) {
  const Eigen::Index samples = centred.cols();
  if (samples < 2) throw InputError("PCA-EM needs at least two training deformations");
  if (settings.dimensions < 1) throw UsageError("the latent dimension must be at least 1");
  const Eigen::Index q = std::min<Eigen::Index>({settings.dimensions, samples - 1, centred.rows()});

  // Roweis' EM for PCA: alternate latent estimates X and loadings C; each step costs O(D K q).
  Eigen::MatrixXd loadings = random_matrix(centred.rows(), q, settings.seed);
  Eigen::MatrixXd subspace = orthonormal_columns(loadings);
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    const Eigen::MatrixXd latent =
        (loadings.transpose() * loadings).completeOrthogonalDecomposition().solve(loadings.transpose() * centred);
    loadings = centred * latent.transpose() *
               (latent * latent.transpose()).completeOrthogonalDecomposition().pseudoInverse();
    if (!loadings.allFinite() || loadings.norm() == 0.0) break;  // data of lower rank than q: keep what we have
    Eigen::MatrixXd next = orthonormal_columns(loadings);
    const bool converged = subspace_distance(subspace, next) < settings.tolerance;
    subspace = std::move(next);
    if (converged) break;
  }

  // EM gives the subspace, not its axes: diagonalise the covariance inside it to order and rotate them.
  const Eigen::MatrixXd coordinates = subspace.transpose() * centred;
  const Eigen::MatrixXd covariance = coordinates * coordinates.transpose() / static_cast<double>(samples - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  variances = eigen.eigenvalues().reverse().cwiseMax(0.0);
  return subspace * eigen.eigenvectors().rowwise().reverse();
}

ShapeSpace learn_shape_space(const std::string& name, const std::vector<int>& point_indices, const Points& canonical,
                             double beta, const std::vector<Points>& training_weights,
                             const PcaEmSettings& settings) {
  if (training_weights.size() < 2)
    throw InputError("shape space '" + name + "' needs at least two training deformations, got " +
                     std::to_string(training_weights.size()));
  const Eigen::Index m = canonical.rows();
  Eigen::MatrixXd data(3 * m, static_cast<Eigen::Index>(training_weights.size()));
  for (std::size_t i = 0; i < training_weights.size(); ++i) {
    if (training_weights[i].rows() != m)
      throw InputError("shape space '" + name + "': a training deformation has " +
                       std::to_string(training_weights[i].rows()) + " rows for " + std::to_string(m) +
                       " canonical points");
    data.col(static_cast<Eigen::Index>(i)) = Eigen::Map<const Eigen::VectorXd>(training_weights[i].data(), 3 * m);
  }

  ShapeSpace space;
  space.name = name;
  space.point_indices = point_indices;
  space.canonical = canonical;
  space.beta = beta;
  space.mean = data.rowwise().mean();
  const Eigen::MatrixXd centred = data.colwise() - space.mean;
  space.total_variance = centred.squaredNorm() / static_cast<double>(data.cols() - 1);
  space.basis = pca_em(centred, settings, space.variances);

  // G times the mean and every basis field, once, so that inference never builds G again.
  const Eigen::Index q = space.basis.cols();
  Eigen::MatrixXd fields(m, 3 * (q + 1));
  fields.leftCols(3) = as_points(space.mean);
  for (Eigen::Index k = 0; k < q; ++k)
    fields.middleCols(3 * (k + 1), 3) = as_points(Eigen::VectorXd(space.basis.col(k)));
  const Eigen::MatrixXd displaced = apply_kernel(canonical, canonical, fields, beta);
  auto vectorise = [m](const Eigen::MatrixXd& block) {
    Eigen::VectorXd out(3 * m);
    Eigen::Map<Points>(out.data(), m, 3) = block;
    return out;
  };
  space.kernel_mean = vectorise(displaced.leftCols(3));
  space.kernel_basis.resize(3 * m, q);
  for (Eigen::Index k = 0; k < q; ++k) space.kernel_basis.col(k) = vectorise(displaced.middleCols(3 * (k + 1), 3));
  return space;
}

Eigen::VectorXd ShapeSpace::explained_fraction() const {
  if (total_variance <= 0.0) return Eigen::VectorXd::Zero(variances.size());
  return variances / total_variance;
}

Points ShapeSpace::weights(const Eigen::VectorXd& latent) const {
  const Eigen::VectorXd field = mean + basis * latent;
  return as_points(field);
}

Points ShapeSpace::deformed(const Eigen::VectorXd& latent) const {
  const Eigen::VectorXd displacement = kernel_mean + kernel_basis * latent;
  return canonical + as_points(displacement);
}

Eigen::VectorXd ShapeSpace::project_weights(const Points& weights) const {
  const Eigen::Map<const Eigen::VectorXd> field(weights.data(), weights.size());
  return basis.transpose() * (field - mean);
}

Eigen::VectorXd ShapeSpace::project_displacement(const Points& displacement) const {
  const Eigen::Map<const Eigen::VectorXd> field(displacement.data(), displacement.size());
  return kernel_basis.colPivHouseholderQr().solve(field - kernel_mean);
}

}  // namespace partreg::core
