#include "partreg/ui/view.hpp"

#include <gtest/gtest.h>

#include "partreg/ui/executor.hpp"
#include "partreg/ui/labelling.hpp"
#include "partreg/ui/script.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg::ui {
namespace {

TEST(View, PixelRayAndProjectAreInverse) {
  Viewport viewport;
  OrbitView view;
  view.target = Eigen::Vector3d(0.1, 0.2, -0.3);
  view.azimuth_deg = 30.0;
  view.elevation_deg = 20.0;
  const Eigen::Vector3d point(0.3, -0.1, 0.2);
  const Eigen::Vector2d pixel = project(view, viewport, point);
  const Ray ray = pixel_ray(view, viewport, pixel.x(), pixel.y());
  const Eigen::Vector3d offset = point - ray.origin;
  const double miss = (offset - offset.dot(ray.direction) * ray.direction).norm();
  EXPECT_LT(miss, 1e-9);
  // The orbit target appears in the middle of the part the panels leave free, not in the frame's middle.
  const Eigen::Vector2d target = project(view, viewport, view.target);
  EXPECT_NEAR(target.x() + 0.5, 0.5 * (viewport.width + viewport.panel_width), 1e-6);
  EXPECT_NEAR(target.y() + 0.5, 0.5 * viewport.height, 1e-6);
}

TEST(View, PaintStaysOnThePickedSurfaceWithinTheBrush) {
  AppState state;
  for (const Command& c :
       parse_script("load " + testing::mug_mesh_path().string() + "\ncreate_part handle\ncamera side"))
    execute(state, c);
  const Eigen::Vector2d centre = project(state.view, state.viewport, state.view.target);
  const std::optional<Hit> hit =
      intersect(state.labelling.mesh, pixel_ray(state.view, state.viewport, centre.x(), centre.y()));
  ASSERT_TRUE(hit);
  execute(state, make_command("paint", {std::to_string(centre.x()), std::to_string(centre.y())},
                              {{"radius", "20"}}));
  const double radius = 20.0 * pixel_size_at(state.view, state.viewport, hit->distance);
  const core::Mesh& mesh = state.labelling.mesh;
  int painted = 0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (state.labelling.labels.labels[f] != 0) continue;
    ++painted;
    const Eigen::Vector3d c = (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
                               mesh.vertices.row(mesh.faces(f, 2)))
                                  .transpose() /
                              3.0;
    EXPECT_LE((c - hit->point).norm(), radius + 1e-12);
  }
  EXPECT_GT(painted, 3);
  // Painting into empty space is refused and changes nothing.
  const Eigen::VectorXi before = state.labelling.labels.labels;
  EXPECT_FALSE(execute_reporting(state, make_command("paint", {"1270", "5"})));
  EXPECT_EQ(state.labelling.labels.labels, before);
}

}  // namespace
}  // namespace partreg::ui
