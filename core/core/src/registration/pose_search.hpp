#pragma once
// The pose search of one space (internal to partreg_core): starting poses that cover what a robot meets (yaw
// all round the up axis, tilts of it, principal-axis flips, or rotations spread over SO(3)), pruned coarse to
// fine by successive halving, the survivors chosen by a score that agrees with the truth
// (docs/registration.md).

#include <vector>

#include "partreg/core/space/category_model.hpp"
#include "space_solver.hpp"

namespace partreg::core::detail {

/// The starting poses of `space` on `observation`: centroids aligned, rotations as the initialisation asks.
/// `centre` is the point put on the observation's centroid (normalised canonical frame); `canonical` gives
/// the principal axes.
std::vector<Pose> starting_poses(const Eigen::Vector3d& centre, const Points& canonical,
                                 const Observation& observation, const RegistrationSettings& settings);

/// What the search kept, and how clear the choice was.
struct SearchOutcome {
  SpaceSolution best;
  int hypotheses = 0;       ///< starting poses tried
  double best_score = 0.0;  ///< the winner's selection score (normalised length)
  double runner_up = 0.0;   ///< the best score among the other finalists (infinity when none)
  SpaceSolution runner_up_fit;  ///< that finalist's fit (empty latent when none)
  Pose best_start;          ///< where the winner started
};

/// Fits `space` from every pose in `starts`: each gets a few outer steps, the better half (by score) goes on
/// with twice the steps, until `InitialisationSettings::finalists` remain; those run to convergence and the
/// lowest score wins. `whole_object`: the space is the whole observed object (the holistic space), so after
/// the screening's first round the search weighs the prior by search_prior_weight at that round's best fit
/// (a part's fit against the whole observation would read the other parts as noise).
SearchOutcome search_poses(const ShapeSpace& space, const ViewSurface& surface,
                           const Observation& observation, const std::vector<Pose>& starts,
                           const Eigen::VectorXd& latent, const RegistrationSettings& settings,
                           bool whole_object);

/// The prior's weight for a search once `fit` is its best so far: noisy_prior_weight (mixture_fit.hpp) at the
/// noise the observation reads against the fit (point_normals.hpp's observed_noise); the settings' weight on
/// a view no noisier than the mixture's limit. On a noisy view a light prior lets a wrong pose fit by bending
/// the shape to the noise, and the screening keeps it (measured: docs/registration.md, "The prior").
double search_prior_weight(const ShapeSpace& space, const Observation& observation, const SpaceSolution& fit,
                           const ObjectiveSettings& objective);

/// The score of a fitted pose and latent by `InitialisationSettings::score`: the fit's cost, or the mean of
/// the robust (trimmed at the loss scale x 4) closest-point distances each way between the posed deformed
/// canonical points the viewpoint sees and the observation (normalised length); lower is better.
double fit_score(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                 const SpaceSolution& solution, const RegistrationSettings& settings);

/// The selection score: fit_score, with the observation's free space multiplied by 1 + free_space_weight
/// times the share of the posed deformed canonical points in front of the measured depth.
double selection_score(const ShapeSpace& space, const ViewSurface& surface, const Observation& observation,
                       const SpaceSolution& solution, const RegistrationSettings& settings);

}  // namespace partreg::core::detail
