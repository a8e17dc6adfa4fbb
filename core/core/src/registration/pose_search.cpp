#include "pose_search.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "mixture_fit.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/parallel.hpp"
#include "geometry/point_normals.hpp"

namespace partreg::core::detail {
namespace {

// Principal axes of a point set as the columns of a rotation, by decreasing spread.
Eigen::Matrix3d principal_axes(const Points& points) {
  const Points centred = points.rowwise() - points.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred);
  Eigen::Matrix3d axes = eigen.eigenvectors().rowwise().reverse();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  return axes;
}

// The category frame, or with principal-axis alignment the four proper rotations that map the canonical's
// axes onto the observation's (the axes' signs are unknown) as well.
std::vector<Eigen::Matrix3d> base_rotations(const Points& canonical, const Observation& observation,
                                            const InitialisationSettings& init) {
  std::vector<Eigen::Matrix3d> rotations = {Eigen::Matrix3d::Identity()};
  if (!init.align_principal_axes) return rotations;
  const Eigen::Matrix3d from = principal_axes(canonical), to = principal_axes(observation.points);
  for (const Eigen::Vector3d& signs : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(-1, -1, 1),
                                       Eigen::Vector3d(-1, 1, -1), Eigen::Vector3d(1, -1, -1)})
    rotations.push_back(to * signs.asDiagonal() * from.transpose());
  return rotations;
}

// Tilts of the up axis: none, or rings at half and the whole of max_tilt, four directions each (about the two
// horizontal axes of the canonical frame, both signs).
std::vector<Eigen::Matrix3d> tilts(const InitialisationSettings& init) {
  std::vector<Eigen::Matrix3d> out = {Eigen::Matrix3d::Identity()};
  if (init.max_tilt <= 0.0) return out;
  const Eigen::Vector3d up = init.up.value_or(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d a = up.unitOrthogonal(), b = up.cross(a);
  for (double angle : {0.5 * init.max_tilt, init.max_tilt})
    for (const Eigen::Vector3d& axis : {a, b, Eigen::Vector3d(-a), Eigen::Vector3d(-b)})
      out.push_back(Eigen::AngleAxisd(angle, axis).toRotationMatrix());
  return out;
}

// Rotations spread over SO(3): the 24 proper rotations of the cube, each turned about the up axis
// `restarts` times (an unknown up axis).
std::vector<Eigen::Matrix3d> cube_rotations() {
  std::vector<Eigen::Matrix3d> out;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  std::vector<int> order = {0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d R;
      for (int c = 0; c < 3; ++c) R.col(c) = ((signs >> c) & 1 ? -1.0 : 1.0) * I.col(order[c]);
      if (R.determinant() > 0.0) out.push_back(R);
    }
  } while (std::next_permutation(order.begin(), order.end()));
  return out;
}

double trimmed_mean_distance(const Eigen::VectorXd& squared, double cap) {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < squared.size(); ++i) sum += std::min(std::sqrt(squared[i]), cap);
  return squared.size() ? sum / static_cast<double>(squared.size()) : std::numeric_limits<double>::infinity();
}

// Continues a candidate by `steps` outer iterations; the new steps are appended to its history. `hints`: its
// closest points from its last round on the same problem (solve_space).
void advance(SpaceSolution& candidate, int steps, const ShapeSpace& space, const ViewSurface& surface,
             const Observation& observation, RegistrationSettings settings, CorrespondenceHints* hints) {
  settings.convergence.outer_iterations = steps;
  SpaceSolution next =
      solve_space(space, surface, observation, candidate.latent, candidate.pose, settings, hints);
  const auto append = [](auto& history, const auto& more) {
    history.insert(history.end(), more.begin(), more.end());
  };
  for (double& seconds : next.step_seconds) seconds += candidate.seconds;
  append(candidate.steps, next.steps);
  append(candidate.step_costs, next.step_costs);
  append(candidate.step_seconds, next.step_seconds);
  next.steps = std::move(candidate.steps);
  next.step_costs = std::move(candidate.step_costs);
  next.step_seconds = std::move(candidate.step_seconds);
  next.iterations += candidate.iterations;
  next.seconds += candidate.seconds;
  candidate = std::move(next);
}

// The rows 3m, 3m + 1, 3m + 2 of a vectorised field (RowMajor points) for every point m in `points`.
Eigen::MatrixXd field_rows(const Eigen::MatrixXd& field, const std::vector<int>& points) {
  Eigen::MatrixXd out(3 * static_cast<Eigen::Index>(points.size()), field.cols());
  for (std::size_t i = 0; i < points.size(); ++i)
    out.middleRows(3 * static_cast<Eigen::Index>(i), 3) = field.middleRows(3 * points[i], 3);
  return out;
}

// The space restricted to some of its canonical points: the same displacement field (kernel_mean,
// kernel_basis) read at those points, so a latent and pose mean the same on both. The kernel weights
// (mean, basis) are cut alike only to keep the dimensions; the solver reads the displacements.
ShapeSpace restricted_space(const ShapeSpace& space, const std::vector<int>& rows) {
  ShapeSpace out;
  out.name = space.name;
  out.beta = space.beta;
  out.canonical = select_rows(space.canonical, rows);
  out.mean = field_rows(space.mean, rows);
  out.basis = field_rows(space.basis, rows);
  out.kernel_mean = field_rows(space.kernel_mean, rows);
  out.kernel_basis = field_rows(space.kernel_basis, rows);
  out.variances = space.variances;
  out.total_variance = space.total_variance;
  return out;
}

// The screening rounds' problem: farthest-point subsets of the canonical points and of the observation.
// Ranking hypotheses needs their coarse shape only, so the many starts cost a fraction of a full step
// each; the finalists then run on the whole problem.
struct CoarseProblem {
  ShapeSpace space;
  ViewSurface surface;
  Observation observation;
};

std::optional<CoarseProblem> coarse_problem(const ShapeSpace& space, const ViewSurface& surface,
                                            const Observation& observation, int points) {
  const auto count = static_cast<std::size_t>(points);
  if (points <= 0 || (space.canonical.rows() <= points && observation.points.rows() <= points))
    return std::nullopt;
  // Every row of a set no larger than `points` (sampling.hpp), else its farthest points.
  const auto rows_of = [&](const Points& set) { return subsample_indices(set, count, /*voxel_size=*/0.0); };
  CoarseProblem coarse;
  const std::vector<int> canonical_rows = rows_of(space.canonical);
  coarse.space = restricted_space(space, canonical_rows);
  if (surface.normals.rows() > 0) coarse.surface = restricted(surface, canonical_rows, coarse.space.canonical);
  const std::vector<int> observed_rows = rows_of(observation.points);
  coarse.observation.points = select_rows(observation.points, observed_rows);
  coarse.observation.tree = std::make_unique<KdTree>(coarse.observation.points);
  coarse.observation.viewpoint = observation.viewpoint;
  coarse.observation.free_space = observation.free_space;
  // The lone points keep their flags: farthest points take them first, so at the paper's 20% outliers about
  // half the subset were outliers, and matched like the rest they decided the ranking of the starts
  // (docs/registration.md, "Strays").
  if (!observation.alone.empty())
    for (int n : observed_rows) coarse.observation.alone.push_back(observation.alone[static_cast<std::size_t>(n)]);
  return coarse;
}

// One hypothesis of the search: its fit so far, where it started and its closest-point hints (on the problem
// it is being advanced on).
struct Candidate {
  SpaceSolution fit;
  Pose start;
  CorrespondenceHints hints;
  double score = 0.0;
};

// The better half (at least `finalists`) of the candidates by score, best first.
std::vector<Candidate> better_half(std::vector<Candidate> candidates, std::size_t finalists) {
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return candidates[a].score < candidates[b].score; });
  std::vector<Candidate> kept;
  const std::size_t keep = std::max(finalists, candidates.size() / 2);
  for (std::size_t k = 0; k < keep; ++k) kept.push_back(std::move(candidates[order[k]]));
  return kept;
}


// Rigid closest-point steps taken by the cheapest look at a start: enough to turn a start 15 degrees off (half
// the default spacing of the yaws) onto its basin's pose on the coarse problem.
constexpr int kLookSteps = 4;

// The cheapest look at a start: its shape (the latent it starts with) moved rigidly by kLookSteps closest-point
// steps both ways (Umeyama, no scale) over the points the viewpoint sees, on the screening's coarse problem.
// No Ceres problem is built, so a look costs a small share of a screening step.
void look(Candidate& candidate, const ShapeSpace& space, const ViewSurface& surface,
          const Observation& observation, const RegistrationSettings& settings) {
  const Points shape = space.deformed(candidate.fit.latent);
  std::vector<int> index;
  Eigen::VectorXd squared;
  for (int step = 0; step < kLookSteps; ++step) {
    const Points posed = candidate.fit.pose.apply(shape);
    const std::vector<bool> visible = visible_rows(posed, surface, candidate.fit.pose, observation.viewpoint);
    std::vector<int> seen;
    for (std::size_t m = 0; m < visible.size(); ++m)
      if (visible[m]) seen.push_back(static_cast<int>(m));
    if (seen.size() < 3) return;
    const Points seen_posed = select_rows(posed, seen);
    // Pairs (shape point, observed point): each seen shape point to its closest observed point, and each
    // observed point to its closest seen shape point.
    observation.tree->nearest_all(seen_posed, index, squared);
    const auto n = static_cast<Eigen::Index>(seen.size());
    Eigen::Matrix3Xd from(3, n + observation.points.rows()), to(3, n + observation.points.rows());
    for (Eigen::Index i = 0; i < n; ++i) {
      from.col(i) = posed.row(seen[static_cast<std::size_t>(i)]).transpose();
      to.col(i) = observation.points.row(index[static_cast<std::size_t>(i)]).transpose();
    }
    KdTree(seen_posed).nearest_all(observation.points, index, squared);
    for (Eigen::Index j = 0; j < observation.points.rows(); ++j) {
      from.col(n + j) = seen_posed.row(index[static_cast<std::size_t>(j)]).transpose();
      to.col(n + j) = observation.points.row(j).transpose();
    }
    const Eigen::Matrix4d T = Eigen::umeyama(from, to, /*with_scaling=*/false);
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    Pose& pose = candidate.fit.pose;
    pose.rotation = Eigen::Quaterniond(R * pose.rotation.toRotationMatrix()).normalized();
    pose.translation = R * pose.translation + T.topRightCorner<3, 1>();
  }
  RegistrationSettings symmetric = settings;
  symmetric.initialisation.score = SelectionScore::symmetric;
  candidate.score = selection_score(space, surface, observation, candidate.fit, symmetric);
}

// Two looks that ended within this of each other are one hypothesis (radians of rotation, normalised length
// of translation): starts in one basin, or a symmetric object's turns that fit alike.
constexpr double kSameRotation = 0.15, kSameTranslation = 0.02;

// The starts worth screening: every start looked at (in parallel), the duplicates merged, the best `keep` by
// the look's score, best first.
std::vector<Candidate> survivors(std::vector<Candidate> candidates, std::size_t keep, const ShapeSpace& space,
                                 const ViewSurface& surface, const Observation& observation,
                                 const RegistrationSettings& settings) {
  parallel_for(
      static_cast<Eigen::Index>(candidates.size()),
      [&](Eigen::Index begin, Eigen::Index end) {
        for (Eigen::Index i = begin; i < end; ++i)
          look(candidates[static_cast<std::size_t>(i)], space, surface, observation, settings);
      },
      0, 1);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  std::vector<Candidate> kept;
  for (Candidate& candidate : candidates) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const Candidate& other) {
      return candidate.fit.pose.rotation.angularDistance(other.fit.pose.rotation) < kSameRotation &&
             (candidate.fit.pose.translation - other.fit.pose.translation).norm() < kSameTranslation;
    });
    if (!duplicate) kept.push_back(std::move(candidate));
    if (kept.size() == keep) break;
  }
  return kept;
}

}  // namespace

double search_prior_weight(const ShapeSpace& space, const Observation& observation, const SpaceSolution& fit,
                           const ObjectiveSettings& objective) {
  const Points posed = fit.pose.apply(space.deformed(fit.latent));
  return noisy_prior_weight(observed_noise(observation.points, posed), objective);
}

std::vector<Pose> starting_poses(const Eigen::Vector3d& centre, const Points& canonical,
                                 const Observation& observation, const RegistrationSettings& settings) {
  const InitialisationSettings& init = settings.initialisation;
  const Eigen::Vector3d up = init.up.value_or(Eigen::Vector3d::UnitY()).normalized();
  std::vector<Eigen::Matrix3d> bases = init.any_rotation ? cube_rotations() : std::vector<Eigen::Matrix3d>{};
  if (!init.any_rotation)
    for (const Eigen::Matrix3d& base : base_rotations(canonical, observation, init))
      for (const Eigen::Matrix3d& tilt : tilts(init)) bases.push_back(base * tilt);
  std::vector<Pose> poses;
  for (const Eigen::Matrix3d& base : bases)
    for (int k = 0; k < init.restarts; ++k) {
      Pose pose;
      pose.rotation = Eigen::Quaterniond(base * Eigen::AngleAxisd(2.0 * M_PI * k / init.restarts, up));
      pose.translation = -(pose.rotation * centre);
      poses.push_back(pose);
    }
  return poses;
}

double selection_score(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                       const SpaceSolution& solution, const RegistrationSettings& settings) {
  const double weight = settings.initialisation.free_space_weight;
  if (!observation.free_space || !(weight > 0.0)) return fit_score(space, surface, observation, solution, settings);
  // Every posed point counts, facing the camera or not: one in front of the measured depth contradicts the
  // image wherever it faces.
  const Points posed = solution.pose.apply(space.deformed(solution.latent));
  return fit_score(space, surface, observation, solution, settings) *
         (1.0 + weight * observation.free_space->violation_share(posed));
}

double fit_score(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                 const SpaceSolution& solution, const RegistrationSettings& settings) {
  if (settings.initialisation.score == SelectionScore::cost) return solution.cost;
  const Points posed = solution.pose.apply(space.deformed(solution.latent));
  const std::vector<bool> visible = visible_rows(posed, surface, solution.pose, observation.viewpoint);
  std::vector<int> rows;
  for (std::size_t m = 0; m < visible.size(); ++m)
    if (visible[m]) rows.push_back(static_cast<int>(m));
  if (rows.size() < 3) return std::numeric_limits<double>::infinity();
  Points seen(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) seen.row(static_cast<Eigen::Index>(i)) = posed.row(rows[i]);
  const double cap = 4.0 * settings.objective.loss_scale;
  std::vector<int> index;
  Eigen::VectorXd to_observed, to_canonical;
  observation.tree->nearest_all(seen, index, to_observed);
  KdTree(seen).nearest_all(observation.points, index, to_canonical);
  const double canonical_side = trimmed_mean_distance(to_observed, cap);
  const double observed_side = trimmed_mean_distance(to_canonical, cap);
  switch (settings.initialisation.score) {
    case SelectionScore::canonical:
      return canonical_side;
    case SelectionScore::observed:
      return observed_side;
    default:
      return 0.5 * (canonical_side + observed_side);
  }
}

SearchOutcome search_poses(const ShapeSpace& space, const ViewSurface& surface,
                           const Observation& observation, const std::vector<Pose>& starts,
                           const Eigen::VectorXd& latent, const RegistrationSettings& settings,
                           bool whole_object) {
  const InitialisationSettings& init = settings.initialisation;
  // The screening's first round runs at the settings' prior; the rest of the search at the prior for the
  // noise the observation reads against that round's best fit.
  RegistrationSettings search_settings = settings;
  bool read_noise = whole_object;  // once, after the first round
  std::vector<Candidate> candidates(starts.size());
  for (std::size_t i = 0; i < starts.size(); ++i) {
    candidates[i].fit.latent = latent;
    candidates[i].fit.pose = candidates[i].start = starts[i];
  }
  const auto finalists = static_cast<std::size_t>(std::max(1, init.finalists));
  const std::optional<CoarseProblem> coarse =
      candidates.size() > finalists ? coarse_problem(space, surface, observation, init.screening_points)
                                    : std::nullopt;
  const ShapeSpace& screen_space = coarse ? coarse->space : space;
  const ViewSurface& screen_surface = coarse ? coarse->surface : surface;
  const Observation& screen_observation = coarse ? coarse->observation : observation;
  if (init.survivors > 0 && candidates.size() > static_cast<std::size_t>(init.survivors))
    candidates = survivors(std::move(candidates), static_cast<std::size_t>(init.survivors), screen_space,
                           screen_surface, screen_observation, settings);
  int steps = std::max(1, init.screening_iterations);
  while (candidates.size() > finalists) {
    parallel_for(
        static_cast<Eigen::Index>(candidates.size()),
        [&](Eigen::Index begin, Eigen::Index end) {
          for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i) {
            Candidate& candidate = candidates[i];
            // Never more outer steps in all than the convergence settings allow.
            const int budget =
                std::min(steps, settings.convergence.outer_iterations - candidate.fit.iterations);
            if (budget > 0)
              advance(candidate.fit, budget, screen_space, screen_surface, screen_observation,
                      search_settings, &candidate.hints);
            candidate.score = selection_score(screen_space, screen_surface, screen_observation, candidate.fit,
                                              search_settings);
          }
        },
        0, 1);
    candidates = better_half(std::move(candidates), finalists);
    steps *= 2;
    if (read_noise) {
      search_settings.objective.prior_weight =
          search_prior_weight(space, observation, candidates.front().fit, settings.objective);
      read_noise = false;
    }
  }
  parallel_for(
      static_cast<Eigen::Index>(candidates.size()),
      [&](Eigen::Index begin, Eigen::Index end) {
        for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i) {
          Candidate& candidate = candidates[i];
          // Steps on the coarse problem do not count against the whole problem's budget (nor in the
          // iterations reported: their history stays), nor does settling there mean settling here.
          if (coarse) candidate.fit.iterations = 0;
          const int left = settings.convergence.outer_iterations - candidate.fit.iterations;
          if (left > 0 && (coarse || !candidate.fit.converged))
            // The screening's hints index the coarse problem's points: the whole problem starts afresh.
            advance(candidate.fit, left, space, surface, observation, search_settings,
                    coarse ? nullptr : &candidate.hints);
          candidate.score = selection_score(space, surface, observation, candidate.fit, search_settings);
        }
      },
      0, 1);
  SearchOutcome outcome;
  outcome.hypotheses = static_cast<int>(starts.size());
  outcome.best_score = outcome.runner_up = std::numeric_limits<double>::infinity();
  for (const Candidate& candidate : candidates) {
    if (candidate.score < outcome.best_score) {
      outcome.runner_up = outcome.best_score;
      if (std::isfinite(outcome.best_score)) outcome.runner_up_fit = outcome.best;
      outcome.best_score = candidate.score;
      outcome.best = candidate.fit;
      outcome.best_start = candidate.start;
    } else if (candidate.score < outcome.runner_up) {
      outcome.runner_up = candidate.score;
      outcome.runner_up_fit = candidate.fit;
    }
  }
  return outcome;
}

}  // namespace partreg::core::detail
