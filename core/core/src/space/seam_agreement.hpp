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
// SeamRefit refits one part's weights so that its field follows the part's own CPD away from
// the seams and the holistic field near them (wholly within half the band, passing smoothly to the part's
// own over the outer half), on both sides: over its own points near another
// part and over the other parts' points near it (where the seam term and the seam gap evaluate it). The
// change is the smallest smooth correction of the part's own weights (kernel-ridge in the part's kernel).

#include <Eigen/Cholesky>
#include <algorithm>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// 3t^2 - 2t^3 on [0, 1], clamped outside: 0 and 1 with zero slope at both ends, so weights built from it
/// have no kink at a band's edge (the seam blend of meshes and the seam refit of training).
inline double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// The refit of one part's fields, prepared once per part: which canonical points take part, how much of the
/// holistic field each follows, and the factorised least-squares problem, which is the same for every
/// training instance (only the right-hand side changes).
class SeamRefit {
 public:
  /// Part `part` (rows `part_rows` of the normalised `canonical`, labels `canonical_part`), seam `band`
  /// (normalised length; 0 = no refit), both fields' kernel width `beta`.
  SeamRefit(const Points& canonical, const Eigen::VectorXi& canonical_part, int part,
            const std::vector<int>& part_rows, double band, double beta);

  /// The part's weights (`part_weights`, over its own canonical points) corrected so that its field meets
  /// the holistic field (`holistic_weights`, over all of the canonical) at the seam; unchanged when the part
  /// has no seam.
  Points apply(const Points& part_weights, const Points& holistic_weights) const;

 private:
  Points canonical_;       // the whole normalised canonical (the holistic field's centres)
  Points fitted_;          // the fitted points: the part's own first, then the neighbours' near it
  Eigen::VectorXd follow_; // per fitted point, the share of the holistic field in its target, in [0, 1]
  Eigen::VectorXd weight_; // per fitted point, its weight in the least-squares fit
  Eigen::MatrixXd kernel_; // G(fitted, own points)
  Eigen::LDLT<Eigen::MatrixXd> normal_;  // the fit's normal equations, factorised
  double beta_ = 0.0;
};

}  // namespace partreg::core::detail
