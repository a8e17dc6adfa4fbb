#include "space_solver.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>

#include "moment_cost.hpp"
#include "partreg/core/errors.hpp"

namespace partreg::core::detail {
namespace {

Points deformed_points(const ShapeSpace& space, const Eigen::VectorXd& latent) {
  return space.deformed(latent);
}

void trim(std::vector<Pair>& pairs, double fraction) {
  if (pairs.size() < 10 || fraction <= 0.0) return;
  const auto keep = static_cast<std::size_t>(static_cast<double>(pairs.size()) * (1.0 - fraction));
  std::nth_element(pairs.begin(), pairs.begin() + static_cast<long>(keep), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.squared_distance < b.squared_distance; });
  pairs.resize(keep);
}

}  // namespace

bool is_stray(const Observation& observation, Eigen::Index n, double squared_distance) {
  return !observation.alone.empty() && observation.alone[static_cast<std::size_t>(n)] &&
         squared_distance > kStrayReach * kStrayReach;
}

Correspondences correspond(const Points& posed, const std::vector<bool>& visible,
                           const Observation& observation, const RegistrationSettings& settings,
                           CorrespondenceHints* hints) {
  Correspondences result;
  std::vector<int> active;
  for (std::size_t m = 0; m < visible.size(); ++m)
    if (visible[m]) active.push_back(static_cast<int>(m));
  if (active.empty()) return result;
  CorrespondenceHints none;
  CorrespondenceHints& last = hints ? *hints : none;
  last.observed_of_row.resize(static_cast<std::size_t>(posed.rows()), -1);
  last.row_of_observed.resize(static_cast<std::size_t>(observation.points.rows()), -1);
  if (settings.objective.direction != Direction::observed_to_canonical) {
    for (int m : active) {
      int& hint = last.observed_of_row[static_cast<std::size_t>(m)];
      const Eigen::Vector3d query = posed.row(m).transpose();
      const auto [n, squared] =
          hint >= 0 ? observation.tree->nearest(query, hint) : observation.tree->nearest(query);
      hint = n;
      result.from_canonical.push_back({m, observation.points.row(n).transpose(), squared});
    }
  }
  if (settings.objective.direction != Direction::canonical_to_observed) {
    Points active_points(static_cast<Eigen::Index>(active.size()), 3);
    std::vector<int> active_of_row(static_cast<std::size_t>(posed.rows()), -1);
    for (std::size_t i = 0; i < active.size(); ++i) {
      active_points.row(static_cast<Eigen::Index>(i)) = posed.row(active[i]);
      active_of_row[static_cast<std::size_t>(active[i])] = static_cast<int>(i);
    }
    const KdTree tree(std::move(active_points));
    for (Eigen::Index n = 0; n < observation.points.rows(); ++n) {
      int& row = last.row_of_observed[static_cast<std::size_t>(n)];
      const int hint = row >= 0 ? active_of_row[static_cast<std::size_t>(row)] : -1;
      const Eigen::Vector3d query = observation.points.row(n).transpose();
      const auto [i, squared] = hint >= 0 ? tree.nearest(query, hint) : tree.nearest(query);
      row = active[static_cast<std::size_t>(i)];
      if (is_stray(observation, n, squared)) continue;
      result.from_observed.push_back({row, query, squared});
    }
  }
  if (settings.objective.loss == Loss::trimmed) {
    trim(result.from_canonical, settings.objective.trim_fraction);
    trim(result.from_observed, settings.objective.trim_fraction);
  }
  return result;
}

// Iteratively reweighted least squares: each step weighs its correspondences by the robust loss at their
// current distance (Huber or Cauchy), and every direction's term by 1 / count so both count equally.
std::vector<WeightedPair> weighted_pairs(const Correspondences& pairs, const RegistrationSettings& settings) {
  std::vector<WeightedPair> all;
  for (const std::vector<Pair>* set : {&pairs.from_canonical, &pairs.from_observed}) {
    const double share = set->empty() ? 0.0 : 1.0 / static_cast<double>(set->size());
    for (const Pair& pair : *set) {
      const double distance = std::sqrt(pair.squared_distance), c = settings.objective.loss_scale;
      double robust = 1.0;
      if (settings.objective.loss == Loss::huber && distance > c) robust = c / distance;
      if (settings.objective.loss == Loss::cauchy) robust = 1.0 / (1.0 + pair.squared_distance / (c * c));
      all.push_back({pair.row, pair.target, share * robust});
    }
  }
  return all;
}

// Which canonical points face the viewpoint under the current pose (all of them without a viewpoint).
std::vector<bool> facing_rows(const Points& posed, const ViewSurface& surface, const Pose& pose,
                              const std::optional<Eigen::Vector3d>& viewpoint) {
  std::vector<bool> facing(static_cast<std::size_t>(posed.rows()), true);
  if (!viewpoint || surface.normals.rows() != posed.rows()) return facing;
  const Eigen::Matrix3d R = pose.rotation.toRotationMatrix();
  for (Eigen::Index m = 0; m < posed.rows(); ++m)
    facing[static_cast<std::size_t>(m)] =
        (R * surface.normals.row(m).transpose()).dot(*viewpoint - posed.row(m).transpose()) > 0.0;
  return facing;
}

std::vector<bool> visible_rows(const Points& posed, const ViewSurface& surface, const Pose& pose,
                               const std::optional<Eigen::Vector3d>& viewpoint) {
  std::vector<bool> facing = facing_rows(posed, surface, pose, viewpoint);
  if (!viewpoint || surface.normals.rows() != posed.rows()) return facing;
  return seen_rows(posed, facing, *viewpoint, surface.spacing);
}

Points Pose::apply(const Points& points) const {
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  return ((scale * points * R.transpose()).rowwise() + translation.transpose());
}

void constrain_pose(ceres::Problem& problem, double* rotation, double* scale,
                    const RegistrationSettings& settings) {
  problem.SetManifold(rotation, new ceres::EigenQuaternionManifold);
  if (!settings.objective.estimate_scale)
    problem.SetParameterBlockConstant(scale);
  else {
    // Bounded both ways, never silently: a fit that ends at a bound is named in the verdict's reasons.
    problem.SetParameterLowerBound(scale, 0, 1.0 / settings.objective.scale_limit);
    problem.SetParameterUpperBound(scale, 0, settings.objective.scale_limit);
  }
}

double solve_inner(ceres::Problem& problem, const RegistrationSettings& settings) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.max_num_iterations = settings.convergence.inner_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.final_cost;
}

SpaceSolution solve_space(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                          const Eigen::VectorXd& initial_latent, const Pose& initial_pose,
                          const RegistrationSettings& settings, CorrespondenceHints* hints) {
  const auto start = std::chrono::steady_clock::now();
  SpaceSolution solution;
  solution.latent = initial_latent;
  solution.pose = initial_pose;
  double previous = std::numeric_limits<double>::infinity();
  CorrespondenceHints own_hints;
  CorrespondenceHints& last = hints ? *hints : own_hints;
  for (int outer = 0; outer < settings.convergence.outer_iterations; ++outer) {
    const Eigen::VectorXd before_latent = solution.latent;
    const Eigen::Vector3d before_translation = solution.pose.translation;
    const Eigen::Quaterniond before_rotation = solution.pose.rotation;
    const Points posed = solution.pose.apply(deformed_points(space, solution.latent));
    const Correspondences pairs =
        correspond(posed, visible_rows(posed, surface, solution.pose, observation.viewpoint), observation,
                   settings, &last);
    if (pairs.from_canonical.empty() && pairs.from_observed.empty()) {
      solution.had_pairs = false;
      break;
    }

    ceres::Problem problem;
    double* rotation = solution.pose.rotation.coeffs().data();
    double* translation = solution.pose.translation.data();
    double* scale = &solution.pose.scale;
    double* latent = solution.latent.data();
    problem.AddResidualBlock(
        new MomentCost(space, weighted_pairs(pairs, settings), settings.objective.prior_weight), nullptr,
        rotation, translation, scale, latent);
    constrain_pose(problem, rotation, scale, settings);
    const double cost = solve_inner(problem, settings);

    solution.iterations = outer + 1;
    solution.cost = cost;
    solution.steps.emplace_back(solution.latent, solution.pose);
    solution.step_costs.push_back(cost);
    solution.step_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    // Settled when neither the cost nor the parameters move any more (correspondences make the cost jitter).
    const double moved = (solution.latent - before_latent).norm() +
                         (solution.pose.translation - before_translation).norm() +
                         solution.pose.rotation.angularDistance(before_rotation);
    if (std::abs(previous - cost) <= settings.convergence.tolerance * std::max(cost, 1e-12) ||
        moved < settings.convergence.tolerance) {
      solution.converged = true;
      break;
    }
    previous = cost;
  }
  solution.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

}  // namespace partreg::core::detail
