// Which parts' surfaces pass through a point (core/core/src/training/part_surfaces.hpp): the truth label
// propagation is judged against where two part files lie on one another.
#include "training/part_surfaces.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace partreg::core::detail {
namespace {

TEST(PartSurfaces, PointTriangleDistanceFromTheFaceItsEdgesAndCorners) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(point_triangle_distance({0.2, 0.2, 0.5}, a, b, c), 0.5, 1e-12);       // above the face
  EXPECT_NEAR(point_triangle_distance({0.5, -0.3, 0.4}, a, b, c), 0.5, 1e-12);      // beside edge ab
  EXPECT_NEAR(point_triangle_distance({1, 1, 0}, a, b, c), std::sqrt(0.5), 1e-12);  // beyond the hypotenuse
  EXPECT_NEAR(point_triangle_distance({-3, -4, 0}, a, b, c), 5.0, 1e-12);           // beyond corner a
  EXPECT_NEAR(point_triangle_distance({2, 1, 0}, a, b, {2, 0, 0}), 1.0, 1e-12);     // a degenerate triangle
  EXPECT_NEAR(point_triangle_distance({1, 1, 1}, a, a, a), std::sqrt(3.0), 1e-12);  // a point
}

// Part 0 is the unit square in z = 0; part 1 a smaller square lying on it (as a kettle's lid on its body's
// top) and a square of its own at z = 1.
TEST(PartSurfaces, PointsWhereOnePartLiesOnAnotherCarryBoth) {
  Mesh mesh;
  mesh.vertices.resize(12, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,     // part 0
      0.2, 0.2, 0, 0.6, 0.2, 0, 0.6, 0.6, 0, 0.2, 0.6, 0,  // part 1 on part 0
      0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;                  // part 1 alone
  mesh.faces.resize(6, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 9, 10, 8, 10, 11;
  Eigen::VectorXi vertex_part(12);
  vertex_part << 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1;
  Points points(5, 3);
  points << 0.4, 0.4, 0.0005,  // on both, within the tolerance
      0.4, 0.4, 0.01,          // above both, beyond it
      0.9, 0.9, 0,             // on part 0 beside the small square
      0.5, 0.5, 1,             // on part 1 alone
      0.5, 0.5, 0.5;           // on neither
  const auto through = parts_through_points(mesh, vertex_part, 2, points, 0.001);
  ASSERT_EQ(through.rows(), 5);
  ASSERT_EQ(through.cols(), 2);
  EXPECT_TRUE(through(0, 0) && through(0, 1));
  EXPECT_FALSE(through(1, 0) || through(1, 1));
  EXPECT_TRUE(through(2, 0) && !through(2, 1));
  EXPECT_TRUE(!through(3, 0) && through(3, 1));
  EXPECT_FALSE(through(4, 0) || through(4, 1));
}

TEST(PartSurfaces, WithoutAPartPerVertexNoPartPassesThrough) {
  Mesh mesh;
  mesh.vertices = Points::Identity(3, 3);
  mesh.faces = Faces(1, 3);
  mesh.faces << 0, 1, 2;
  const auto through =
      parts_through_points(mesh, Eigen::VectorXi(), 2, Points::Constant(1, 3, 1.0 / 3), 0.01);
  EXPECT_FALSE(through.any());
}

}  // namespace
}  // namespace partreg::core::detail
