#pragma once
// The coupled part registration (internal to partreg_core): one Ceres problem over the object's pose, every
// part's latent and a small rigid offset per part from that pose, with a prior keeping the offsets near zero
// and a seam term holding neighbouring parts together.
//
// Part p moves its canonical points y (deformed by its space) to s R0 (R_p (y - c_p) + c_p + d_p) + t0:
// the object's pose (R0, t0, s) after the part's offset (R_p, d_p), which turns about the part's canonical
// centroid c_p so that its rotation and translation stay apart. As a similarity that is the pose
// (R0 R_p, s R0 (c_p + d_p - R_p c_p) + t0, s), so each part's data term is the MomentCost of its space at
// that pose. The objective (normalised lengths):
//   data:   sum over the object's closest-point pairs of the robust weight times the squared distance, each
//           direction weighed by 1 / its count (as the other variants), every pair going to its point's part
//   prior:  prior_weight s_p sum_k x_pk^2 / var_pk, per part, s_p the part's share of the step's pair weights
//           (part_prior_weights)
//   offset: offset_weight (|d_p|^2 + rho_p^2 |r_p|^2), r_p the offset's angle-axis, rho_p the part's
//           RMS radius
//   seam:   seam_weight * the mean over seam points z of |m_a(z) - m_b(z)|^2, where
//           m_p(z) = R_p (z + G(z, C_p) W_p(x_p) - c_p) + c_p + d_p is part p's motion of z before the shared
//           object pose (which moves both sides alike, so the gap is pose-free up to the scale)

#include <memory>
#include <vector>

#include "moment_cost.hpp"
#include "partreg/core/space/category_model.hpp"
#include "pose_search.hpp"
#include "space_solver.hpp"

namespace partreg::core::detail {

/// One part's data term (and its latent prior) at the part's effective pose, with exact derivatives: the
/// MomentCost of `space` chained through the offset pose about `centre` (normalised canonical frame).
/// Parameter blocks: object rotation (Eigen quaternion x, y, z, w), object translation (3), scale (1),
/// offset rotation (angle-axis, radians, 3), offset translation (3), latent (q). Exposed for its test.
std::unique_ptr<ceres::CostFunction> make_part_data_cost(const ShapeSpace& space,
                                                         const std::vector<WeightedPair>& pairs,
                                                         double prior_weight, const Eigen::Vector3d& centre);

/// Each part's latent prior weight in a step whose pairs, by part, are `pairs`: `prior_weight` times the
/// part's share of the pairs' total weight, so that a part's prior weighs against its own data as a single
/// space's prior weighs against the whole observation (holistic, and each part of hol+part). Undivided, the
/// prior of a handle holding a tenth of the pairs weighed ten times as much against its data as the holistic
/// fit's does (measured: docs/variants.md, "The coupled variant"). A part without
/// pairs gets none: the seams and its start hold it. No pairs at all: the weight as given, for every part.
std::vector<double> part_prior_weights(const std::vector<std::vector<WeightedPair>>& pairs,
                                       double prior_weight);

/// The seam term of parts a and b at the points `z` (normalised canonical frame), with exact derivatives:
/// root_weight (m_a(z) - m_b(z)), three residuals per point. Parameter blocks: part a's offset rotation
/// (angle-axis, 3), offset translation (3) and latent (q_a), then part b's. Exposed for its test.
std::unique_ptr<ceres::CostFunction> make_seam_cost(const ShapeSpace& a, const Eigen::Vector3d& centre_a,
                                                    const ShapeSpace& b, const Eigen::Vector3d& centre_b,
                                                    const Points& z, double root_weight);

/// Fits every part of `model` jointly, starting from the holistic fit `holistic` (its pose for the object,
/// its deformation projected into each part's space for the latents, zero offsets). `surface`: the
/// holistic canonical points' normals and spacing (used only with a viewpoint). Returns one outcome per part
/// space (model.spaces[1..]), each with its part's effective pose (object pose then offset) and latent, the
/// joint cost and the joint steps.
/// With `mixture_targets` (a noisy observation), the closest-point steps are followed by a finish in the
/// Gaussian mixture of those points (mixture_fit.hpp) centred on the `centres` rows of the canonical
/// (mixture_centres); nullptr: closest points only.
std::vector<SearchOutcome> solve_coupled(const CategoryModel& model, const ViewSurface& surface,
                                         const Observation& observation, const SpaceSolution& holistic,
                                         const RegistrationSettings& settings, const Points* mixture_targets,
                                         const std::vector<bool>& centres);

}  // namespace partreg::core::detail
