// The scene cut on rendered table tops whose truth is known: the plane's normal, the object nearest the image
// centre, the object at a picked pixel or point, and the refusals (no plane, no cluster, a pick off the image).
#include <gtest/gtest.h>

#include <random>

#include "partreg/core/errors.hpp"
#include "partreg/scene/depth_render.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/segmentation.hpp"
#include "partreg/scene/table_scene.hpp"
#include "support/test_shapes.hpp"

namespace partreg::scene {
namespace {

struct Rendered {
  TableScene table;
  SceneView view;
  Intrinsics k;
};

// Three balls (diagonal 0.12 m) on a table, 0.2 m apart, seen by the default camera.
Rendered three_balls(bool with_table = true) {
  Rendered out;
  std::vector<TableObject> objects(3, TableObject{testing::uv_sphere(1.0, 16, 24), Eigen::Vector3d::UnitY(), 0.12});
  out.table = lay_out_table(objects);
  std::vector<core::Mesh> meshes;
  for (const PlacedObject& object : out.table.objects) meshes.push_back(object.mesh);
  if (with_table) meshes.push_back(out.table.table);
  out.view = depth_view(render_depth(meshes, out.k).depth, out.k);
  return out;
}

Eigen::Vector3d centre_of(const PlacedObject& object) { return object.mesh.vertices.colwise().mean().transpose(); }

double angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

TEST(SceneCut, FindsTheTableAndTheObjectNearestTheImageCentre) {
  const Rendered scene = three_balls();
  const SceneCut cut = cut_scene(scene.view);
  EXPECT_LT(angle_degrees(cut.up, scene.table.plane.head<3>()), 1.0);
  EXPECT_NEAR(cut.plane[3], scene.table.plane[3], 0.005);
  ASSERT_EQ(cut.clusters.size(), 3u);
  const Eigen::Vector3d chosen = cut.object.points.colwise().mean().transpose();
  // The visible side's mean lies within a radius (0.035 m) of the ball's centre; the neighbours are 0.2 m off.
  EXPECT_LT((chosen - centre_of(scene.table.objects[0])).norm(), 0.035);
  EXPECT_GT(cut.object.points.rows(), 500);
  for (Eigen::Index i = 0; i < cut.object.points.rows(); ++i)
    ASSERT_GT(cut.plane.head<3>().dot(cut.object.points.row(i).transpose()) + cut.plane[3], 0.0);
}

TEST(SceneCut, PickByPixelAndByPointChooseThatObject) {
  const Rendered scene = three_balls();
  for (int target : {1, 2}) {
    const Eigen::Vector3d centre = centre_of(scene.table.objects[target]);
    Pick by_pixel;
    by_pixel.pixel = scene.k.project(centre);
    Pick by_point;
    by_point.point = centre;
    for (const Pick& pick : {by_pixel, by_point}) {
      const SceneCut cut = cut_scene(scene.view, pick);
      const Eigen::Vector3d chosen = cut.object.points.colwise().mean().transpose();
      EXPECT_LT((chosen - centre).norm(), 0.035) << "object " << target << ": " << cut.choice;
    }
  }
}

TEST(SceneCut, RefusesPicksOffTheImageOrWithoutACamera) {
  Rendered scene = three_balls();
  Pick outside;
  outside.pixel = Eigen::Vector2d(640, 10);
  EXPECT_THROW(cut_scene(scene.view, outside), UsageError);
  outside.pixel = Eigen::Vector2d(-1, 10);
  EXPECT_THROW(cut_scene(scene.view, outside), UsageError);
  Pick far_away;
  far_away.point = Eigen::Vector3d(5, 5, 5);
  EXPECT_THROW(cut_scene(scene.view, far_away), InputError);
  scene.view.intrinsics.reset();  // a cloud without intrinsics has no pixels to pick
  Pick pixel;
  pixel.pixel = Eigen::Vector2d(320, 240);
  EXPECT_THROW(cut_scene(scene.view, pixel), UsageError);
}

TEST(SceneCut, RefusesASceneWithNoPlaneOrNoCluster) {
  // Points spread through a 0.5 m cube: no plane holds a tenth of them.
  SceneView cube;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(-0.25, 0.25);
  cube.measured.points.resize(20000, 3);
  for (Eigen::Index i = 0; i < cube.measured.points.rows(); ++i)
    cube.measured.points.row(i) << uniform(random), uniform(random), 1.0 + uniform(random);
  cube.measured.pixel.assign(20000, -1);
  try {
    cut_scene(cube);
    FAIL() << "a cube of points gave a plane";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no support plane"), std::string::npos) << e.what();
  }
  // A bare table: a plane and nothing on it.
  Rendered scene;
  const TableScene table = lay_out_table({});
  scene.view = depth_view(render_depth({table.table}, scene.k).depth, scene.k);
  try {
    cut_scene(scene.view);
    FAIL() << "a bare table gave a cluster";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no cluster"), std::string::npos) << e.what();
  }
}

TEST(SceneCut, AMaskChoosesTheObjectAndThePlaneStillGivesTheUpAxis) {
  const Rendered scene = three_balls();
  // The truth's mask of object 2.
  std::vector<core::Mesh> meshes;
  for (const PlacedObject& object : scene.table.objects) meshes.push_back(object.mesh);
  meshes.push_back(scene.table.table);
  const RenderedDepth rendered = render_depth(meshes, scene.k);
  const PixelMask mask = surface_mask(rendered, 2);
  const SceneCut cut = cut_scene(depth_view(rendered.depth, scene.k, &mask));
  EXPECT_EQ(cut.chosen, -1);
  EXPECT_LT((cut.object.points.colwise().mean().transpose() - centre_of(scene.table.objects[2])).norm(), 0.035);
  EXPECT_LT(angle_degrees(cut.up, scene.table.plane.head<3>()), 1.0);
}

}  // namespace
}  // namespace partreg::scene

namespace partreg::scene {
namespace {

// A table seen by the default camera: the depth along each ray where it meets the table's plane.
TEST(DepthRender, TrueDepthIsTheRayPlaneIntersectionAndNoiseGrowsWithDepthSquared) {
  const TableScene table = lay_out_table({});
  const Intrinsics k;
  SensorSettings sensor;
  sensor.noise = 0.01, sensor.disparity_step = 0.0;  // noise alone, large enough to measure
  const RenderedDepth rendered = render_depth({table.table}, k, sensor);
  double worst = 0.0;
  double sum_near = 0, sum_far = 0;
  int near = 0, far = 0;
  for (int v = 0; v < k.height; v += 7)
    for (int u = 0; u < k.width; u += 7) {
      const float z = rendered.clean.at(u, v);
      if (z == 0.0f) continue;
      const Eigen::Vector3d ray((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
      const double expected = -table.plane[3] / table.plane.head<3>().dot(ray);
      worst = std::max(worst, std::abs(z - expected));
      if (rendered.depth.at(u, v) == 0.0f) continue;
      const double residual = (rendered.depth.at(u, v) - z) / (z * z);  // in units of noise at 1 m
      (z < 0.55 ? sum_near : sum_far) += residual * residual;
      ++(z < 0.55 ? near : far);
    }
  EXPECT_LT(worst, 1e-5);
  ASSERT_GT(near, 100);
  ASSERT_GT(far, 100);
  // Divided by z^2 the residuals have the same spread, 0.01, near and far.
  EXPECT_NEAR(std::sqrt(sum_near / near), 0.01, 0.0015);
  EXPECT_NEAR(std::sqrt(sum_far / far), 0.01, 0.0015);
}

TEST(DepthRender, LosesGrazingSurfacesShadowsAndEdges) {
  const Intrinsics k;
  TableLayout low;
  low.elevation_degrees = 10.0;  // the table seen 80 degrees from its normal
  auto measured_share = [&](const TableLayout& layout, const SensorSettings& sensor) {
    const RenderedDepth r = render_depth({lay_out_table({}, layout).table}, k, sensor);
    int hit = 0, kept = 0;
    for (std::size_t i = 0; i < r.clean.metres.size(); ++i) hit += r.clean.metres[i] > 0, kept += r.depth.metres[i] > 0;
    return double(kept) / hit;
  };
  EXPECT_GT(measured_share({}, {}), 0.95);
  // Seen from 10 degrees above the table, a pixel is lost exactly where its ray meets the table more than 75
  // degrees from the normal (the image's upper part), and kept below.
  const TableScene flat = lay_out_table({}, low);
  const RenderedDepth seen = render_depth({flat.table}, k);
  int wrong = 0, grazing = 0, hit = 0;
  for (int v = 0; v < k.height; ++v)
    for (int u = 1; u + 1 < k.width; ++u) {
      const std::size_t i = std::size_t(v) * k.width + u;
      if (seen.clean.metres[i] == 0 || seen.clean.metres[i - 1] == 0 || seen.clean.metres[i + 1] == 0) continue;
      const Eigen::Vector3d ray = Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0).normalized();
      const bool beyond = std::abs(ray.dot(flat.plane.head<3>())) < std::cos(75.0 * M_PI / 180.0);
      ++hit, grazing += beyond, wrong += beyond != (seen.depth.metres[i] == 0);
    }
  EXPECT_GT(grazing, hit / 10);
  EXPECT_LT(wrong, hit / 100);
  SensorSettings lenient;
  lenient.grazing_degrees = 89.0;
  EXPECT_GT(measured_share(low, lenient), 0.9);
  // A ball on the table: its edge pixels and the shadow the projector (at +x) leaves beside it are lost.
  const TableScene scene = lay_out_table({TableObject{testing::uv_sphere(1.0, 16, 24), Eigen::Vector3d::UnitY(), 0.12}});
  const RenderedDepth r = render_depth({scene.objects[0].mesh, scene.table}, k);
  const PixelMask ball = surface_mask(r, 0);
  int lost_table_right = 0, lost_table_left = 0, ball_lost = 0, ball_pixels = 0;
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const std::size_t i = std::size_t(v) * k.width + u;
      if (ball.selected[i]) ball_pixels++, ball_lost += r.depth.metres[i] == 0;
      if (r.surface[i] == 1 && r.depth.metres[i] == 0) (u > k.cx ? lost_table_right : lost_table_left)++;
    }
  EXPECT_GT(ball_lost, 0);
  EXPECT_LT(ball_lost, ball_pixels / 3);
  EXPECT_GT(lost_table_left, 2 * lost_table_right);  // lit from +x, the ball shadows the table on its -x side
}

}  // namespace
}  // namespace partreg::scene
