#include "mixture_fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core::detail {
namespace {

constexpr double kMinimumSigma2 = 1e-8;

Points active_rows(const Points& posed, const std::vector<int>& rows) {
  Points active(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) active.row(static_cast<Eigen::Index>(i)) = posed.row(rows[i]);
  return active;
}

// The closest-point residual per axis, observed to centres: where the mixture's variance starts.
double residual_sigma2(const Points& centres, const Points& targets) {
  const KdTree tree(centres);
  std::vector<int> unused;
  Eigen::VectorXd squared;
  tree.nearest_all(targets, unused, squared);
  return std::max(kMinimumSigma2, squared.mean() / 3.0);
}

}  // namespace

std::vector<bool> mixture_centres(const Points& canonical) {
  std::vector<bool> centres(static_cast<std::size_t>(canonical.rows()), false);
  const auto count =
      static_cast<std::size_t>(std::ceil(kMixtureCentreShare * static_cast<double>(canonical.rows())));
  for (int row : farthest_point_indices(canonical, count)) centres[static_cast<std::size_t>(row)] = true;
  return centres;
}

Mixture::Mixture(Points targets, std::vector<bool> centres)
    : targets_(std::move(targets)), centres_(std::move(centres)) {}

std::vector<WeightedPair> Mixture::pairs(const Points& posed, const std::vector<bool>& visible) {
  rows_.clear();
  for (std::size_t m = 0; m < visible.size() && m < centres_.size(); ++m)
    if (visible[m] && centres_[m]) rows_.push_back(static_cast<int>(m));
  if (rows_.empty() || targets_.rows() == 0) return {};
  const Points centres = active_rows(posed, rows_);
  if (sigma2_ <= 0.0) sigma2_ = residual_sigma2(centres, targets_);
  // No outlier term: the strays are already out, and a uniform term lets EM shrink the variance by calling
  // the noise's tail outliers (the variance then falls below the noise and the fit follows it).
  EStepSettings settings;
  settings.outlier_weight = 0.0;
  settings.threads = 1;  // parts and hypotheses run in parallel above
  expectation_ = expectation(centres, targets_, sigma2_, settings);
  std::vector<WeightedPair> pairs;
  if (!(expectation_.Np > 0.0)) return pairs;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const double mass = expectation_.P1(static_cast<Eigen::Index>(i));
    if (mass <= 1e-12 * expectation_.Np) continue;
    pairs.push_back({rows_[i], expectation_.PX.row(static_cast<Eigen::Index>(i)).transpose() / mass,
                     mass / expectation_.Np});
  }
  return pairs;
}

bool Mixture::update(const Points& posed, double tolerance) {
  if (rows_.empty() || !(expectation_.Np > 0.0)) return true;
  const double next = std::max(kMinimumSigma2, nonrigid_variance(expectation_, targets_, active_rows(posed, rows_)));
  const bool settled = std::abs(next - sigma2_) <= tolerance * sigma2_;
  sigma2_ = next;
  return settled;
}

double noisy_prior_weight(double sigma, const ObjectiveSettings& objective) {
  if (!(objective.mixture_noise > 0.0)) return objective.prior_weight;
  const double ratio = sigma / objective.mixture_noise;
  return objective.prior_weight * std::max(1.0, ratio * ratio);
}

double finish_in_mixture(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                       const Points& targets, const std::vector<bool>& centres,
                       const RegistrationSettings& settings, SpaceSolution& solution) {
  const auto start = std::chrono::steady_clock::now();
  const double before = solution.seconds;
  const auto elapsed = [&] {
    return before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  Mixture mixture(targets, centres);
  for (int step = 0; step < settings.convergence.outer_iterations; ++step) {
    const Points posed = solution.pose.apply(space.deformed(solution.latent));
    std::vector<WeightedPair> pairs =
        mixture.pairs(posed, visible_rows(posed, surface, solution.pose, observation.viewpoint));
    if (pairs.empty()) break;
    ceres::Problem problem;
    double* rotation = solution.pose.rotation.coeffs().data();
    double* scale = &solution.pose.scale;
    const double prior_weight = noisy_prior_weight(mixture.sigma(), settings.objective);
    problem.AddResidualBlock(new MomentCost(space, std::move(pairs), prior_weight), nullptr, rotation,
                             solution.pose.translation.data(), scale, solution.latent.data());
    constrain_pose(problem, rotation, scale, settings);
    solution.cost = solve_inner(problem, settings);
    solution.steps.emplace_back(solution.latent, solution.pose);
    solution.step_costs.push_back(solution.cost);
    solution.step_seconds.push_back(elapsed());
    solution.seconds = elapsed();
    ++solution.iterations;
    if (mixture.update(solution.pose.apply(space.deformed(solution.latent)), settings.convergence.tolerance)) break;
  }
  return mixture.sigma();
}

}  // namespace partreg::core::detail
