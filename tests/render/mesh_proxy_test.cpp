// The coarse proxy that interactive frames draw for dense meshes: small enough, close to the surface, and
// following the mesh's deformation; and the renderer's interactive frame of a dense mesh through it.
#include "partreg/render/mesh_proxy.hpp"

#include <gtest/gtest.h>

#include "image_baseline.hpp"
#include "partreg/render/headless.hpp"
#include "support/test_shapes.hpp"

namespace partreg::render {
namespace {

TEST(MeshProxy, KeepsTheTriangleBudgetAndStaysOnTheSurface) {
  const core::Mesh sphere = testing::uv_sphere(1.0, 100, 200);  // 40,000 triangles
  const MeshProxy proxy(sphere, 4000);
  EXPECT_LE(proxy.faces().rows(), 4000);
  EXPECT_GE(proxy.faces().rows(), 2000);  // the finest grid within the budget, not any coarse one
  const core::Points vertices = proxy.vertices(sphere.vertices);
  ASSERT_EQ(vertices.rows(), proxy.cluster_count());
  // Cluster means lie within a cell (about 2/30 of the diameter here) of the unit sphere.
  const Eigen::ArrayXd radii = vertices.rowwise().norm().array();
  EXPECT_GT(radii.minCoeff(), 0.9);
  EXPECT_LE(radii.maxCoeff(), 1.0 + 1e-12);
  EXPECT_GE(proxy.faces().minCoeff(), 0);
  EXPECT_LT(proxy.faces().maxCoeff(), proxy.cluster_count());
}

TEST(MeshProxy, FollowsTheMeshAsItDeforms) {
  const core::Mesh sphere = testing::uv_sphere(1.0, 60, 120);
  const MeshProxy proxy(sphere, 2000);
  core::Points moved = sphere.vertices;
  moved.col(0) *= 2.0;
  moved.col(2).array() += 0.5;
  core::Points expected = proxy.vertices(sphere.vertices);
  expected.col(0) *= 2.0;
  expected.col(2).array() += 0.5;
  EXPECT_TRUE(proxy.vertices(moved).isApprox(expected, 1e-12));
}

TEST(MeshProxy, SmallMeshIsKeptWhole) {
  const core::Mesh sphere = testing::uv_sphere(1.0, 8, 16);
  const MeshProxy proxy(sphere, 100000);
  EXPECT_EQ(proxy.cluster_count(), sphere.vertices.rows() - 2 * 15);  // the poles' rings of copies merge
}

TEST(Renderer, InteractiveFrameOfADenseMeshLooksLikeTheFullOne) {
  RenderSettings settings;
  settings.width = 320;
  settings.height = 240;
  settings.interactive_triangles = 3000;
  MeshItem item;
  item.mesh = testing::uv_sphere(1.0, 80, 160);  // 25,600 triangles: drawn as a proxy of at most 3000
  item.vertex_colors = part_colors((item.mesh.vertices.col(1).array() > 0.0).cast<int>().matrix().eval());
  Scene scene;
  scene.meshes.push_back(item);
  OsMesaContext context;
  Renderer renderer(settings);
  const Camera camera = fit_camera(scene.bounds(), View::front, 320.0 / 240.0);
  testing::expect_interactive_likeness(renderer, scene, camera, 0.05);
}

}  // namespace
}  // namespace partreg::render
