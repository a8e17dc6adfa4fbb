#pragma once
// Which canonical points the viewpoint sees (internal to partreg_core): the canonical half of the objective,
// the pose search's score and the mixture's centres use only those.

#include <Eigen/Core>
#include <vector>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// What the visibility test needs of a set of canonical points (empty without a viewpoint).
struct ViewSurface {
  Points normals;        ///< outward normals, one per point (point_normals.hpp)
  double spacing = 0.0;  ///< median distance from a point to its nearest neighbour (normalised length)
};

/// The normals and spacing of `points`.
ViewSurface view_surface(const Points& points);

/// The same surface restricted to `rows` of it, whose points are `points` (a part, or a sparser subset: the
/// spacing is measured again).
ViewSurface restricted(const ViewSurface& surface, const std::vector<int>& rows, const Points& points);

/// Which of the posed points `posed` (normalised observed frame) the `viewpoint` sees. `facing`: each point's
/// normal faces the viewpoint. A point is seen when nothing lies in front of it by more than two spacings, or
/// when it faces the viewpoint and nothing lies in front of it by more than six ("depth" is measured in a
/// buffer of the points splatted one spacing wide). Occlusion alone is coarse at a thousand points and loses
/// the grazing points of a convex body, which face the viewpoint; facing alone is wrong inside concave shells,
/// where normals turned away from the centroid point into the wall, and it sees through the body.
std::vector<bool> seen_rows(const Points& posed, const std::vector<bool>& facing, const Eigen::Vector3d& viewpoint,
                            double spacing);

}  // namespace partreg::core::detail
