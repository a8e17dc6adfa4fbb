// Which canonical points a viewpoint sees (core/core/src/geometry/visibility.hpp): occlusion by a depth
// buffer, with the facing test for grazing points. Shapes whose answer is known: a closed sphere and an open
// bowl.
#include "geometry/visibility.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "registration/space_solver.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core::detail {
namespace {

using testing::fibonacci_sphere;
using testing::open_bowl;

TEST(Visibility, ASphereHidesItsFarSideAndKeepsItsRim) {
  const Points points = fibonacci_sphere(3000, 0.3);  // about as dense as a canonical of 1000 points, diagonal 1
  const Eigen::Vector3d viewpoint(0.0, 0.0, 2.0);
  const ViewSurface surface = view_surface(points);
  const std::vector<bool> seen = visible_rows(points, surface, Pose(), viewpoint);
  // The depth buffer alone, as if no point faced the viewpoint.
  const std::vector<bool> unoccluded =
      seen_rows(points, std::vector<bool>(static_cast<std::size_t>(points.rows()), false), viewpoint, surface.spacing);
  int far_seen = 0, near_hidden = 0, rim = 0, rim_seen = 0, rim_unoccluded = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double z = points(i, 2);
    if (z < -0.05) far_seen += seen[i];
    if (z > 0.1) near_hidden += !seen[i];
    // Just inside the rim as the viewpoint sees it (its rays graze the sphere at z = 0.3^2 / 2 = 0.045).
    if (z > 0.05 && z < 0.1) ++rim, rim_seen += seen[i], rim_unoccluded += unoccluded[i];
  }
  EXPECT_EQ(far_seen, 0) << "the far side is behind the near side";
  EXPECT_EQ(near_hidden, 0) << "nothing is in front of the near side";
  ASSERT_GT(rim, 20);
  std::cout << "rim: " << rim << " points, " << rim_seen << " seen, " << rim_unoccluded << " by depth alone\n";
  EXPECT_GE(rim_seen, 0.8 * rim) << "grazing points face the viewpoint and are kept";
  EXPECT_LT(rim_unoccluded, 0.5 * rim) << "the buffer alone loses them: the facing clause is what keeps them";
}

TEST(Visibility, ABowlSeenFromAboveShowsItsInsideThoughItsNormalsPointOut) {
  const Points points = open_bowl(1600);
  const Eigen::Vector3d viewpoint(0.0, 3.0, 0.0);
  const ViewSurface surface = view_surface(points);
  const std::vector<bool> facing = facing_rows(points, surface, Pose(), viewpoint);
  const std::vector<bool> seen = visible_rows(points, surface, Pose(), viewpoint);
  int inside = 0, inside_facing = 0, inside_seen = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (points.row(i).norm() < 0.46 && points(i, 1) < -0.3) {  // the inner surface's floor
      ++inside;
      inside_facing += facing[i];
      inside_seen += seen[i];
    }
  ASSERT_GT(inside, 50);
  // Normals turned away from the centroid point down, into the wall, on the floor of a bowl: the facing test
  // alone hides the very surface the camera looks at.
  EXPECT_LT(inside_facing, 0.1 * inside);
  EXPECT_EQ(inside_seen, inside) << "nothing lies in front of the bowl's floor";
}

TEST(Visibility, WithoutAViewpointEveryPointCounts) {
  const Points points = fibonacci_sphere(200, 0.5);
  const std::vector<bool> seen = visible_rows(points, view_surface(points), Pose(), std::nullopt);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 200);
}

}  // namespace
}  // namespace partreg::core::detail
