#pragma once
// Normals of a point set without a surface (internal to partreg_core): the registration's visibility test
// and the refinement's both use them, and so does the noise read along them.

#include <utility>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// Unit normal per point: the smallest principal direction of its neighbours within `radius` (units of the
/// points), turned away from the set's centroid (right for convex-ish objects; a mug's inner wall is not).
Points outward_normals(const Points& points, double radius);

/// outward_normals of canonical points in the normalised frame (the model's diagonal is 1, about 1000
/// points): a radius of 0.05 spans a few canonical spacings.
Points canonical_normals(const Points& points);

/// The observation's noise (normalised length) against a fit of it: the median spread, along the fit's
/// `normals`, of the observed points around each small patch of fitted points (definition: point_normals.cpp).
/// The refinement widens its kernel with it; the registration finishes its space fits in a Gaussian mixture
/// above RegistrationSettings' mixture_noise.
double observed_noise(const Points& observed, const Points& fitted, const Points& normals);

/// observed_noise along the fitted canonical points' own normals (canonical_normals): the read that decides
/// the mixture and the pose search's prior.
double observed_noise(const Points& observed, const Points& fitted);

}  // namespace partreg::core::detail
