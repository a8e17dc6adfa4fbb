#include "space_solver.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>

#include "partreg/core/errors.hpp"

namespace partreg::core::detail {
namespace {

struct Pair {
  int row;                 ///< canonical row of the space
  Eigen::Vector3d target;  ///< observed point (normalised)
  double squared_distance;
  double weight = 1.0;  ///< robust (IRLS) weight times the direction's 1 / count
};

// Every correspondence of one outer step as one cost function with analytic derivatives:
// r_i = sqrt(w_i) (s R (b_i + K_i x) + t - o_i), plus the prior sqrt(lambda) x_k / sd_k. One block instead of
// thousands keeps Ceres' bookkeeping out of the per-point cost. b_i + K_i x is the deformed canonical point
// (K_i: three rows of G times the basis), so no kernel is evaluated here.
class StepCost : public ceres::CostFunction {
 public:
  StepCost(const ShapeSpace& space, std::vector<Pair> pairs, double prior_weight)
      : space_(space), pairs_(std::move(pairs)), q_(space.dimensions()) {
    inverse_sd_ = (prior_weight / space.variances.array().max(1e-12)).sqrt().matrix();
    set_num_residuals(static_cast<int>(3 * pairs_.size()) + q_);
    *mutable_parameter_block_sizes() = {4, 3, 1, q_};
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> rotation(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> translation(parameters[1]);
    const double scale = parameters[2][0];
    const Eigen::Map<const Eigen::VectorXd> latent(parameters[3], q_);
    const Eigen::Matrix3d R = rotation.toRotationMatrix();
    const Eigen::Vector3d v = rotation.vec();
    const double w = rotation.w();
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
      const Pair& pair = pairs_[i];
      const Eigen::Index row = 3 * pair.row;
      const Eigen::Vector3d p = space_.canonical.row(pair.row).transpose() +
                                space_.kernel_mean.segment<3>(row) +
                                space_.kernel_basis.middleRows<3>(row) * latent;
      const double root = std::sqrt(pair.weight);
      const Eigen::Vector3d rotated = R * p;
      Eigen::Map<Eigen::Vector3d>(residuals + 3 * i) = root * (scale * rotated + translation - pair.target);
      if (!jacobians) continue;
      const Eigen::Index offset = static_cast<Eigen::Index>(3 * i);
      if (jacobians[0]) {  // d(R p)/d(x, y, z, w) of a unit quaternion, in Eigen's coefficient order
        Eigen::Map<RowMajor> J(jacobians[0], num_residuals(), 4);
        Eigen::Matrix3d skew_p;
        skew_p << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
        const Eigen::Matrix3d d_vector =
            -2.0 * w * skew_p +
            2.0 * (v.dot(p) * Eigen::Matrix3d::Identity() + v * p.transpose() - 2.0 * p * v.transpose());
        J.block(offset, 0, 3, 3) = root * scale * d_vector;
        J.block(offset, 3, 3, 1) = root * scale * 2.0 * v.cross(p);
      }
      if (jacobians[1])
        Eigen::Map<RowMajor>(jacobians[1], num_residuals(), 3).block(offset, 0, 3, 3) =
            root * Eigen::Matrix3d::Identity();
      if (jacobians[2])
        Eigen::Map<Eigen::VectorXd>(jacobians[2], num_residuals()).segment<3>(offset) = root * rotated;
      if (jacobians[3])
        Eigen::Map<RowMajor>(jacobians[3], num_residuals(), q_).block(offset, 0, 3, q_) =
            root * scale * R * space_.kernel_basis.middleRows<3>(row);
    }
    const Eigen::Index prior = static_cast<Eigen::Index>(3 * pairs_.size());
    Eigen::Map<Eigen::VectorXd>(residuals + prior, q_) = inverse_sd_.cwiseProduct(latent);
    if (jacobians) {
      if (jacobians[0]) Eigen::Map<RowMajor>(jacobians[0], num_residuals(), 4).bottomRows(q_).setZero();
      if (jacobians[1]) Eigen::Map<RowMajor>(jacobians[1], num_residuals(), 3).bottomRows(q_).setZero();
      if (jacobians[2]) Eigen::Map<Eigen::VectorXd>(jacobians[2], num_residuals()).tail(q_).setZero();
      if (jacobians[3]) {
        Eigen::Map<RowMajor> J(jacobians[3], num_residuals(), q_);
        J.bottomRows(q_) = inverse_sd_.asDiagonal();
      }
    }
    return true;
  }

 private:
  const ShapeSpace& space_;
  std::vector<Pair> pairs_;
  int q_;
  Eigen::VectorXd inverse_sd_;
};

Points deformed_points(const ShapeSpace& space, const Eigen::VectorXd& latent) {
  return space.deformed(latent);
}

// Which canonical points face the viewpoint under the current pose (all of them without a viewpoint).
std::vector<bool> visible_rows(const Points& posed, const Points& normals, const Pose& pose,
                               const std::optional<Eigen::Vector3d>& viewpoint) {
  std::vector<bool> visible(static_cast<std::size_t>(posed.rows()), true);
  if (!viewpoint || normals.rows() != posed.rows()) return visible;
  const Eigen::Matrix3d R = pose.rotation.toRotationMatrix();
  for (Eigen::Index m = 0; m < posed.rows(); ++m)
    visible[static_cast<std::size_t>(m)] =
        (R * normals.row(m).transpose()).dot(*viewpoint - posed.row(m).transpose()) > 0.0;
  return visible;
}

void trim(std::vector<Pair>& pairs, double fraction) {
  if (pairs.size() < 10 || fraction <= 0.0) return;
  const auto keep = static_cast<std::size_t>(static_cast<double>(pairs.size()) * (1.0 - fraction));
  std::nth_element(pairs.begin(), pairs.begin() + static_cast<long>(keep), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.squared_distance < b.squared_distance; });
  pairs.resize(keep);
}

struct Correspondences {
  std::vector<Pair> from_canonical, from_observed;
};

Correspondences correspond(const Points& posed, const std::vector<bool>& visible,
                           const Observation& observation, const RegistrationSettings& settings) {
  Correspondences result;
  std::vector<int> active;
  for (std::size_t m = 0; m < visible.size(); ++m)
    if (visible[m]) active.push_back(static_cast<int>(m));
  if (active.empty()) return result;
  if (settings.direction != Direction::observed_to_canonical) {
    for (int m : active) {
      const auto [n, squared] = observation.tree->nearest(posed.row(m).transpose());
      result.from_canonical.push_back({m, observation.points.row(n).transpose(), squared});
    }
  }
  if (settings.direction != Direction::canonical_to_observed) {
    Points active_points(static_cast<Eigen::Index>(active.size()), 3);
    for (std::size_t i = 0; i < active.size(); ++i)
      active_points.row(static_cast<Eigen::Index>(i)) = posed.row(active[i]);
    const KdTree tree(active_points);
    for (Eigen::Index n = 0; n < observation.points.rows(); ++n) {
      const auto [i, squared] = tree.nearest(observation.points.row(n).transpose());
      result.from_observed.push_back(
          {active[static_cast<std::size_t>(i)], observation.points.row(n).transpose(), squared});
    }
  }
  if (settings.loss == Loss::trimmed) {
    trim(result.from_canonical, settings.trim_fraction);
    trim(result.from_observed, settings.trim_fraction);
  }
  return result;
}

// Iteratively reweighted least squares: each step weighs its correspondences by the robust loss at their
// current distance (Huber or Cauchy), and every direction's term by 1 / count so both count equally.
std::vector<Pair> weighted_pairs(const Correspondences& pairs, const RegistrationSettings& settings) {
  std::vector<Pair> all;
  for (const std::vector<Pair>* set : {&pairs.from_canonical, &pairs.from_observed}) {
    const double share = set->empty() ? 0.0 : 1.0 / static_cast<double>(set->size());
    for (Pair pair : *set) {
      const double distance = std::sqrt(pair.squared_distance), c = settings.loss_scale;
      double robust = 1.0;
      if (settings.loss == Loss::huber && distance > c) robust = c / distance;
      if (settings.loss == Loss::cauchy) robust = 1.0 / (1.0 + pair.squared_distance / (c * c));
      pair.weight = share * robust;
      all.push_back(pair);
    }
  }
  return all;
}

}  // namespace

Points Pose::apply(const Points& points) const {
  const Eigen::Matrix3d R = rotation.toRotationMatrix();
  return ((scale * points * R.transpose()).rowwise() + translation.transpose());
}

SpaceSolution solve_space(const ShapeSpace& space, const Points& normals, const Observation& observation,
                          const Eigen::VectorXd& initial_latent, const Pose& initial_pose,
                          const RegistrationSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  SpaceSolution solution;
  solution.latent = initial_latent;
  solution.pose = initial_pose;
  double previous = std::numeric_limits<double>::infinity();
  for (int outer = 0; outer < settings.outer_iterations; ++outer) {
    const Eigen::VectorXd before_latent = solution.latent;
    const Eigen::Vector3d before_translation = solution.pose.translation;
    const Eigen::Quaterniond before_rotation = solution.pose.rotation;
    const Points posed = solution.pose.apply(deformed_points(space, solution.latent));
    const Correspondences pairs = correspond(
        posed, visible_rows(posed, normals, solution.pose, observation.viewpoint), observation, settings);
    if (pairs.from_canonical.empty() && pairs.from_observed.empty()) break;

    ceres::Problem problem;
    double* rotation = solution.pose.rotation.coeffs().data();
    double* translation = solution.pose.translation.data();
    double* scale = &solution.pose.scale;
    double* latent = solution.latent.data();
    problem.AddResidualBlock(new StepCost(space, weighted_pairs(pairs, settings), settings.prior_weight),
                             nullptr, rotation, translation, scale, latent);
    problem.SetManifold(rotation, new ceres::EigenQuaternionManifold);
    if (!settings.estimate_scale)
      problem.SetParameterBlockConstant(scale);
    else
      problem.SetParameterLowerBound(scale, 0, 0.2);

    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;  // 13 unknowns, thousands of residuals
    options.max_num_iterations = settings.inner_iterations;
    options.num_threads = 1;  // parts run in parallel above this level
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    solution.iterations = outer + 1;
    solution.cost = summary.final_cost;
    solution.steps.emplace_back(solution.latent, solution.pose);
    solution.step_costs.push_back(summary.final_cost);
    solution.step_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    // Settled when neither the cost nor the parameters move any more (correspondences make the cost jitter).
    const double moved = (solution.latent - before_latent).norm() +
                         (solution.pose.translation - before_translation).norm() +
                         solution.pose.rotation.angularDistance(before_rotation);
    if (std::abs(previous - summary.final_cost) <= settings.tolerance * std::max(summary.final_cost, 1e-12) ||
        moved < settings.tolerance)
      break;
    previous = summary.final_cost;
  }
  solution.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

}  // namespace partreg::core::detail
