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
#include "observation.hpp"
#include "geometry/point_normals.hpp"
#include "pose_search.hpp"
#include "space_solver.hpp"

namespace partreg::core {
namespace {

using detail::count_strays;
using detail::Observation;
using detail::Pose;
using detail::prepare_observation;
using detail::SpaceSolution;
using detail::split_observation;
using detail::without_strays;

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
