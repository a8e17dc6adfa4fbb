#include "seam_weight_choice.hpp"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "partreg/core/geometry/sampling.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/registration.hpp"
#include "geometry/visibility.hpp"

namespace partreg::core::detail {
namespace {

constexpr std::size_t kMostHeldOut = 8;
// Another weight replaces kDefaultSeamWeight only when its mean error is this much lower. The default was
// measured best on kettles' full views with the full pose search, which the choice leaves out to stay cheap;
// the kettles' candidates then lie within 1% of each other, the mugs' and spray bottles' best 5-10% below it.
constexpr double kClearMargin = 0.02;

// The partial views' directions: a tetrahedron's corners, so four views between them see every side.
std::vector<Eigen::Vector3d> view_directions() {
  return {Eigen::Vector3d(1, 1, 1).normalized(), Eigen::Vector3d(1, -1, -1).normalized(),
          Eigen::Vector3d(-1, 1, -1).normalized(), Eigen::Vector3d(-1, -1, 1).normalized()};
}

// What a held-out instance is observed as: its whole sample, then what each direction's viewpoint sees of it
// (normalised units; the camera 1.5 diagonals from the centre, as the evaluation's depth camera stands).
struct Observation {
  Points points;
  std::optional<Eigen::Vector3d> viewpoint;
};

std::vector<Observation> observations_of(const Points& sample) {
  std::vector<Observation> views{{sample, std::nullopt}};
  const ViewSurface surface = view_surface(sample);
  const Eigen::Vector3d centre =
      0.5 * (sample.colwise().minCoeff() + sample.colwise().maxCoeff()).transpose();
  for (const Eigen::Vector3d& direction : view_directions()) {
    const Eigen::Vector3d viewpoint = centre + 1.5 * direction;
    std::vector<bool> facing(static_cast<std::size_t>(sample.rows()));
    for (Eigen::Index i = 0; i < sample.rows(); ++i)
      facing[static_cast<std::size_t>(i)] =
          surface.normals.row(i).dot(viewpoint - sample.row(i).transpose()) > 0.0;
    const std::vector<bool> seen = seen_rows(sample, facing, viewpoint, surface.spacing);
    std::vector<int> rows;
    for (std::size_t i = 0; i < seen.size(); ++i)
      if (seen[i]) rows.push_back(static_cast<int>(i));
    if (rows.size() >= 50) views.push_back({select_rows(sample, rows), viewpoint});
  }
  return views;
}

// `model` with every space learned again from the training fields without instance `held_out`.
CategoryModel without_instance(const CategoryModel& model, const std::vector<std::vector<Points>>& fields,
                               std::size_t held_out, const TrainingSettings& settings) {
  CategoryModel reduced = model;
  PcaEmSettings pca;
  pca.dimensions = settings.latent_dimensions;
  pca.seed = settings.seed;
  for (std::size_t s = 0; s < model.spaces.size(); ++s) {
    const ShapeSpace& space = model.spaces[s];
    std::vector<Points> kept;
    for (std::size_t i = 0; i < fields[s].size(); ++i)
      if (i != held_out) kept.push_back(fields[s][i]);
    reduced.spaces[s] =
        learn_shape_space(space.name, space.point_indices, select_rows(model.canonical, space.point_indices),
                          space.beta, kept, pca);
  }
  return reduced;
}

// The symmetric RMS error (fraction of the diagonal) of each candidate on each observation of `sample`.
std::vector<std::vector<double>> errors_of(const CategoryModel& model, const Points& sample,
                                           const std::vector<double>& candidates) {
  const Points truth = model.normalization.undo(sample);
  const KdTree truth_tree(truth);
  const double diagonal = truth_diagonal(truth);
  std::vector<std::vector<double>> errors(candidates.size());
  for (const Observation& view : observations_of(sample)) {
    RegistrationSettings settings;
    settings.variant = Variant::coupled;
    // The instance lies in the category's frame: one start there, so the weights are compared on the fit,
    // not on which of many starts the search settles in.
    settings.initialisation.restarts = 1;
    settings.initialisation.max_tilt = 0.0;
    if (view.viewpoint)
      settings.viewpoint = model.normalization.undo(Points(view.viewpoint->transpose())).row(0);
    const Points observed = model.normalization.undo(view.points);
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      settings.objective.seam_weight = candidates[c];
      const RegistrationResult result = register_observation(model, observed, settings);
      errors[c].push_back(
          measure_against_truth(result.deformed, result.part, model.part_names, truth_tree, diagonal)
              .symmetric_rms_per_diagonal);
    }
  }
  return errors;
}

}  // namespace

std::vector<std::size_t> seam_weight_held_out(std::size_t instances, std::size_t canonical_index,
                                              const std::vector<double>& candidates) {
  if (candidates.size() < 2 || instances < 3) return {};
  std::vector<std::size_t> others;
  for (std::size_t i = 0; i < instances; ++i)
    if (i != canonical_index) others.push_back(i);
  if (others.size() <= kMostHeldOut) return others;
  std::vector<std::size_t> spread;
  for (std::size_t k = 0; k < kMostHeldOut; ++k) spread.push_back(others[k * others.size() / kMostHeldOut]);
  return spread;
}

SeamWeightChoice choose_seam_weight(const CategoryModel& model,
                                    const std::vector<std::vector<Points>>& fields,
                                    const std::vector<Points>& samples, std::size_t canonical_index,
                                    const TrainingSettings& settings,
                                    const std::function<void(const std::string&)>& step) {
  const std::vector<double>& candidates = settings.seam_weight_candidates;
  const std::vector<std::size_t> held_out = seam_weight_held_out(samples.size(), canonical_index, candidates);
  if (held_out.empty())
    return {candidates[candidates.size() / 2],
            candidates.size() == 1 ? "given" : "the middle candidate: too few instances to choose"};

  // Each held-out instance is one job; its registrations run on one thread each, so jobs run side by side.
  std::vector<std::vector<std::vector<double>>> errors(held_out.size());
  parallel_for(
      static_cast<Eigen::Index>(held_out.size()),
      [&](Eigen::Index begin, Eigen::Index end) {
        const ThreadBudget one(1);
        for (Eigen::Index k = begin; k < end; ++k) {
          const std::size_t i = held_out[static_cast<std::size_t>(k)];
          errors[static_cast<std::size_t>(k)] =
              errors_of(without_instance(model, fields, i, settings), samples[i], candidates);
        }
      },
      0, 1);
  // Reported here, on the caller's thread: a listener (a Python callback) need not be thread-safe.
  for (std::size_t i : held_out)
    if (step)
      step("seam weight: held out instance " + std::to_string(i + 1) + " of " +
           std::to_string(samples.size()));

  std::vector<double> means;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    std::vector<double> all;
    for (const auto& instance : errors) all.insert(all.end(), instance[c].begin(), instance[c].end());
    means.push_back(std::accumulate(all.begin(), all.end(), 0.0) / static_cast<double>(all.size()));
  }
  std::size_t best = static_cast<std::size_t>(std::min_element(means.begin(), means.end()) - means.begin());
  const auto standing = std::find(candidates.begin(), candidates.end(), kDefaultSeamWeight);
  const auto standing_index = static_cast<std::size_t>(standing - candidates.begin());
  const bool kept = standing != candidates.end() && best != standing_index &&
                    means[best] > (1.0 - kClearMargin) * means[standing_index];
  if (kept) best = standing_index;
  std::ostringstream text;
  text << "coupled registrations of " << held_out.size()
       << " held-out instances' own views (whole and 4 partial), mean symmetric RMS % of the diagonal:";
  for (std::size_t c = 0; c < candidates.size(); ++c)
    text << (c ? ", " : " ") << candidates[c] << ": " << 100.0 * means[c];
  if (kept)
    text << "; the default " << kDefaultSeamWeight << " stays unless another is " << 100.0 * kClearMargin
         << "% lower";
  std::vector<SeamWeightTrial> trials;
  for (std::size_t c = 0; c < candidates.size(); ++c) trials.push_back({candidates[c], means[c]});
  return {candidates[best], text.str(), trials};
}

}  // namespace partreg::core::detail
