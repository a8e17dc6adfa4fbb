#pragma once
/// \file
/// Carrying what is attached to the canonical onto the observed object (paper, Eq. 4): the canonical mesh,
/// any points, and frames (a grasp pose as position plus rotation). Points move by the registered
/// deformation field v(z) = G(z, C) W(x) and then by the pose. With part-based variants each part's field
/// and pose apply near that part, blended smoothly where parts meet (SeamBlend), so no triangle tears.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"

namespace partreg::core {

/// A frame attached to the canonical, in the category's data frame.
struct Frame {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< columns: the frame's axes
};

/// How part fields are blended where parts meet. Each point z has a distance d_s(z) to the canonical points
/// of every space s taking part; with d(z) their smallest, space s weighs smoothstep(1 - (d_s - d) / band)
/// and the weights are divided by their sum (a partition of unity). Away from seams the nearest part moves
/// a point alone; across a seam the weights pass from one part to the other over about one band, so the
/// mesh stretches instead of tearing. Measured on the real mug's handle (docs/registration.md).
struct SeamBlend {
  /// Width of the seam band (normalised length: the canonical's diagonal is 1). 0 = no blending: every
  /// point follows its nearest part alone (the deformation that tears meshes, kept for comparison). 0.2
  /// keeps every edge of the real mug within 2.9x its canonical length on the parts' +-2 sd grids (0.1:
  /// 4.8x, 0.05: 5.2x, 0: 20x; wider bands let a part's field reach too far into its neighbour).
  double band = 0.2;
};

/// Blend weights (rows of `normalised`, one column per entry of `spaces`; every row sums to 1) of the
/// spaces' fields at `normalised` points (normalised units), as SeamBlend describes. Throws UsageError for
/// a negative band or no space.
Eigen::MatrixXd seam_weights(const std::vector<const ShapeSpace*>& spaces, const Points& normalised,
                             const SeamBlend& blend = {});

/// What a moved point is: a point of the registered surface (the refinement's whole field moves it), or a
/// material point that carries something (the refinement moves it only along the surface normal, so it
/// does not slide: RefinementField::material_displacement_at).
enum class Follow { surface, material };

/// Moves points given in the canonical data frame into the observed frame as the registration moved the
/// canonical.
Points deform_points(const CategoryModel& model, const RegistrationResult& result,
                     const Points& canonical_points, const SeamBlend& blend = {}, Follow follow = Follow::surface);

/// The canonical mesh deformed into the observed frame (same faces): deform_points of its vertices, except
/// where that turns a face over against the posed canonical or stretches an edge beyond 3x: there, and two
/// rings of vertices around, the displacement is smoothed (screened, then harmonic, in rounds over a growing
/// region) as far as removes the faults without moving any vertex more than 5% of the diagonal; a fold that
/// needs more is left as the field made it. Held-out ShapeNet mugs, 24 default registrations: 3394 faces
/// turned over after the repair against 8924 before (18 registrations with any against 22).
Mesh deform_mesh(const CategoryModel& model, const RegistrationResult& result, const SeamBlend& blend = {});

/// How far the registration stretched the canonical mesh: the largest ratio of an edge's length in
/// deform_mesh to its canonical length (the pose moves lengths not at all, a fitted scale does). The
/// shape-space grid's figure is space_grid_stretch (space_walk.hpp); this is any registration's, refinement
/// included. 0 for a model without a canonical mesh.
double mesh_stretch(const CategoryModel& model, const RegistrationResult& result);

/// How far a registration's parts came apart: canonical points of one part within `radius` of another
/// part's canonical points are boundary points; each is moved by both parts' fields and poses, and the gap is
/// the distance between the two positions.
struct SeamGap {
  double max = 0.0;   ///< largest gap over the boundary points (fraction of the model's diagonal)
  double mean = 0.0;  ///< mean gap (fraction of the model's diagonal)
  int points = 0;     ///< boundary points measured (0: no part result, or no boundary)
};

/// The seam gap of a part-based result (boundary radius in normalised length; 0.03 is about one canonical
/// point spacing at M = 1000). A holistic result has no seam: all zeros.
SeamGap seam_gap(const CategoryModel& model, const RegistrationResult& result, double radius = 0.03);

/// The seam gap of the part spaces themselves: each training instance's own latents in every part space,
/// every part at the identity pose, averaged over the instances (mean of their means, largest of their
/// largest). How far apart the spaces put the parts of the shapes they were trained on: near zero when they
/// can represent attached parts (training's seam band), several percent without it. Zeros without parts.
SeamGap training_seam_gap(const CategoryModel& model, double radius = 0.03);

/// A region of the canonical around some anchors: rows of CategoryModel::canonical within three `radius` of
/// an anchor (and at least the 8 nearest each), each weighted by a Gaussian of width `radius` (normalised
/// length) of its distance to the nearest anchor (category data frame).
struct Region {
  std::vector<int> rows;
  Eigen::VectorXd weights;
};
std::vector<Region> frame_regions(const CategoryModel& model, const std::vector<Points>& anchor_sets,
                                  double radius);

/// The best rotation (weighted Kabsch, no scale) taking `before` to `after` (rows paired); where the points
/// leave axes free (a line), the turn about them is `free_axes_rotation`'s.
Eigen::Matrix3d region_motion(const Points& before, const Points& after, const Eigen::VectorXd& weights,
                              const Eigen::Matrix3d& free_axes_rotation);

/// How a registration turns regions of the canonical, one rotation per set of anchors: the best rotation
/// (weighted Kabsch, no scale) taking the canonical points near a set's anchors (category data frame) to
/// where deform_points puts them, each weighted by a Gaussian of its distance to the nearest anchor of width
/// `radius` (normalised length). A region at the scale of what is attached (a grasp's finger contacts) turns
/// as a whole, where the pointwise Jacobian inside a thin wall turned frames by tens of degrees. A region
/// too thin to fix a rotation (points on a line) keeps the pose's turn about the axis it leaves free.
std::vector<Eigen::Matrix3d> region_rotations(const CategoryModel& model, const RegistrationResult& result,
                                              const std::vector<Points>& anchor_sets, double radius);

/// The width of the region a frame's rotation is read from (normalised length): with the 8 nearest canonical
/// points a region always takes, about one canonical spacing at M = 1000. A frame on the synthetic mug's
/// handle turned 9.5 degrees off the truth at 0.01, 14.5 at 0.02, 16.1 at 0.03 (core_registration_test).
inline constexpr double kFrameRegionRadius = 0.015;

/// Frames carried over: the position moves like a material point (deform_points, Follow::material); the rotation turns with the region
/// around it (region_rotations, `radius` in normalised length).
std::vector<Frame> transfer_frames(const CategoryModel& model, const RegistrationResult& result,
                                   const std::vector<Frame>& frames, double radius = kFrameRegionRadius);

}  // namespace partreg::core
