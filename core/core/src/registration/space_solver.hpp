#pragma once
// Fitting one shape space and a pose to an observation with Ceres (internal to partreg_core).

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

namespace ceres {
class Problem;
}

#include "moment_cost.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "geometry/visibility.hpp"
#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/core/space/shape_space.hpp"

namespace partreg::core::detail {

/// The observation in normalised units: centred on its centroid, divided by the model's diagonal.
struct Observation {
  Points points;                             ///< downsampled, normalised
  std::unique_ptr<KdTree> tree;              ///< over `points`
  std::optional<Eigen::Vector3d> viewpoint;  ///< normalised observed frame
  /// Per point: it stands alone (sampling.hpp's rows_with_neighbours left it out). Such a point is matched only
  /// while the fit passes within kStrayReach of it; empty: none stands alone.
  std::vector<bool> alone;
  /// The camera's free space with its T_camera_observed reading normalised points (empty: none given).
  std::shared_ptr<const FreeSpace> free_space;
};

/// An observed point that stands alone and is farther than this from the fit (normalised length) is a stray:
/// neither the space fit nor the refinement matches it. A thinly seen surface (a handle edge-on) lies within
/// it once the fit is near; most outliers off the surface do not. About the space fit's own error on a partial
/// view; chosen, not tuned (docs/registration.md, "Strays").
constexpr double kStrayReach = 0.03;

/// A similarity in normalised units: observed = scale * rotation * canonical + translation.
struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;
  Points apply(const Points& points) const;
};

struct SpaceSolution {
  Eigen::VectorXd latent;
  Pose pose;
  double cost = 0.0;
  int iterations = 0;
  bool converged = false;  ///< false: stopped at the iteration limit or for lack of correspondences
  bool had_pairs = true;   ///< false: a refresh found no correspondence
  double seconds = 0.0;
  std::vector<std::pair<Eigen::VectorXd, Pose>> steps;  ///< latent and pose after every outer step
  std::vector<double> step_costs, step_seconds;
};

/// One closest-point pair of a step.
struct Pair {
  int row;                 ///< row of the posed canonical points
  Eigen::Vector3d target;  ///< observed point (normalised)
  double squared_distance;
};

/// A step's pairs, by the direction they were found in (each empty when its direction is not summed).
struct Correspondences {
  std::vector<Pair> from_canonical, from_observed;
};

/// The last step's closest points by index, kept by a solver from one correspondence step to the next: the
/// points move a little between steps, so each search starts from its last answer (KdTree::nearest with a
/// hint) and visits a small part of the tree. The pairs are the same as without.
struct CorrespondenceHints {
  std::vector<int> observed_of_row;  ///< per posed row: its last nearest observed point (-1: none yet)
  std::vector<int> row_of_observed;  ///< per observed point: its last nearest posed row (-1: none yet)
};

/// Whether observed point `n`, at `squared_distance` from the fit, is a stray (Observation::alone).
bool is_stray(const Observation& observation, Eigen::Index n, double squared_distance);

/// The closest-point pairs between the `visible` rows of `posed` and the observation, in the directions the
/// objective sums over, trimmed when the loss is trimmed. `hints` (optional) is read and updated.
Correspondences correspond(const Points& posed, const std::vector<bool>& visible,
                           const Observation& observation, const RegistrationSettings& settings,
                           CorrespondenceHints* hints = nullptr);

/// The pairs weighted for one IRLS step: the robust loss's weight at each pair's distance times its
/// direction's 1 / count.
std::vector<WeightedPair> weighted_pairs(const Correspondences& pairs, const RegistrationSettings& settings);

/// Which rows of `posed` (a space's posed canonical points, `surface` theirs) face the viewpoint by their
/// normals under `pose`; all of them without a viewpoint.
std::vector<bool> facing_rows(const Points& posed, const ViewSurface& surface, const Pose& pose,
                              const std::optional<Eigen::Vector3d>& viewpoint);

/// Which rows of `posed` the viewpoint sees (visibility.hpp's seen_rows); all of them without a viewpoint.
std::vector<bool> visible_rows(const Points& posed, const ViewSurface& surface, const Pose& pose,
                               const std::optional<Eigen::Vector3d>& viewpoint);

/// The pose's constraints every solver applies: the rotation on the quaternion manifold, the scale fixed or
/// kept above 0.2.
void constrain_pose(ceres::Problem& problem, double* rotation, double* scale,
                    const RegistrationSettings& settings);

/// Runs Ceres on `problem` for the inner iterations the settings allow (dense normal Cholesky: a few dozen
/// unknowns; one thread, since parts and hypotheses run in parallel above); returns the final cost.
double solve_inner(ceres::Problem& problem, const RegistrationSettings& settings);

/// Fits `space` from the initial latent and pose. `surface`: the space's canonical points' normals and spacing
/// (used only with a viewpoint). `hints` (optional): the closest points of an earlier fit of the same
/// space to the same observation, read and updated (a fit continued in rounds keeps them between rounds).
SpaceSolution solve_space(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                          const Eigen::VectorXd& initial_latent, const Pose& initial_pose,
                          const RegistrationSettings& settings, CorrespondenceHints* hints = nullptr);

}  // namespace partreg::core::detail
