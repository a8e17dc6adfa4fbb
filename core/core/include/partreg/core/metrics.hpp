#pragma once
/// \file
/// Registration errors against a ground-truth instance (paper, section 4).

#include "partreg/core/types.hpp"

namespace partreg::core {

/// The paper's Eq. 5: mean over the deformed canonical points of the squared distance to the closest point of
/// the ground-truth instance (squared units of the inputs).
double closest_point_error(const Points& deformed, const Points& truth);

/// Symmetric Chamfer distance: the mean closest-point distance from a to b plus that from b to a, halved
/// (units of the inputs).
double chamfer_distance(const Points& a, const Points& b);

}  // namespace partreg::core
