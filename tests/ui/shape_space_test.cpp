#include <gtest/gtest.h>

#include "partreg/core/gaussian_kernel.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/script.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg::ui {
namespace {

TEST(ShapeSpace, SlidersDeformTheCanonicalMeshByEq4) {
  AppState state;
  for (const Command& c :
       parse_script("load " + testing::small_model_path().string() + "\nset_latent holistic 1 2.0"))
    execute(state, c);
  ASSERT_TRUE(state.shapes.loaded());
  const core::CategoryModel& model = *state.shapes.model;
  ASSERT_GT(model.canonical_mesh.vertices.rows(), 0);
  const core::Mesh shown = shape_space_mesh(state);
  // Eq. 4 directly: V + G(V, C) W(x) with x = 2 standard deviations along the first direction.
  const core::ShapeSpace& space = model.holistic();
  Eigen::VectorXd latent = Eigen::VectorXd::Zero(space.dimensions());
  latent[0] = 2.0 * std::sqrt(space.variances[0]);
  const core::Points weights = space.weights(latent);
  const core::Points expected =
      model.canonical_mesh.vertices +
      core::Points(core::apply_kernel(model.canonical_mesh.vertices, space.canonical, weights, space.beta));
  EXPECT_LT((shown.vertices - expected).cwiseAbs().maxCoeff(), 1e-9);
  // The mean shape differs from it by far more than that tolerance.
  execute(state, make_command("reset_latents"));
  EXPECT_GT((shape_space_mesh(state).vertices - expected).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(ShapeSpace, PartSpacesMoveOnlyTheirPart) {
  AppState state;
  execute(state, make_command("load", {testing::small_model_path().string()}));
  const core::Mesh mean_parts = [&] {
    execute(state, make_command("space", {"handle"}));
    return shape_space_mesh(state);
  }();
  execute(state, make_command("set_latent", {"handle", "1", "-2"}));
  const core::Mesh moved = shape_space_mesh(state);
  const core::CategoryModel& model = *state.shapes.model;
  double handle_motion = 0.0, body_motion = 0.0;
  for (Eigen::Index v = 0; v < moved.vertices.rows(); ++v) {
    const double d = (moved.vertices.row(v) - mean_parts.vertices.row(v)).norm();
    (model.mesh_vertex_part[v] == 1 ? handle_motion : body_motion) =
        std::max(model.mesh_vertex_part[v] == 1 ? handle_motion : body_motion, d);
  }
  EXPECT_GT(handle_motion, 1e-3);
  EXPECT_EQ(body_motion, 0.0);
  EXPECT_FALSE(execute_reporting(state, make_command("set_latent", {"handle", "9", "1"})));
  EXPECT_FALSE(execute_reporting(state, make_command("set_latent", {"lid", "1", "1"})));
}

TEST(ShapeSpace, AnAnimatedSliderSweepsTwoStandardDeviationsEveryFourSeconds) {
  AppState state;
  execute(state, make_command("load", {testing::small_model_path().string()}));
  execute(state, make_command("animate", {"handle", "2"}));
  const int handle = state.shapes.space;
  EXPECT_EQ(state.shapes.model->spaces[static_cast<std::size_t>(handle)].name, "handle");
  advance_animation(state, 1.0);  // a quarter cycle: the top of the sweep
  EXPECT_NEAR(state.shapes.std_devs[static_cast<std::size_t>(handle)][1], 2.0, 1e-12);
  advance_animation(state, 2.0);  // three quarters: the bottom
  EXPECT_NEAR(state.shapes.std_devs[static_cast<std::size_t>(handle)][1], -2.0, 1e-12);
  EXPECT_EQ(state.shapes.std_devs[static_cast<std::size_t>(handle)][0], 0.0);  // the others stay
  execute(state, make_command("animate", {"off"}));
  advance_animation(state, 1.0);
  EXPECT_NEAR(state.shapes.std_devs[static_cast<std::size_t>(handle)][1], -2.0, 1e-12);
  EXPECT_FALSE(execute_reporting(state, make_command("animate", {"handle", "9"})));
}

}  // namespace
}  // namespace partreg::ui
