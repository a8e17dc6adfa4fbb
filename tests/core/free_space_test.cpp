// Free space (core/geometry/free_space.hpp) on a synthetic depth image of a plane facing the camera: which
// points violate and by how much, lost pixels on a surface and open sky, the frame map, and the verdict's
// reading.
#include "partreg/core/geometry/free_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/verdict.hpp"
#include "support/test_shapes.hpp"

namespace partreg::core {
namespace {

constexpr double kPlaneDepth = 1.0;  // m

// A 64 x 48 camera looking at a plane at kPlaneDepth, everywhere measured.
FreeSpace plane() {
  FreeSpace free;
  free.fx = free.fy = 60.0;
  free.cx = 31.5, free.cy = 23.5;
  free.depth = Eigen::MatrixXf::Constant(48, 64, static_cast<float>(kPlaneDepth));
  return free;
}

// The camera-frame point on pixel (u, v) at depth z.
Eigen::Vector3d at_pixel(const FreeSpace& free, double u, double v, double z) {
  return {(u - free.cx) * z / free.fx, (v - free.cy) * z / free.fy, z};
}

// The allowance in front of the plane: 3 sigma(1 m) + the margin = 3 x 2.5 mm + 5 mm.
double allowance(const FreeSpace& free) {
  return free.noise_multiple * free.sigma(kPlaneDepth) + free.margin;
}

TEST(FreeSpace, APointInFrontOfThePlaneViolatesByItsDistanceBeyondTheAllowance) {
  const FreeSpace free = plane();
  ASSERT_NEAR(allowance(free), 0.0125, 1e-12);
  EXPECT_NEAR(free.violation(at_pixel(free, 10, 20, 0.9)), 0.1 - 0.0125, 1e-6);
  EXPECT_NEAR(free.violation(at_pixel(free, 40, 5, 0.5)), 0.5 - 0.0125, 1e-6);
  // On the surface, within the allowance in front of it, and behind it: no violation.
  EXPECT_EQ(free.violation(at_pixel(free, 10, 20, kPlaneDepth)), 0.0);
  EXPECT_EQ(free.violation(at_pixel(free, 10, 20, kPlaneDepth - 0.01)), 0.0);
  EXPECT_EQ(free.violation(at_pixel(free, 10, 20, kPlaneDepth + 0.3)), 0.0);
}

TEST(FreeSpace, PointsTheCameraCannotSeeNeverViolate) {
  const FreeSpace free = plane();
  EXPECT_EQ(free.violation(at_pixel(free, -3, 20, 0.5)), 0.0);      // left of the image
  EXPECT_EQ(free.violation(at_pixel(free, 10, 48.6, 0.5)), 0.0);    // below it
  EXPECT_EQ(free.violation(Eigen::Vector3d(0.0, 0.0, -0.5)), 0.0);  // behind the camera
  EXPECT_EQ(free.violation(Eigen::Vector3d(0.0, 0.0, 0.0)), 0.0);
}

TEST(FreeSpace, ALostPixelOnASurfaceStandsForItsNeighboursAndOpenSkyIsFreeAllAlong) {
  FreeSpace free = plane();
  free.depth(20, 10) = 0.0f;  // a lost pixel amid the plane
  free.depth(21, 10) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(free.depth_at(10, 20), static_cast<float>(kPlaneDepth));
  EXPECT_EQ(free.violation(at_pixel(free, 10, 20, kPlaneDepth)), 0.0);
  EXPECT_NEAR(free.violation(at_pixel(free, 10, 21, 0.9)), 0.1 - 0.0125, 1e-6);
  // A block of sky wider than the missing window: its centre's ray met nothing, so any point there violates.
  free.depth.block(4, 4, 40, 40).setZero();
  EXPECT_EQ(free.depth_at(24, 24), 0.0);
  EXPECT_TRUE(std::isinf(free.violation(at_pixel(free, 24, 24, 3.0))));
  // Within the missing window of its rim the hole stands for the plane.
  EXPECT_EQ(free.depth_at(10, 10), static_cast<float>(kPlaneDepth));
  EXPECT_EQ(free.violation(at_pixel(free, 10, 10, kPlaneDepth)), 0.0);
}

TEST(FreeSpace, APointAPixelOrTwoAcrossASilhouetteMeetsTheObjectsDepth) {
  FreeSpace free = plane();
  free.depth.leftCols(32).setConstant(0.5f);  // an object in front of the plane on the left half
  // On the plane's side, one and two pixels from the object: judged against the object's 0.5 m.
  EXPECT_EQ(free.violation(at_pixel(free, 32, 20, 0.5)), 0.0);
  EXPECT_EQ(free.violation(at_pixel(free, 33, 20, 0.5)), 0.0);
  // Three pixels and more across: the plane behind, 0.5 m farther, so the point floats in free space.
  EXPECT_GT(free.violation(at_pixel(free, 34, 20, 0.5)), 0.4);
  EXPECT_GT(free.violation(at_pixel(free, 50, 20, 0.5)), 0.4);
}

TEST(FreeSpace, PreparedReadsTheSameAsTheWindowsItBakesIn) {
  FreeSpace free = plane();
  free.depth.leftCols(20).setConstant(0.6f);
  free.depth.block(10, 30, 6, 6).setZero();   // a hole in the plane
  free.depth.block(0, 44, 48, 20).setZero();  // sky on the right
  const FreeSpace prepared = free.prepared();
  EXPECT_EQ(prepared.lateral_window, 0);
  EXPECT_EQ(prepared.missing_window, 0);
  for (int v = 0; v < free.height(); ++v)
    for (int u = 0; u < free.width(); ++u) {
      ASSERT_EQ(prepared.depth_at(u, v), free.depth_at(u, v)) << u << ", " << v;
      for (double z : {0.3, 0.59, 0.9, 1.2}) {
        const Eigen::Vector3d p = at_pixel(free, u, v, z);
        ASSERT_EQ(prepared.violation(p), free.violation(p)) << u << ", " << v << ", " << z;
      }
    }
}

TEST(FreeSpace, TheShareReadsPointsThroughTheMapIntoTheCameraFrame) {
  FreeSpace free = plane();
  // Four points: two in front of the plane, one on it, one behind, given in a frame turned a quarter about y
  // and shifted: observed = R^T (camera - t).
  const Eigen::Matrix3d R = testing::rotation(M_PI / 2, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d t(0.1, 0.0, 0.2);
  Points camera(4, 3);
  camera.row(0) = at_pixel(free, 30, 20, 0.6).transpose();
  camera.row(1) = at_pixel(free, 35, 25, 0.8).transpose();
  camera.row(2) = at_pixel(free, 32, 22, kPlaneDepth).transpose();
  camera.row(3) = at_pixel(free, 32, 22, 1.4).transpose();
  const Points observed = (camera.rowwise() - t.transpose()) * R;
  EXPECT_DOUBLE_EQ(free.violation_share(camera), 0.5);
  // Read as camera-frame points they lie elsewhere; through the map they are the camera's again.
  EXPECT_NE(free.violation_share(observed), 0.5);
  free.T_camera_observed = Eigen::Translation3d(t) * R;
  EXPECT_DOUBLE_EQ(free.violation_share(observed), 0.5);
  EXPECT_EQ(free.violation_share(Points(0, 3)), 0.0);
}

TEST(FreeSpace, BadImagesAndNoiseAreRefused) {
  FreeSpace free = plane();
  EXPECT_NO_THROW(free.validate());
  free.fx = 0.0;
  EXPECT_THROW(free.validate(), InputError);
  free = plane();
  free.depth(3, 3) = -1.0f;
  EXPECT_THROW(free.validate(), InputError);
  free = plane();
  free.noise_quadratic = -0.1;
  EXPECT_THROW(free.validate(), InputError);
  free = plane();
  free.depth.resize(0, 0);
  EXPECT_THROW(free.validate(), InputError);
}

TEST(FreeSpace, TheVerdictFlagsAShareBeyondItsThresholds) {
  const VerdictSettings settings;
  TrustFigures figures;
  figures.inlier_share = 1.0;
  figures.pose_ambiguity = std::numeric_limits<double>::infinity();
  EXPECT_EQ(judge(figures, settings).verdict, Verdict::good);  // unset: no depth image
  figures.free_space_violation = 0.5 * settings.doubtful_free_space_violation;
  EXPECT_EQ(judge(figures, settings).verdict, Verdict::good);
  figures.free_space_violation =
      0.5 * (settings.doubtful_free_space_violation + settings.failed_free_space_violation);
  const Assessment doubtful = judge(figures, settings);
  EXPECT_EQ(doubtful.verdict, Verdict::doubtful);
  ASSERT_EQ(doubtful.reasons.size(), 1u);
  EXPECT_NE(doubtful.reasons[0].find("free space"), std::string::npos) << doubtful.reasons[0];
  figures.free_space_violation = 1.0;
  EXPECT_EQ(judge(figures, settings).verdict, Verdict::failed);
  VerdictSettings reversed;
  reversed.failed_free_space_violation = 0.5 * reversed.doubtful_free_space_violation;
  EXPECT_THROW(judge(figures, reversed), UsageError);
}

}  // namespace
}  // namespace partreg::core
