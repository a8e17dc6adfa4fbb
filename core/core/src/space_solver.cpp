#include "space_solver.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>

#include "partreg/core/errors.hpp"

namespace partreg::core::detail {
namespace {

constexpr int kMaxLatent = 10;

// One deformed canonical point, posed, against one observed point (Eq. 3's summand). The deformed point is
// base + K x (K: the point's three rows of G times the basis), so no kernel is evaluated here.
template <int Q>
struct PointResidual {
  Eigen::Vector3d base;
  Eigen::Matrix<double, 3, Q> rows;
  Eigen::Vector3d target;

  template <typename T>
  bool operator()(const T* rotation, const T* translation, const T* scale, const T* latent, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, Q, 1>> x(latent);
    const Eigen::Matrix<T, 3, 1> deformed = base.cast<T>() + rows.template cast<T>() * x;
    const Eigen::Map<const Eigen::Quaternion<T>> q(rotation);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(translation);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = scale[0] * (q * deformed) + t - target.cast<T>();
    return true;
  }
};

// The Gaussian prior on the latent: x_k / sd_k, weighted.
template <int Q>
struct PriorResidual {
  Eigen::Matrix<double, Q, 1> inverse_sd;
  template <typename T>
  bool operator()(const T* latent, T* residual) const {
    for (int k = 0; k < Q; ++k) residual[k] = latent[k] * inverse_sd[k];
    return true;
  }
};

struct Pair {
  int row;                   ///< canonical row of the space
  Eigen::Vector3d target;    ///< observed point (normalised)
  double squared_distance;
};

template <int Q>
ceres::CostFunction* point_cost(const ShapeSpace& space, const Pair& pair) {
  auto* functor = new PointResidual<Q>;
  const Eigen::Index m = space.point_count();
  for (int d = 0; d < 3; ++d) {
    functor->base[d] = space.canonical(pair.row, d) + space.kernel_mean[3 * pair.row + d];
    for (int k = 0; k < Q; ++k) functor->rows(d, k) = space.kernel_basis(3 * pair.row + d, k);
  }
  (void)m;
  functor->target = pair.target;
  return new ceres::AutoDiffCostFunction<PointResidual<Q>, 3, 4, 3, 1, Q>(functor);
}

template <int Q>
ceres::CostFunction* prior_cost(const ShapeSpace& space, double weight) {
  auto* functor = new PriorResidual<Q>;
  for (int k = 0; k < Q; ++k) functor->inverse_sd[k] = std::sqrt(weight / std::max(space.variances[k], 1e-12));
  return new ceres::AutoDiffCostFunction<PriorResidual<Q>, Q, Q>(functor);
}

// Ceres needs the latent size at compile time for automatic derivatives: dispatch 1..kMaxLatent.
template <int Q = 1>
ceres::CostFunction* make_cost(int q, const ShapeSpace& space, const Pair* pair, double prior_weight) {
  if constexpr (Q > kMaxLatent) {
    throw UsageError("shape spaces of more than " + std::to_string(kMaxLatent) + " dimensions are not supported");
  } else {
    if (q != Q) return make_cost<Q + 1>(q, space, pair, prior_weight);
    return pair ? point_cost<Q>(space, *pair) : prior_cost<Q>(space, prior_weight);
  }
}

Points deformed_points(const ShapeSpace& space, const Eigen::VectorXd& latent) { return space.deformed(latent); }

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

Correspondences correspond(const Points& posed, const std::vector<bool>& visible, const Observation& observation,
                           const RegistrationSettings& settings) {
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
    for (std::size_t i = 0; i < active.size(); ++i) active_points.row(static_cast<Eigen::Index>(i)) = posed.row(active[i]);
    const KdTree tree(active_points);
    for (Eigen::Index n = 0; n < observation.points.rows(); ++n) {
      const auto [i, squared] = tree.nearest(observation.points.row(n).transpose());
      result.from_observed.push_back({active[static_cast<std::size_t>(i)], observation.points.row(n).transpose(), squared});
    }
  }
  if (settings.loss == Loss::trimmed) {
    trim(result.from_canonical, settings.trim_fraction);
    trim(result.from_observed, settings.trim_fraction);
  }
  return result;
}

ceres::LossFunction* base_loss(const RegistrationSettings& settings) {
  if (settings.loss == Loss::huber) return new ceres::HuberLoss(settings.loss_scale);
  if (settings.loss == Loss::cauchy) return new ceres::CauchyLoss(settings.loss_scale);
  return nullptr;
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
  const int q = space.dimensions();
  SpaceSolution solution;
  solution.latent = initial_latent;
  solution.pose = initial_pose;
  double previous = std::numeric_limits<double>::infinity();
  for (int outer = 0; outer < settings.outer_iterations; ++outer) {
    const Points posed = solution.pose.apply(deformed_points(space, solution.latent));
    const Correspondences pairs =
        correspond(posed, visible_rows(posed, normals, solution.pose, observation.viewpoint), observation, settings);
    if (pairs.from_canonical.empty() && pairs.from_observed.empty()) break;

    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    double* rotation = solution.pose.rotation.coeffs().data();
    double* translation = solution.pose.translation.data();
    double* scale = &solution.pose.scale;
    double* latent = solution.latent.data();
    // Each direction's term is a mean over its pairs, so the symmetric form weighs both equally.
    std::unique_ptr<ceres::LossFunction> losses[2];
    const std::vector<Pair>* sets[2] = {&pairs.from_canonical, &pairs.from_observed};
    for (int s = 0; s < 2; ++s) {
      if (sets[s]->empty()) continue;
      losses[s] = std::make_unique<ceres::ScaledLoss>(base_loss(settings), 1.0 / static_cast<double>(sets[s]->size()),
                                                      ceres::TAKE_OWNERSHIP);
      for (const Pair& pair : *sets[s])
        problem.AddResidualBlock(make_cost(q, space, &pair, 0.0), losses[s].get(), rotation, translation, scale, latent);
    }
    problem.AddResidualBlock(make_cost(q, space, nullptr, settings.prior_weight), nullptr, latent);
    problem.SetManifold(rotation, new ceres::EigenQuaternionManifold);
    if (!settings.estimate_scale) problem.SetParameterBlockConstant(scale);
    else problem.SetParameterLowerBound(scale, 0, 0.2);

    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = settings.inner_iterations;
    options.num_threads = 1;  // parts run in parallel above this level
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    solution.iterations = outer + 1;
    solution.cost = summary.final_cost;
    solution.steps.emplace_back(solution.latent, solution.pose);
    solution.step_costs.push_back(summary.final_cost);
    solution.step_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (std::abs(previous - summary.final_cost) <= settings.tolerance * std::max(summary.final_cost, 1e-12)) break;
    previous = summary.final_cost;
  }
  solution.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

}  // namespace partreg::core::detail
