#pragma once
/// \file
/// A fit beyond the shape space: the space fit is as good as the training set's shapes allow;
/// the refinement lets the observed regions reach what the sensor saw. It is non-rigid CPD (Myronenko &
/// Song 2010) with three changes: it starts at the space fit with the fit's own residual variance, only the
/// canonical points that were observed take part in the E-step, and the others are pulled back to the
/// space's prediction (an anchor), so unseen regions keep the space's plausible shape. The field is a
/// Gaussian kernel field on landmarks of the fitted points, v(p) = sum_l g(p, c_l) w_l, so a mesh vertex,
/// any point or a frame moved by the space follows by evaluating v where the space put it (deformation.hpp).

#include <Eigen/Core>
#include <optional>

#include "partreg/core/registration/registration_settings.hpp"
#include "partreg/core/types.hpp"

namespace partreg::core {

/// The refinement's displacement field, in the frame of the points it was fitted to (after the pose).
struct RefinementField {
  Points centres;  ///< kernel centres c_l: landmarks of the space fit's points (frame units); none = no field
  Points weights;  ///< w_l, one row per centre (frame units)
  double beta = 0.0;  ///< kernel width (frame units)
  /// The space fit's points (frame units) and a unit normal per point: where material points may move.
  Points surface, surface_normals;
  int points = 0;     ///< fitted points refined
  int observed = 0;   ///< of those, the ones treated as observed (pulled to the data)
  /// The observation's noise (normalised length): the median over patches of the fit of the spread of the
  /// observed points' offsets from it. 0 when nothing was seen.
  double noise = 0.0;
  /// The kernel width used (normalised length): RefinementSettings::beta, or noise_width x noise when that is
  /// wider. 0 when nothing was seen.
  double width = 0.0;
  int matched = 0;  ///< observed points the E-step matched: all but the strays (far from the fit and alone)
  /// The E-step's outlier weight w: RefinementSettings::outlier_weight, or the share of observed points left
  /// out as strays when that is larger (at most 0.5). 0 when nothing was seen.
  double outlier_weight = 0.0;
  int iterations = 0;  ///< EM iterations run
  double seconds = 0.0;
  /// How far the field moved the fitted points: mean and largest |v(p)| over them, in normalised length (the
  /// model's diagonal is 1; transformed() leaves them so). 0 when empty.
  double mean_movement = 0.0, max_movement = 0.0;

  bool empty() const { return centres.rows() == 0; }
  /// v(p) at every row of `positions` (frame units); zeros when empty: how the refined surface moves.
  Points displacement_at(const Points& positions) const;
  /// v(p) projected on the space fit's surface normal near p (frame units): how a material point moves.
  /// The field may slide the surface along itself to reach the data (its tangential part changes the
  /// surface hardly at all); what is attached to material points (grasps, frames, labels) must not slide
  /// with it: on synthetic mugs the full field put material points 5-7 times the surface error off.
  /// The full field when `surface` is empty (a field read from an older result).
  Points material_displacement_at(const Points& positions) const;
  /// The same field in the frame p' = scale p + offset (scale > 0).
  RefinementField transformed(double scale, const Eigen::Vector3d& offset) const;
};

/// Refines `fitted` (the space fit's points, one per canonical point) towards `observed`, both in one frame
/// whose lengths are normalised (the model's diagonal is 1: settings' lengths are in it). `viewpoint` is the
/// camera position in that frame, if known; without it, the gate alone decides what was observed (a stated
/// fallback: a point near the observation counts as seen). Fewer than 10 observed points leave nothing to
/// refine: the field comes back empty. InputError for fewer than 10 or non-finite points in either set;
/// UsageError for settings out of range.
RefinementField refine_fit(const Points& fitted, const Points& observed,
                           const std::optional<Eigen::Vector3d>& viewpoint,
                           const RefinementSettings& settings);

}  // namespace partreg::core
