// Non-rigid CPD (Myronenko & Song 2010, Fig. 4, and section 6 for the low-rank kernel).
#include <Eigen/Dense>
#include <cmath>

#include "cpd_em.hpp"
#include "options/option_builders.hpp"
#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core {
namespace {

// G ~ U U^T from a Nystrom approximation on farthest-point landmarks L (rows of the source):
// U = G(Y, L) V_k Lambda_k^(-1/2) with the eigenpairs of G(L, L) above a relative threshold. Memory O(M k);
// no M x M matrix is formed. The landmark weights W_L = V_k Lambda_k^(-1/2) Z turn a low-rank displacement
// U Z back into an exact kernel field G(Y, L) W_L, so the result keeps the paper's form Y + G W.
struct LowRankKernel {
  std::vector<int> landmarks;  ///< rows of the source used as kernel centres
  Eigen::MatrixXd factor;      ///< U (M x k)
  Eigen::MatrixXd to_weights;  ///< V_k Lambda_k^(-1/2) (L x k): landmark weights of a unit column of Z
};

LowRankKernel low_rank_kernel(const Points& source, double beta, int kernel_rank) {
  const auto landmarks_wanted = static_cast<Eigen::Index>(std::ceil(30.0 / (beta * beta)));
  const auto count = std::min<Eigen::Index>(source.rows(), std::max<Eigen::Index>(200, landmarks_wanted));
  LowRankKernel kernel;
  kernel.landmarks = farthest_point_indices(source, static_cast<std::size_t>(count));
  const Points landmarks = select_rows(source, kernel.landmarks);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gaussian_kernel(landmarks, landmarks, beta));
  const Eigen::VectorXd values = eigen.eigenvalues().reverse();
  Eigen::Index rank = 0;
  while (rank < values.size() && values[rank] > 1e-7 * values[0]) ++rank;  // beyond this, round-off
  if (kernel_rank > 0) rank = std::min<Eigen::Index>(rank, kernel_rank);
  kernel.to_weights = eigen.eigenvectors().rowwise().reverse().leftCols(rank) *
                      values.head(rank).cwiseSqrt().cwiseInverse().asDiagonal();
  kernel.factor = apply_kernel(source, landmarks, kernel.to_weights, beta);
  return kernel;
}

// The fast M-step for source rows `source` with kernel factor rows U: with G = U U^T only Z = U^T W moves
// the points, (lambda sigma2 I + U^T d(P1) U) Z = U^T (P X - d(P1) Y) (Woodbury, solved for Z). It stays well
// conditioned as sigma2 shrinks, unlike W itself. Returns Z (k x 3); the points move to source + U Z.
Eigen::MatrixXd low_rank_m_step(const detail::Expectation& e, const Eigen::MatrixXd& U, const Points& source,
                                double regulariser) {
  Eigen::MatrixXd system = U.transpose() * e.P1.asDiagonal() * U;
  system.diagonal().array() += regulariser;
  return system.ldlt().solve(U.transpose() * (e.PX - e.P1.asDiagonal() * source));
}

void check_settings(const NonrigidCpdSettings& s) {
  // A kernel 10 diagonals wide is already rigid; 1e308 or infinity would only overflow G to NaN.
  if (!(s.beta >= 1e-6 && s.beta <= 10.0))
    throw UsageError("CPD beta must be in [1e-6, 10] (normalised length), not " + detail::text_of(s.beta));
  if (!(s.lambda >= 1e-6 && s.lambda <= 1e6))
    throw UsageError("CPD lambda must be in [1e-6, 1e6], not " + detail::text_of(s.lambda));
  if (s.kernel_rank < 0) throw UsageError("the kernel rank must be 0 (automatic) or positive");
  detail::check_fast_e_step(s.truncation, s.cell_size);
  detail::check_coarse_points(s.coarse_points);
  detail::check_cpd_common(s.outlier_weight, s.tolerance, s.max_iterations);
}

// G(z, source) W over the source rows whose weight is not zero only: the fast solver's field has weights on
// its landmarks alone, so this costs z x landmarks instead of z x M.
Points field_at(const Points& z, const Points& source, const Points& weights, double beta) {
  std::vector<int> rows;
  for (Eigen::Index m = 0; m < weights.rows(); ++m)
    if (weights.row(m).squaredNorm() > 0.0) rows.push_back(static_cast<int>(m));
  if (rows.empty()) return Points::Zero(z.rows(), 3);
  return apply_kernel(z, select_rows(source, rows), select_rows(weights, rows), beta);
}

bool use_fast_solver(const NonrigidCpdSettings& s, Eigen::Index source_points) {
  if (s.solver == NonrigidCpdSettings::Solver::automatic) return source_points > 300;
  return s.solver == NonrigidCpdSettings::Solver::fast;
}

}  // namespace

Points NonrigidCpdResult::displacement_at(const Points& z) const {
  const Points working = normalization.apply(z);
  const Points working_source = normalization.apply(source);
  return field_at(working, working_source, weights, beta) * normalization.scale;
}

NonrigidCpdResult register_nonrigid(const Points& source_in, const Points& target_in,
                                    const NonrigidCpdSettings& settings) {
  const auto start = detail::now_nanoseconds();
  check_settings(settings);
  detail::check_cpd_points(source_in, "source");
  detail::check_cpd_points(target_in, "target");
  NonrigidCpdResult result;
  result.normalization = settings.normalize ? Normalization::fit(target_in) : Normalization{};
  const Points source = result.normalization.apply(source_in), target = result.normalization.apply(target_in);
  const Eigen::Index m = source.rows();
  const bool fast = use_fast_solver(settings, m);

  Eigen::MatrixXd kernel;  // exact solver: G (M x M)
  LowRankKernel low_rank;  // fast solver: G ~ U U^T
  if (fast)
    low_rank = low_rank_kernel(source, settings.beta, settings.kernel_rank);
  else
    kernel = gaussian_kernel(source, source, settings.beta);
  Eigen::MatrixXd latent;  // fast solver: Z (k x 3), the displacement is U Z

  Points weights = Points::Zero(m, 3);
  Points moved = source;
  detail::EmControl control;
  control.e_step.outlier_weight = settings.outlier_weight;
  control.e_step.threads = settings.threads;
  control.e_step.exact = !fast || settings.exact_e_step;
  // No SQUAREM here (docs/cpd.md): jumps of the field changed which fit training's CPDs settled on, and the
  // registration tests on the held-out mug moved with them.
  control.accelerate = false;
  control.e_step.truncation = settings.truncation;
  control.e_step.cell_size = settings.cell_size;
  control.tolerance = settings.tolerance;
  control.max_iterations = settings.max_iterations;
  control.progress = settings.progress;
  // Coarse to fine: each stage starts from the field the one before found (Z: the same landmarks serve
  // every stage). The data term sums over the target, the regulariser does not: lambda scaled by the
  // stage's share of the target gives a subset the full problem's balance.
  int iterations = 0;
  control = detail::run_coarse_stages(
      fast ? detail::coarse_stages(m, target.rows(), settings.coarse_points, settings.exact_e_step)
           : std::vector<detail::CoarseStage>{},
      control,
      [&](const detail::CoarseStage& rows, const detail::EmControl& stage_control) {
        const Points stage_source = select_rows(source, rows.source),
                     stage_target = select_rows(target, rows.target);
        const Eigen::MatrixXd stage_factor = low_rank.factor(rows.source, Eigen::all);
        const double stage_lambda =
            settings.lambda * static_cast<double>(rows.target.size()) / static_cast<double>(target.rows());
        Points stage_moved = latent.size() > 0 ? Points(stage_source + stage_factor * latent) : stage_source;
        return detail::run_em(
            stage_target, stage_moved, stage_control, [&](const detail::Expectation& e, double sigma2) {
              latent = low_rank_m_step(e, stage_factor, stage_source, stage_lambda * sigma2);
              stage_moved = stage_source + stage_factor * latent;
              return detail::nonrigid_variance(e, stage_target, stage_moved);
            });
      },
      iterations);
  if (latent.size() > 0) moved = source + low_rank.factor * latent;
  const auto outcome =
      detail::run_em(target, moved, control, [&](const detail::Expectation& e, double sigma2) {
        const double regulariser = settings.lambda * sigma2;
        if (fast) {
          latent = low_rank_m_step(e, low_rank.factor, source, regulariser);
          moved = source + low_rank.factor * latent;
        } else {
          // (G + lambda sigma2 d(P1)^-1) W = d(P1)^-1 PX - Y
          Eigen::MatrixXd system = e.P1.asDiagonal() * kernel;
          system.diagonal().array() += regulariser;
          weights = system.partialPivLu().solve(e.PX - e.P1.asDiagonal() * source);
          moved = source + kernel * weights;
        }
        return detail::nonrigid_variance(e, target, moved);
      });
  // The fast solver's field is exactly G(Y, L) W_L: W is zero outside the landmark rows. The moved points
  // are recomputed from W so that apply(source) reproduces them whatever solver found it.
  if (fast && latent.size() > 0) {
    const Eigen::MatrixXd landmark_weights = low_rank.to_weights * latent;
    for (std::size_t l = 0; l < low_rank.landmarks.size(); ++l)
      weights.row(low_rank.landmarks[l]) = landmark_weights.row(static_cast<Eigen::Index>(l));
  }
  result.weights = weights;
  result.beta = settings.beta;
  result.source = source_in;
  result.moved = result.normalization.undo(source + field_at(source, source, weights, settings.beta));
  result.sigma2 = outcome.sigma2;
  result.iterations = iterations + outcome.iterations;
  result.stop_reason = outcome.stop_reason;
  result.kernel_rank = fast ? static_cast<int>(low_rank.factor.cols()) : 0;
  result.seconds = detail::seconds_since(start);
  return result;
}

}  // namespace partreg::core
