// Partial views: the viewpoint sphere and what a depth camera sees of a closed shape.
#include "partreg/eval/views.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "partreg/core/errors.hpp"
#include "support/test_shapes.hpp"

namespace partreg {
namespace {

TEST(SphereDirections, FortyTwoUnitDirectionsEvenlySpreadWithTheTwelveFirst) {
  const std::vector<Eigen::Vector3d> directions = eval::sphere_directions(42);
  ASSERT_EQ(directions.size(), 42u);
  const std::vector<Eigen::Vector3d> twelve = eval::sphere_directions(12);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_LT((twelve[i] - directions[i]).norm(), 1e-12);
  double closest_min = 10, closest_max = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& a : directions) {
    EXPECT_NEAR(a.norm(), 1.0, 1e-12);
    sum += a;
    double closest = 10;
    for (const Eigen::Vector3d& b : directions)
      if (&a != &b) closest = std::min(closest, std::acos(std::clamp(a.dot(b), -1.0, 1.0)));
    closest_min = std::min(closest_min, closest);
    closest_max = std::max(closest_max, closest);
  }
  // Evenly spread: every direction's nearest neighbour is 29 to 32 degrees away, and they balance out.
  EXPECT_GT(closest_min * 180 / M_PI, 29.0);
  EXPECT_LT(closest_max * 180 / M_PI, 32.5);
  EXPECT_LT(sum.norm(), 1e-9);
  EXPECT_EQ(eval::sphere_directions(162).size(), 162u);
  EXPECT_THROW(eval::sphere_directions(40), UsageError);
}

TEST(ViewCaster, AClosedSphereShowsOnlyTheSideFacingTheCamera) {
  const Eigen::Vector3d centre(0.3, -0.2, 0.5);
  const eval::ViewCaster caster(testing::uv_sphere(1.0, 40, 80, centre));
  for (const Eigen::Vector3d& direction : eval::sphere_directions(12)) {
    const eval::View view = caster.cast(direction);
    ASSERT_GT(view.points.rows(), 2000) << "a sphere filling the image gives thousands of hits";
    EXPECT_GT((view.viewpoint - centre).dot(direction), 0.0);
    for (Eigen::Index i = 0; i < view.points.rows(); ++i) {
      const Eigen::Vector3d p = view.points.row(i).transpose();
      const Eigen::Vector3d outward = (p - centre).normalized();
      EXPECT_NEAR((p - centre).norm(), 1.0, 0.01);                       // on the surface
      ASSERT_GT(outward.dot((view.viewpoint - p).normalized()), -1e-3);  // facing the camera
      ASSERT_GT(outward.dot(direction), 0.1);  // never the far side (the visible cap starts near 0.2)
      ASSERT_GT(view.normals.row(i).dot(outward), 0.9);  // normal of the surface hit
    }
    // The near half is seen: the points' mean lies towards the camera.
    EXPECT_GT((view.points.colwise().mean().transpose() - centre).dot(direction), 0.4);
  }
}

TEST(ViewCaster, ACloudViewIsTheSubsetOfPointsOnTheNearSide) {
  // Points on a unit sphere (Fibonacci lattice): a view keeps the cloud's own points, near side only.
  const int count = 2000;
  const core::Points cloud = testing::fibonacci_sphere(count, 1.0);
  const eval::ViewCaster caster(cloud);
  const Eigen::Vector3d direction = Eigen::Vector3d(1, 1, 0).normalized();
  const eval::View view = caster.cast(direction);
  EXPECT_GT(view.points.rows(), 0.3 * count);
  EXPECT_LT(view.points.rows(), 0.55 * count);
  for (Eigen::Index i = 0; i < view.points.rows(); ++i) {
    EXPECT_NEAR(view.points.row(i).norm(), 1.0, 1e-9);  // one of the cloud's points, not a sphere surface
    ASSERT_GT(view.points.row(i).dot(direction), 0.0) << "a point on the far side was seen";
  }
}

TEST(ViewCaster, EmptyInputIsRefused) {
  EXPECT_THROW(eval::ViewCaster(core::Mesh{}), InputError);
  EXPECT_THROW(eval::ViewCaster(core::Points(0, 3)), InputError);
}

// A field of view of 1e-300 degrees put the camera 1e300 sizes away, where Embree aborted the process.
TEST(ViewCaster, CamerasOutsideTheDeclaredRangesAreUsageErrors) {
  using Camera = eval::CameraSettings;
  const Camera fine{};
  EXPECT_NO_THROW(eval::check_camera(fine));
  for (const Camera bad :
       {Camera{160, 120, 1e-300, 1.1}, Camera{160, 120, NAN, 1.1}, Camera{160, 120, 180.0, 1.1},
        Camera{160, 120, 45.0, INFINITY}, Camera{160, 120, 45.0, 0.5}, Camera{0, 120, 45.0, 1.1},
        Camera{160, 100000, 45.0, 1.1}})
    EXPECT_THROW(eval::check_camera(bad), UsageError) << bad.fov_degrees << " " << bad.margin;
  const eval::ViewCaster caster(core::Points::Random(50, 3));
  EXPECT_THROW(caster.cast(Eigen::Vector3d::UnitZ(), Camera{160, 120, 1e-300, 1.1}), UsageError);
}

}  // namespace
}  // namespace partreg
