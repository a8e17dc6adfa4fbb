#pragma once
// Part fields that agree at their seams (internal to partreg_core's training).
//
// Each part's CPD registers the canonical part alone onto the instance's part, so near a seam the two parts'
// fields send the same canonical place to different places of the instance: a handle's CPD does not know
// where on the body the handle is fixed. The shape spaces learned from those fields disagree at their seams
// even at the training instances' own latents (kettles: 2.5-8% of the diagonal on average), and a registration
// that holds the parts together (the coupled variant) then pays in accuracy for what the spaces cannot
// represent. The holistic CPD sees the whole object, so its field is one field across every seam.
//
// seam_agreeing_weights refits one part's weights so that its field follows the part's own CPD away from
// the seams and the holistic field near them (wholly within half the band, passing smoothly to the part's
// own over the outer half), on both sides: over its own points near another
// part and over the other parts' points near it (where the seam term and the seam gap evaluate it). The
// change is the smallest smooth correction of the part's own weights (kernel-ridge in the part's kernel).

#include <algorithm>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// 3t^2 - 2t^3 on [0, 1], clamped outside: 0 and 1 with zero slope at both ends, so weights built from it
/// have no kink at a band's edge (the seam blend of meshes and the seam refit of training).
inline double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// The seam geometry of one part, computed once per model: which canonical points take part in the refit
/// and how much of the holistic field each should follow.
struct PartSeam {
  std::vector<int> rows;   ///< canonical rows fitted: the part's own first (in its order), then neighbours'
  Eigen::VectorXd follow;  ///< per fitted row, the share of the holistic field in its target, in [0, 1]
  Eigen::VectorXd weight;  ///< per fitted row, its weight in the least-squares fit
  int own = 0;             ///< how many of `rows` are the part's own
};

/// The seam of part `part` (rows `part_rows` of `canonical`, labels `canonical_part`) within `band`
/// (normalised length) of the other parts.
PartSeam find_part_seam(const Points& canonical, const Eigen::VectorXi& canonical_part, int part,
                        const std::vector<int>& part_rows, double band);

/// The part's weights (`part_weights`, over its own canonical points) corrected so that its field meets
/// the holistic field (`holistic_weights`, over all of `canonical`) at the seam; `beta` is both fields'
/// kernel width. Returns `part_weights` unchanged when the part has no seam.
Points seam_agreeing_weights(const Points& canonical, const PartSeam& seam, const Points& part_weights,
                             const Points& holistic_weights, double beta);

}  // namespace partreg::core::detail
