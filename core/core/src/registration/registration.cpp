#include "partreg/core/registration/registration.hpp"

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/registration/verdict.hpp"
#include "coupled_solver.hpp"
#include "mixture_fit.hpp"
#include "geometry/point_normals.hpp"
#include "pose_search.hpp"
#include "space_solver.hpp"

namespace partreg::core {
namespace {

using detail::Observation;
using detail::Pose;
using detail::SpaceSolution;

// A point stands alone when its second nearest neighbour is farther than the stray limit times the median:
// the fewer the neighbours, the more a uniform outlier stands out against a surface (its distance grows as
// k^(1/3), a surface's as k^(1/2)), and two outliers seldom fall close together (docs/registration.md,
// "Strays").
constexpr int kStrayNeighbours = 2;

// The rows of `points` that registration matches: farthest points among those with company (farthest
// points of a set with strays would favour the strays: the paper's 20% outliers became 40% of the subset),
// then every row that stands alone, flagged in `alone`. Those are matched only while the fit passes near
// (detail::is_stray): a thinly seen handle is surface, a speck of dust is not.
std::vector<int> matched_rows(const Points& points, const SamplingSettings& sampling,
                              std::vector<bool>& alone) {
  const std::vector<int> with_company = rows_with_neighbours(points, kStrayNeighbours, sampling.stray_limit);
  std::vector<int> rows = subsample_indices(select_rows(points, with_company),
                                            static_cast<std::size_t>(sampling.observed_points), 0.0);
  for (int& row : rows) row = with_company[static_cast<std::size_t>(row)];
  std::vector<bool> has_company(static_cast<std::size_t>(points.rows()), false);
  for (int row : with_company) has_company[static_cast<std::size_t>(row)] = true;
  alone.assign(rows.size(), false);
  for (Eigen::Index n = 0; n < points.rows(); ++n)
    if (!has_company[static_cast<std::size_t>(n)]) {
      rows.push_back(static_cast<int>(n));
      alone.push_back(true);
    }
  if (with_company.size() == static_cast<std::size_t>(points.rows())) alone.clear();  // none stands alone
  return rows;
}

// A cloud of more than this many times SamplingSettings::observed_points is thinned to at most that many before
// anything is built over it: the strays' neighbour queries and the farthest points cost O(N log N) and more,
// and on a depth camera's million points they were 90% of the registration. Four candidates per matched point
// leave the farthest points a choice at a third of their spacing.
constexpr double kCandidatesPerMatched = 4.0;

// The rows of `points` registration chooses its matched points from: every row of a cloud no larger than
// observed_points, else one voxel pass at voxel_size (data units here) over all of it, the only pass over every
// point, then passes at growing voxels over the representatives until no more than kCandidatesPerMatched x
// observed_points remain. `fine`: the first pass's representatives, where it ran.
std::vector<int> candidate_rows(const Points& points, const SamplingSettings& sampling, double voxel_size,
                                std::optional<std::vector<int>>& fine) {
  std::vector<int> rows(static_cast<std::size_t>(points.rows()));
  std::iota(rows.begin(), rows.end(), 0);
  if (points.rows() <= sampling.observed_points || !(voxel_size > 0.0)) return rows;
  rows = voxel_representatives(points, voxel_size);
  fine = rows;
  const double most = kCandidatesPerMatched * sampling.observed_points;
  while (static_cast<double>(rows.size()) > most) {
    // A surface's voxels fall as the square of their size: grow it by the root of the excess, and a little.
    voxel_size *= 1.05 * std::sqrt(static_cast<double>(rows.size()) / most);
    std::vector<int> coarser = voxel_representatives(select_rows(points, rows), voxel_size);
    for (int& row : coarser) row = rows[static_cast<std::size_t>(row)];
    rows = std::move(coarser);
  }
  return rows;
}

// An observation orders of magnitude off the model's size is in other units: refused, naming both sizes.
// Within the bounds a partial view (smaller) or stray points (larger) still pass.
void check_size(const CategoryModel& model, const Points& observed) {
  const double seen = bounding_box_diagonal(observed), expected = model.observed_diagonal();
  if (seen > 0.1 * expected && seen < 10.0 * expected) return;
  const std::string units = model.size ? "metres (the model's real size)" : "the model's data units";
  throw InputError("the observed cloud's diagonal is " + std::to_string(seen) + " but the '" + model.category +
                   "' model's is " + std::to_string(expected) + ", both in " + units +
                   ": check the observation's units" + (model.size ? "" : " or train with --size"));
}

detail::Observation prepare_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings, Eigen::Vector3d& centroid,
                                        std::optional<Points>& statistics_points) {
  if (observed.rows() < 10)
    throw InputError("the observed cloud has " + std::to_string(observed.rows()) +
                     " points; at least 10 are needed");
  if (!observed.allFinite()) throw InputError("the observed cloud holds NaN or infinite points");
  check_size(model, observed);
  const double S = model.observed_diagonal();
  centroid = observed.colwise().mean().transpose();
  // Thinned first, in data units: only the candidates are ever normalised, searched or sampled.
  std::optional<std::vector<int>> fine;
  const std::vector<int> rows = candidate_rows(
      observed, settings.sampling, settings.sampling.voxel_size * S, fine);
  // The fit statistics of a thinned cloud read its fine representatives: a tree over every point of a million
  // cost more than the fit.
  if (fine && static_cast<double>(observed.rows()) > kCandidatesPerMatched * settings.sampling.observed_points)
    statistics_points = select_rows(observed, *fine);
  const Points candidates =
      (select_rows(observed, rows).rowwise() - centroid.transpose()) / S;
  Observation observation;
  observation.points = select_rows(candidates, matched_rows(candidates, settings.sampling, observation.alone));
  observation.tree = std::make_unique<KdTree>(observation.points);
  if (settings.viewpoint)
    observation.viewpoint = (*settings.viewpoint - centroid) / S;
  if (settings.free_space) {
    // The fits' normalised points: scaled back and moved onto the centroid before the camera's own map.
    auto normalised = std::make_shared<FreeSpace>(settings.free_space->prepared());
    normalised->T_camera_observed = settings.free_space->T_camera_observed * Eigen::Translation3d(centroid) *
                                    Eigen::Scaling(S);
    observation.free_space = std::move(normalised);
  }
  return observation;
}

// Canonical data frame -> observed frame; with a real size the model's data units become metres on the way.
Eigen::Matrix4d to_data_frame(const Pose& pose, const CategoryModel& model, const Eigen::Vector3d& centroid) {
  const double S = model.observed_diagonal();
  const Eigen::Matrix3d sR = model.observed_per_data() * pose.scale * pose.rotation.toRotationMatrix();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = sR;
  T.topRightCorner<3, 1>() = S * pose.translation + centroid - sR * model.normalization.centre;
  return T;
}

double mahalanobis(const ShapeSpace& space, const Eigen::VectorXd& latent) {
  double sum = 0.0;
  for (Eigen::Index k = 0; k < latent.size() && k < space.variances.size(); ++k)
    if (space.variances(k) > 0.0) sum += latent(k) * latent(k) / space.variances(k);
  return std::sqrt(sum);
}

// RMS closest-point distance between two fits' posed shapes, each way (normalised length; 0 without `other`).
double shift(const ShapeSpace& space, const SpaceSolution& fit, const SpaceSolution& other) {
  if (other.latent.size() != fit.latent.size()) return 0.0;
  const Points a = fit.pose.apply(space.deformed(fit.latent)), b = other.pose.apply(space.deformed(other.latent));
  std::vector<int> index;
  Eigen::VectorXd ab, ba;
  KdTree(b).nearest_all(a, index, ab);
  KdTree(a).nearest_all(b, index, ba);
  return std::sqrt(0.5 * (ab.mean() + ba.mean()));
}

void record(RegistrationResult& result, const std::string& name, const detail::SearchOutcome& search,
            const CategoryModel& model, const Eigen::Vector3d& centroid) {
  const SpaceSolution& solution = search.best;
  const StopReason stop = !solution.had_pairs  ? StopReason::no_pairs
                          : solution.converged ? StopReason::converged
                                               : StopReason::max_iterations;
  SpaceFit fit{name,
               solution.latent,
               to_data_frame(solution.pose, model, centroid),
               solution.pose.scale,
               solution.cost,
               solution.iterations,
               stop,
               solution.seconds};
  fit.hypotheses = search.hypotheses;
  fit.score = search.best_score;
  fit.runner_up_score = search.runner_up;
  const ShapeSpace& space = model.space(name);
  fit.latent_distance = mahalanobis(space, solution.latent);
  fit.runner_up_shift = shift(space, solution, search.runner_up_fit);
  result.fits.push_back(fit);
  for (std::size_t i = 0; i < solution.steps.size(); ++i)
    result.history.push_back({name, solution.steps[i].first,
                              to_data_frame(solution.steps[i].second, model, centroid),
                              solution.step_costs[i], solution.step_seconds[i]});
}

Points rows_of(const Points& points, const std::vector<int>& rows) { return select_rows(points, rows); }


// Splits the observation by part: each observed point goes to the part of the nearest point of the
// holistic fit (indexed by space; a part with fewer than 10 points gets no observation of its own).
std::vector<Observation> split_observation(const CategoryModel& model, const Observation& observation,
                                           const Points& holistic_posed) {
  const KdTree tree(holistic_posed);
  std::vector<std::vector<int>> rows(model.spaces.size());
  for (Eigen::Index n = 0; n < observation.points.rows(); ++n) {
    const int part = model.canonical_part[tree.nearest(observation.points.row(n).transpose()).first];
    rows[static_cast<std::size_t>(part) + 1].push_back(static_cast<int>(n));
  }
  std::vector<Observation> split(model.spaces.size());
  for (std::size_t p = 1; p < split.size(); ++p) {
    if (rows[p].size() < 10) continue;
    split[p].points = select_rows(observation.points, rows[p]);
    split[p].tree = std::make_unique<KdTree>(split[p].points);
    split[p].viewpoint = observation.viewpoint;
    split[p].free_space = observation.free_space;
    if (!observation.alone.empty())
      for (int n : rows[p]) split[p].alone.push_back(observation.alone[static_cast<std::size_t>(n)]);
  }
  return split;
}

// The rows of the observation that are not strays of `fitted` (detail::is_stray); only the points that stand
// alone are looked up, and no tree is built when none does.
std::vector<int> rows_near(const Observation& observation, const Points& fitted) {
  std::vector<int> rows;
  const std::optional<KdTree> tree =
      observation.alone.empty() ? std::nullopt : std::optional<KdTree>(std::in_place, fitted);
  for (Eigen::Index n = 0; n < observation.points.rows(); ++n)
    if (!tree || !observation.alone[static_cast<std::size_t>(n)] ||
        !detail::is_stray(observation, n, tree->nearest(observation.points.row(n).transpose()).second))
      rows.push_back(static_cast<int>(n));
  return rows;
}

// The observation the refinement follows: the space fit's strays left out, as the fit left them out.
Points without_strays(const Observation& observation, const Points& fitted) {
  return observation.alone.empty() ? observation.points
                                   : select_rows(observation.points, rows_near(observation, fitted));
}

// The observed points a mixture finishes the space fits on (mixture_fit.hpp), or none when the observation
// reads no noisier than the setting against the holistic fit `fitted`; `finish` records the noise read.
std::optional<Points> mixture_targets(const Observation& observation, const Points& fitted,
                                      const RegistrationSettings& settings, MixtureFinish& finish) {
  Points targets = without_strays(observation, fitted);
  finish.noise = detail::observed_noise(targets, fitted);
  finish.applied = finish.noise > settings.objective.mixture_noise;
  if (!finish.applied) return std::nullopt;
  return targets;
}

// Observed points the final fit left out (FitStatistics::strays).
int count_strays(const Observation& observation, const Points& fitted) {
  return observation.alone.empty() ? 0
                                   : static_cast<int>(observation.points.rows() -
                                                      static_cast<Eigen::Index>(rows_near(observation, fitted).size()));
}

FitStatistics fit_statistics(const Points& deformed, const Points& observed, double scale) {
  const KdTree tree(observed);
  std::vector<int> index;
  Eigen::VectorXd squared;
  tree.nearest_all(deformed, index, squared);
  std::vector<double> distances(squared.data(), squared.data() + squared.size());
  for (double& d : distances) d = std::sqrt(d);
  FitStatistics fit;
  fit.mean = std::accumulate(distances.begin(), distances.end(), 0.0) / static_cast<double>(distances.size());
  const auto at = distances.begin() + static_cast<long>(0.9 * static_cast<double>(distances.size() - 1));
  std::nth_element(distances.begin(), at, distances.end());
  fit.p90 = *at;
  fit.mean_normalised = fit.mean / scale;
  fit.p90_normalised = fit.p90 / scale;
  return fit;
}


// Wall seconds since the last lap (or since construction): each stage's time, read once at its end.
class StageClock {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// The warm start's pose in the normalised frame the fits work in: to_data_frame read backwards. Its scale is
// kept only where the fit estimates one.
Pose normalised_pose(const Eigen::Matrix4d& T, const CategoryModel& model, const Eigen::Vector3d& centroid,
                     bool keep_scale) {
  const Eigen::Matrix3d sR = T.topLeftCorner<3, 3>();
  const double scale = std::cbrt(sR.determinant());
  const Eigen::Matrix3d R = sR / scale;
  if (!T.allFinite() || !(scale > 0.0) || !(R.transpose() * R).isIdentity(1e-3) ||
      !T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)))
    throw UsageError("the initial pose is not a rotation with a uniform scale and a translation");
  Pose pose;
  pose.rotation = Eigen::Quaterniond(R).normalized();
  // With a real size the pose also carries the data-units-to-metres factor (to_data_frame): not the fit's scale.
  pose.scale = keep_scale ? scale / model.observed_per_data() : 1.0;
  pose.translation =
      (T.topRightCorner<3, 1>() - centroid + sR * model.normalization.centre) / model.observed_diagonal();
  return pose;
}

// The symmetric selection score of a space's fit: how a warm start is judged, whatever picks the search's winner.
double symmetric_score(const ShapeSpace& space, const detail::ViewSurface& surface, const Observation& observation,
                       const SpaceSolution& fit, RegistrationSettings settings) {
  settings.initialisation.score = SelectionScore::symmetric;
  return detail::selection_score(space, surface, observation, fit, settings);
}

// The holistic space's pose and latent: the search over `poses`, or with a warm start its single fit, which
// stands while its symmetric score stays below warm_limit or near the score of the frame it came from.
detail::SearchOutcome holistic_search(const CategoryModel& model, const detail::ViewSurface& surface,
                                      const Observation& observation, const std::vector<Pose>& poses,
                                      const RegistrationSettings& settings, const WarmStart* warm,
                                      const Eigen::Vector3d& centroid, RegistrationResult& result) {
  const ShapeSpace& holistic = model.holistic();
  const Eigen::VectorXd mean = Eigen::VectorXd::Zero(holistic.dimensions());
  if (warm) {
    if (warm->latent.size() != 0 && warm->latent.size() != holistic.dimensions())
      throw UsageError("the initial latent has " + std::to_string(warm->latent.size()) + " values; the '" +
                       holistic.name + "' space has " + std::to_string(holistic.dimensions()));
    const Pose start = normalised_pose(warm->T_observed_canonical, model, centroid,
                                       settings.objective.estimate_scale);
    detail::SearchOutcome fit = detail::search_poses(holistic, surface, observation, {start},
                                                     warm->latent.size() ? warm->latent : mean, settings,
                                                     /*whole_object=*/true);
    result.warm_score = symmetric_score(holistic, surface, observation, fit.best, settings);
    const bool held = result.warm_score < settings.initialisation.warm_limit ||
                      (warm->score > 0.0 && result.warm_score <= kWarmScoreGrowth * warm->score);
    result.start = held ? StartOutcome::warm : StartOutcome::warm_lost;
    if (held) {
      result.pose_score = result.warm_score;
      return fit;
    }
  }
  detail::SearchOutcome search =
      detail::search_poses(holistic, surface, observation, poses, mean, settings, /*whole_object=*/true);
  result.pose_score = symmetric_score(holistic, surface, observation, search.best, settings);
  return search;
}

}  // namespace

RegistrationSettings with_model_defaults(RegistrationSettings settings, const CategoryModel& model) {
  if (!settings.initialisation.up) settings.initialisation.up = model.up;
  if (!settings.objective.seam_weight)
    settings.objective.seam_weight = model.training.seam_weight.value_or(kDefaultSeamWeight);
  return settings;
}

namespace {

RegistrationResult register_from(const CategoryModel& model, const Points& observed,
                                 const RegistrationSettings& request, const WarmStart* warm,
                                 const ProgressListener& progress) {
  StageClock clock;
  validate(request);
  const RegistrationSettings settings = with_model_defaults(request, model);
  if (settings.variant != Variant::holistic && !model.has_parts())
    throw UsageError("model '" + model.category + "' has no parts: use the holistic variant");
  Eigen::Vector3d centroid;
  std::optional<Points> statistics_points;  // a thinned cloud's fine voxel representatives
  const Observation observation = prepare_observation(model, observed, settings, centroid, statistics_points);
  const detail::ViewSurface surface = settings.viewpoint ? detail::view_surface(model.canonical) : detail::ViewSurface();
  const ShapeSpace& holistic = model.holistic();
  // Every space starts with the whole object's centroid on the observation's: a part keeps its place.
  const Eigen::Vector3d centre =
      holistic.deformed(Eigen::VectorXd::Zero(holistic.dimensions())).colwise().mean().transpose();
  const std::vector<Pose> poses = detail::starting_poses(centre, model.canonical, observation, settings);
  RegistrationResult result;
  result.stages.prepare = clock.lap();
  const std::size_t parts_fitted = settings.variant == Variant::holistic ? 0 : model.spaces.size() - 1;
  ProgressCounter fitted(parts_fitted + (settings.variant == Variant::partwise ? 0 : 1), progress);

  result.variant = settings.variant;
  Points deformed_normalised(model.canonical.rows(), 3);
  SpaceSolution whole;
  std::optional<Points> mixture;  // the observed points the space fits end on, when the observation is noisy
  std::vector<bool> centres;      // the canonical rows that centre it (computed only when it is used)
  // The part fits after a mixture weigh the prior by its variance (detail::noisy_prior_weight).
  RegistrationSettings fit_settings = settings;
  if (settings.variant != Variant::partwise) {
    detail::SearchOutcome search =
        holistic_search(model, surface, observation, poses, settings, warm, centroid, result);
    result.stages.search = clock.lap();
    deformed_normalised = search.best.pose.apply(holistic.deformed(search.best.latent));
    mixture = mixture_targets(observation, deformed_normalised, settings, result.mixture);
    if (mixture) {
      centres = detail::mixture_centres(model.canonical);
      result.mixture.sigma =
          detail::finish_in_mixture(holistic, surface, observation, *mixture, centres, settings, search.best);
      fit_settings.objective.prior_weight =
          detail::noisy_prior_weight(result.mixture.sigma, settings.objective);
      deformed_normalised = search.best.pose.apply(holistic.deformed(search.best.latent));
    }
    record(result, holistic.name, search, model, centroid);
    fitted.step("fitted " + holistic.name);
    whole = search.best;
  }
  if (settings.variant != Variant::holistic) {
    const Points holistic_displacement = settings.variant == Variant::hol_part
                                             ? Points(holistic.deformed(whole.latent) - holistic.canonical)
                                             : Points();
    // Summing over observed points needs the observation split by part: hol+part takes the split from the
    // holistic fit; partwise has none, so its parts use the canonical direction only (Eq. 3).
    std::vector<Observation> part_observations(model.spaces.size());
    RegistrationSettings part_settings = fit_settings;
    if (settings.variant == Variant::hol_part)
      part_observations = split_observation(model, observation, deformed_normalised);
    else {
      part_settings.objective.direction = Direction::canonical_to_observed;
      part_settings.objective.prior_weight = settings.objective.partwise_prior_weight;
      // A part alone is too ambiguous for a search all round (the real mug's handle lands at a wrong yaw):
      // partwise keeps the paper's single start in the category frame.
      part_settings.initialisation.restarts = 1;
    }
    // Partwise from a warm start: every part starts at its pose, searching nothing.
    const std::vector<Pose> part_poses =
        warm ? std::vector<Pose>{normalised_pose(warm->T_observed_canonical, model, centroid,
                                                 settings.objective.estimate_scale)}
             : detail::starting_poses(centre, model.canonical, observation, part_settings);
    if (warm && settings.variant == Variant::partwise) result.start = StartOutcome::warm;
    // Parts are independent given their initialisation: solve them in parallel, within the thread budget.
    std::vector<detail::SearchOutcome> parts(model.spaces.size() - 1);
    if (settings.variant == Variant::coupled)
      parts = detail::solve_coupled(model, surface, observation, whole, settings,
                                    mixture ? &*mixture : nullptr, centres);
    else
      parallel_for(
        static_cast<Eigen::Index>(parts.size()),
        [&](Eigen::Index begin, Eigen::Index end) {
          for (Eigen::Index i = begin; i < end; ++i) {
            const std::size_t p = static_cast<std::size_t>(i) + 1;
            const ShapeSpace& space = model.spaces[p];
            const detail::ViewSurface part_surface = surface.normals.rows()
                                                         ? detail::restricted(surface, space.point_indices, space.canonical)
                                                         : detail::ViewSurface();
            if (settings.variant == Variant::partwise) {
              parts[p - 1] = detail::search_poses(space, part_surface, observation, part_poses,
                                                  Eigen::VectorXd::Zero(space.dimensions()), part_settings,
                                                  /*whole_object=*/false);
              fitted.step("fitted " + space.name);
              continue;
            }
            const Observation& own = part_observations[p].tree ? part_observations[p] : observation;
            RegistrationSettings own_settings = fit_settings;
            if (!part_observations[p].tree)
              own_settings.objective.direction = Direction::canonical_to_observed;
            const Eigen::VectorXd latent =
                space.project_displacement(rows_of(holistic_displacement, space.point_indices));
            parts[p - 1] = detail::search_poses(space, part_surface, own, {whole.pose}, latent, own_settings,
                                                /*whole_object=*/false);
            fitted.step("fitted " + space.name);
          }
        },
        0, 1);
    for (std::size_t p = 1; p < model.spaces.size(); ++p) {
      const SpaceSolution& solution = parts[p - 1].best;
      const ShapeSpace& space = model.spaces[p];
      record(result, space.name, parts[p - 1], model, centroid);
      const Points posed = solution.pose.apply(space.deformed(solution.latent));
      for (std::size_t i = 0; i < space.point_indices.size(); ++i)
        deformed_normalised.row(space.point_indices[i]) = posed.row(static_cast<Eigen::Index>(i));
    }
  }
  result.stages.fits = clock.lap();
  if (settings.refinement.enabled) {
    const RefinementField field =
        refine_fit(deformed_normalised, without_strays(observation, deformed_normalised), observation.viewpoint,
                   settings.refinement);
    deformed_normalised += field.displacement_at(deformed_normalised);
    result.refinement = field.transformed(model.observed_diagonal(), centroid);
  }
  result.stages.refinement = clock.lap();
  result.deformed = (deformed_normalised * model.observed_diagonal()).rowwise() + centroid.transpose();
  result.part = model.canonical_part;
  const Points& statistics_observed = statistics_points ? *statistics_points : observed;
  result.fit = fit_statistics(result.deformed, statistics_observed, model.observed_diagonal());
  result.fit.strays = count_strays(observation, deformed_normalised);
  result.figures = trust_figures(model, statistics_observed, result, settings);
  result.assessment = judge(result.figures, settings.verdict);
  result.stages.statistics = clock.lap();
  result.seconds = result.stages.sum();
  return result;
}

}  // namespace

RegistrationResult register_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings,
                                        const ProgressListener& progress) {
  return register_from(model, observed, settings, nullptr, progress);
}

RegistrationResult register_observation(const CategoryModel& model, const Points& observed,
                                        const RegistrationSettings& settings, const WarmStart& start,
                                        const ProgressListener& progress) {
  return register_from(model, observed, settings, &start, progress);
}

}  // namespace partreg::core

namespace partreg::core {

WarmStart warm_start_of(const RegistrationResult& result) {
  if (result.fits.empty()) throw UsageError("the result holds no space fit to start from");
  WarmStart start;
  start.T_observed_canonical = result.fits.front().T_observed_canonical;
  if (result.variant != Variant::partwise) start.latent = result.fits.front().latent;
  start.score = result.pose_score;
  return start;
}

std::vector<RegistrationResult> register_sequence(const CategoryModel& model, const std::vector<Points>& frames,
                                                  const RegistrationSettings& settings,
                                                  const std::optional<WarmStart>& start) {
  std::vector<RegistrationResult> results;
  results.reserve(frames.size());
  std::optional<WarmStart> next = start;
  for (const Points& frame : frames) {
    results.push_back(next ? register_observation(model, frame, settings, *next)
                           : register_observation(model, frame, settings));
    next = warm_start_of(results.back());
  }
  return results;
}

}  // namespace partreg::core
