// The gripper test on shapes whose answer is known, grasp sampling, and re-seating.
#include "partreg/eval/gripper.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/test_shapes.hpp"
#include "partreg/core/errors.hpp"

namespace partreg::eval {
namespace {

// An axis-aligned box centred at the origin (12 triangles).
core::Mesh box(const Eigen::Vector3d& half) {
  core::Mesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    mesh.vertices.row(i) << ((i & 1) ? half.x() : -half.x()), ((i & 2) ? half.y() : -half.y()),
        ((i & 4) ? half.z() : -half.z());
  mesh.faces.resize(12, 3);
  mesh.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1,
      3, 5, 3, 7, 5;
  return mesh;
}

// A closed cylinder along z: radius r, half height h, `segments` around.
core::Mesh cylinder(double r, double h, int segments) {
  core::Mesh mesh;
  mesh.vertices.resize(2 * segments + 2, 3);
  for (int s = 0; s < segments; ++s) {
    const double a = 2.0 * M_PI * s / segments;
    mesh.vertices.row(s) << r * std::cos(a), r * std::sin(a), -h;
    mesh.vertices.row(segments + s) << r * std::cos(a), r * std::sin(a), h;
  }
  mesh.vertices.row(2 * segments) << 0, 0, -h;
  mesh.vertices.row(2 * segments + 1) << 0, 0, h;
  mesh.faces.resize(4 * segments, 3);
  for (int s = 0; s < segments; ++s) {
    const int n = (s + 1) % segments;
    mesh.faces.row(4 * s) << s, n, segments + s;
    mesh.faces.row(4 * s + 1) << n, segments + n, segments + s;
    mesh.faces.row(4 * s + 2) << 2 * segments, n, s;
    mesh.faces.row(4 * s + 3) << 2 * segments + 1, segments + s, segments + n;
  }
  return mesh;
}

core::Gripper gripper() {
  core::Gripper g;
  g.max_aperture = 0.1, g.pad_size = 0.01, g.finger_depth = 0.03, g.friction = 0.5;
  return g;
}

core::Grasp grasp_at(const Eigen::Vector3d& position, const Eigen::Vector3d& closing, const Eigen::Vector3d& approach) {
  core::Grasp grasp;
  grasp.position = position;
  grasp.rotation = core::grasp_axes(closing, approach);
  return grasp;
}

TEST(GripperTest, PinchingABoxAcrossItsFacesHolds) {
  const MeshRays object(box({0.02, 0.04, 0.04}));
  const GraspCheck check = check_grasp(object, grasp_at({0, 0, 0.03}, {1, 0, 0}, {0, 0, -1}), gripper());
  EXPECT_TRUE(check.holds) << check.reason;
  EXPECT_NEAR(check.width, 0.04, 1e-5);
  EXPECT_NEAR(check.angles_degrees[0], 0.0, 1e-3);
  EXPECT_NEAR(check.contacts[0].x(), -0.02, 1e-5);
  EXPECT_NEAR(check.contacts[1].x(), 0.02, 1e-5);
  EXPECT_NEAR(grasp_quality(check, gripper()), 1.0, 1e-6);
}

TEST(GripperTest, PinchingABoxAcrossAnEdgeSlips) {
  // The closing axis runs diagonally in x-y: each finger meets a face at 45 degrees, outside a 26.6-degree cone.
  const MeshRays object(box({0.02, 0.02, 0.04}));
  const GraspCheck check =
      check_grasp(object, grasp_at({0, 0, 0.03}, Eigen::Vector3d(1, 1, 0), {0, 0, -1}), gripper());
  EXPECT_FALSE(check.holds);
  EXPECT_NEAR(check.angles_degrees[0], 45.0, 1e-3);
  EXPECT_NE(check.reason.find("slips"), std::string::npos) << check.reason;
  EXPECT_EQ(grasp_quality(check, gripper()), 0.0);
}

TEST(GripperTest, TooWideABoxIsNotHeld) {
  const MeshRays object(box({0.06, 0.02, 0.04}));  // 0.12 across, the aperture is 0.1: fingers start inside
  EXPECT_FALSE(check_grasp(object, grasp_at({0, 0, 0.03}, {1, 0, 0}, {0, 0, -1}), gripper()).holds);
}

TEST(GripperTest, AFingerThatMeetsTheObjectOnItsWayInCollides) {
  // A block under a wide shelf: approached from above, the fingers' bodies pass through the shelf; from
  // below they are free.
  core::Mesh block = box({0.02, 0.02, 0.02});
  core::Mesh shelf = box({0.08, 0.02, 0.004});
  shelf.vertices.col(2).array() += 0.026;
  core::Mesh both;
  both.vertices.resize(16, 3);
  both.vertices << block.vertices, shelf.vertices;
  both.faces.resize(24, 3);
  both.faces << block.faces, (shelf.faces.array() + 8).matrix();
  const MeshRays object(both);
  const GraspCheck from_above = check_grasp(object, grasp_at({0, 0, 0}, {1, 0, 0}, {0, 0, -1}), gripper());
  EXPECT_FALSE(from_above.holds);
  EXPECT_TRUE(from_above.collides);
  const GraspCheck from_below = check_grasp(object, grasp_at({0, 0, 0}, {1, 0, 0}, {0, 0, 1}), gripper());
  EXPECT_TRUE(from_below.holds) << from_below.reason;
}

TEST(GripperTest, ACylinderPinchedThroughItsCapsHoldsOnlyInsideTheCone) {
  const MeshRays object(cylinder(0.02, 0.03, 48));
  const core::Gripper g = gripper();  // cone atan(0.5) = 26.57 degrees
  for (const double tilt_degrees : {0.0, 10.0, 20.0, 35.0, 50.0}) {
    const double t = tilt_degrees * M_PI / 180.0;
    // Through the middle of the caps, tilted about y: the caps' normals are tilt_degrees off the axis.
    const GraspCheck check =
        check_grasp(object, grasp_at({0, 0, 0}, {std::sin(t), 0, std::cos(t)}, {0, 1, 0}), g);
    EXPECT_EQ(check.holds, tilt_degrees < 26.0) << tilt_degrees << " degrees: " << check.reason;
    // Below atan(r / h) = 33.7 degrees the axis leaves through the caps; beyond, through the side wall.
    if (tilt_degrees < 33.0) EXPECT_NEAR(check.angles_degrees[0], tilt_degrees, 0.5);
  }
}

TEST(GripperTest, SampledGraspsOnABoxHoldAndAreRanked) {
  const core::Mesh mesh = box({0.02, 0.03, 0.04});
  const std::vector<core::Grasp> grasps = sample_grasps(mesh, gripper(), 20, 7);
  ASSERT_GE(grasps.size(), 10u);
  const MeshRays object(mesh);
  for (std::size_t g = 0; g < grasps.size(); ++g) {
    EXPECT_TRUE(check_grasp(object, grasps[g], gripper()).holds) << grasps[g].name;
    if (g > 0) EXPECT_LE(grasps[g].quality, grasps[g - 1].quality);
    // Antipodal on a box: the closing axis is a face normal, the width the box's side along it.
    const Eigen::Vector3d axis = grasps[g].closing_axis().cwiseAbs();
    EXPECT_GT(axis.maxCoeff(), 0.99);
  }
  EXPECT_THROW(sample_grasps(mesh, gripper(), 0, 1), UsageError);
}

TEST(GripperTest, ReseatingMovesAnOffsetTurnedGraspOntoTheSurface) {
  const core::Mesh mesh = box({0.02, 0.04, 0.04});
  const MeshRays object(mesh);
  // Carried 6 mm off centre and 20 degrees off the face normal: held only after re-seating.
  const double t = 20.0 * M_PI / 180.0;
  core::Grasp carried = grasp_at({0.006, 0, 0.03}, {std::cos(t), std::sin(t), 0}, {0, 0, -1});
  carried.width = 0.05;
  const std::vector<core::Grasp> seated = reseat_grasps(object, nullptr, {carried}, gripper());
  ASSERT_EQ(seated.size(), 1u);
  EXPECT_NEAR(seated[0].closing_axis().x(), 1.0, 1e-6);
  EXPECT_NEAR(seated[0].position.x(), 0.0, 1e-5);
  EXPECT_NEAR(seated[0].width, 0.04, 1e-5);
  EXPECT_NEAR(seated[0].quality, 1.0, 1e-6);
  // Observed points say the real face is 3 mm further out on +x: the contact follows the sensor.
  core::Points observed(9, 3);
  for (int i = 0; i < 9; ++i) observed.row(i) << 0.023, 0.001 * (i % 3 - 1), 0.03 + 0.001 * (i / 3 - 1);
  const std::vector<core::Grasp> seen = reseat_grasps(object, &observed, {carried}, gripper());
  EXPECT_NEAR(seen[0].width, 0.043, 1e-4);
}

}  // namespace
}  // namespace partreg::eval
