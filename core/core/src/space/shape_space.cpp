#include "partreg/core/space/shape_space.hpp"

#include <Eigen/Dense>
#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"

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

// G(C, C) times each column of `fields` (3M x K, vectorised weight fields), vectorised the same way.
Eigen::MatrixXd kernel_times_fields(const Points& canonical, const Eigen::MatrixXd& fields, double beta) {
  const Eigen::Index m = canonical.rows(), k = fields.cols();
  Eigen::MatrixXd stacked(m, 3 * k);
  for (Eigen::Index i = 0; i < k; ++i)
    stacked.middleCols(3 * i, 3) = as_points(Eigen::VectorXd(fields.col(i)));
  const Eigen::MatrixXd moved = apply_kernel(canonical, canonical, stacked, beta);
  Eigen::MatrixXd out(3 * m, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    Eigen::VectorXd column(3 * m);
    Eigen::Map<Points>(column.data(), m, 3) = moved.middleCols(3 * i, 3);
    out.col(i) = column;
  }
  return out;
}

}  // namespace

Eigen::MatrixXd pca_em(const Eigen::MatrixXd& centred, const PcaEmSettings& settings,
                       Eigen::VectorXd& variances) {
  const Eigen::Index samples = centred.cols();
  if (samples < 2) throw InputError("PCA-EM needs at least two training deformations");
  if (settings.dimensions < 1) throw UsageError("the latent dimension must be at least 1");
  const Eigen::Index q = std::min<Eigen::Index>({settings.dimensions, samples - 1, centred.rows()});

  // Roweis' EM for PCA: alternate latent estimates X and loadings C; each step costs O(D K q).
  Eigen::MatrixXd loadings = random_matrix(centred.rows(), q, settings.seed);
  Eigen::MatrixXd subspace = orthonormal_columns(loadings);
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    const Eigen::MatrixXd latent = (loadings.transpose() * loadings)
                                       .completeOrthogonalDecomposition()
                                       .solve(loadings.transpose() * centred);
    loadings = centred * latent.transpose() *
               (latent * latent.transpose()).completeOrthogonalDecomposition().pseudoInverse();
    if (!loadings.allFinite() || loadings.norm() == 0.0)
      break;  // data of lower rank than q: keep what we have
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

ShapeSpace learn_shape_space(const std::string& name, const std::vector<int>& point_indices,
                             const Points& canonical, double beta,
                             const std::vector<Points>& training_weights, const PcaEmSettings& settings) {
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
    data.col(static_cast<Eigen::Index>(i)) =
        Eigen::Map<const Eigen::VectorXd>(training_weights[i].data(), 3 * m);
  }

  // PCA runs on the displacements D_i = G W_i, which are what a shape is; W itself has large components
  // along directions G nearly annihilates (the kernel is smooth), which would dominate a PCA of W without
  // changing any shape. Each principal displacement is a combination D_c a of the centred training
  // displacements, and the same combination W_c a of the fields is its W: G (W_c a) = D_c a exactly.
  const Eigen::MatrixXd displacements = kernel_times_fields(canonical, data, beta);
  ShapeSpace space;
  space.name = name;
  space.point_indices = point_indices;
  space.canonical = canonical;
  space.beta = beta;
  space.mean = data.rowwise().mean();
  space.kernel_mean = displacements.rowwise().mean();
  const Eigen::MatrixXd centred_fields = data.colwise() - space.mean;
  const Eigen::MatrixXd centred = displacements.colwise() - space.kernel_mean;
  space.total_variance = centred.squaredNorm() / static_cast<double>(data.cols() - 1);
  space.kernel_basis = pca_em(centred, settings, space.variances);
  const Eigen::MatrixXd combination =
      centred.completeOrthogonalDecomposition().solve(space.kernel_basis);  // K x q: D_c a = basis column
  space.basis = centred_fields * combination;
  // Kept so the app can show where each training instance lies in the space (and set the sliders there).
  space.training_latents = (space.kernel_basis.transpose() * centred).transpose();
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
  return basis.colPivHouseholderQr().solve(field - mean);
}

Eigen::VectorXd ShapeSpace::project_displacement(const Points& displacement) const {
  const Eigen::Map<const Eigen::VectorXd> field(displacement.data(), displacement.size());
  return kernel_basis.transpose() * (field - kernel_mean);  // orthonormal columns
}

}  // namespace partreg::core
