#pragma once
// Normals of a point set without a surface (internal to partreg_core): the registration's visibility test
// and the refinement's both use them.

#include <utility>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// Unit normal per point: the smallest principal direction of its neighbours within `radius` (units of the
/// points), turned away from the set's centroid (right for convex-ish objects; a mug's inner wall is not).
Points outward_normals(const Points& points, double radius);

/// The scatter matrix (sum of outer products about their mean) of the rows of `points` listed in
/// `neighbours` (index, squared distance pairs, as KdTree returns them), and their mean in `mean`.
Eigen::Matrix3d neighbourhood_scatter(const Points& points, const std::vector<std::pair<int, double>>& neighbours,
                                      Eigen::Vector3d& mean);

}  // namespace partreg::core::detail
