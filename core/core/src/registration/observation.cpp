#include "observation.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/geometry/sampling.hpp"

namespace partreg::core::detail {
namespace {

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

}  // namespace

Observation prepare_observation(const CategoryModel& model, const Points& observed,
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

Points without_strays(const Observation& observation, const Points& fitted) {
  return observation.alone.empty() ? observation.points
                                   : select_rows(observation.points, rows_near(observation, fitted));
}

int count_strays(const Observation& observation, const Points& fitted) {
  return observation.alone.empty() ? 0
                                   : static_cast<int>(observation.points.rows() -
                                                      static_cast<Eigen::Index>(rows_near(observation, fitted).size()));
}

}  // namespace partreg::core::detail
