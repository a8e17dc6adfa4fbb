#pragma once
// Which parts' surfaces pass through a point (internal to partreg_core's training).
//
// Part files need not meet edge to edge: the kettles' lids are shells lying on their bodies' tops, so 20-29%
// of kettles 2-5's surface lies within 1% of the diagonal of another part's (50-88% of each lid within 0.5% of
// its body). A point sampled there carries the label of the file it was drawn from, which its
// position cannot tell; label propagation is judged against every part whose surface passes through it.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "partreg/core/types.hpp"

namespace partreg::core::detail {

/// Points x parts: true where that part's surface passes through the point.
using PartsThrough = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;

/// Which parts' faces pass within `tolerance` of each point. A face belongs to the part of each of its
/// vertices (`vertex_part`, one per mesh vertex), so one that straddles a labelled boundary counts for both
/// sides. Same units for all three; `part_count` columns.
PartsThrough parts_through_points(const Mesh& mesh, const Eigen::VectorXi& vertex_part, int part_count,
                                  const Points& points, double tolerance);

/// Distance from `p` to the triangle (a, b, c), degenerate triangles included.
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

}  // namespace partreg::core::detail
