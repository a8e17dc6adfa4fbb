#include <gtest/gtest.h>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/gaussian_kernel.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/deformation.hpp"
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

TEST(ShapeSpace, PartSpacesMoveTheirPartAndTheSeamBandOnly) {
  AppState state;
  // A labelled mesh loaded first puts the app on the labelling tab; opening a model moves it to its spaces.
  execute(state, make_command("mode", {"labelling"}));
  execute(state, make_command("load", {testing::small_model_path().string()}));
  EXPECT_EQ(state.mode, Mode::shape_space);
  const core::Mesh mean_parts = [&] {
    execute(state, make_command("space", {"handle"}));
    return shape_space_mesh(state);
  }();
  execute(state, make_command("set_latent", {"handle", "1", "-2"}));
  const core::Mesh moved = shape_space_mesh(state);
  const core::CategoryModel& model = *state.shapes.model;
  // The handle's field reaches the body within about a seam band of the handle's canonical points (a body
  // vertex weighs the handle when its distance to it exceeds that to the body by less than the band).
  const core::KdTree handle_points(model.space("handle").canonical);
  const double band = core::SeamBlend{}.band;
  double handle_motion = 0.0, far_body_motion = 0.0, near_body_motion = 0.0;
  for (Eigen::Index v = 0; v < moved.vertices.rows(); ++v) {
    const double d = (moved.vertices.row(v) - mean_parts.vertices.row(v)).norm();
    const double to_handle =
        std::sqrt(handle_points.nearest(model.canonical_mesh.vertices.row(v).transpose()).second);
    if (model.mesh_vertex_part[v] == 1)
      handle_motion = std::max(handle_motion, d);
    else if (to_handle < 0.5 * band)
      near_body_motion = std::max(near_body_motion, d);
    else if (to_handle > 1.5 * band)
      far_body_motion = std::max(far_body_motion, d);
  }
  EXPECT_GT(handle_motion, 1e-3);
  EXPECT_GT(near_body_motion, 0.0);  // the seam is blended, not torn
  EXPECT_EQ(far_body_motion, 0.0);
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

// The UsageError message of a command that must fail (empty when it succeeds).
std::string refusal(AppState& state, const Command& command) {
  try {
    execute(state, command);
  } catch (const UsageError& error) {
    return error.what();
  }
  return "";
}

TEST(ShapeSpace, ATrainingInstanceIsDrawnExactlyAsFittedBesideTheSlidersShape) {
  AppState state;
  execute(state, make_command("load", {testing::small_model_path().string()}));
  const core::CategoryModel& model = *state.shapes.model;
  ASSERT_EQ(model.training.instances.size(), 5u);
  EXPECT_FALSE(instance_beside(state));
  const std::string name = model.training.instances[2];
  execute(state, make_command("show_instance", {name}));
  EXPECT_EQ(state.shapes.shown_instance, 2);
  const std::optional<InstanceBeside> shown = instance_beside(state);
  ASSERT_TRUE(shown);
  EXPECT_EQ(shown->name, name);
  // Its holistic fit V + G(V, C) W_2, moved by the offset only.
  const core::ShapeSpace& holistic = model.holistic();
  const core::Points& vertices = model.canonical_mesh.vertices;
  const core::Points fit =
      vertices + core::Points(core::apply_kernel(vertices, holistic.canonical, model.training_weight_field(2),
                                                 holistic.beta));
  ASSERT_EQ(shown->mesh.vertices.rows(), vertices.rows());
  EXPECT_LT(((shown->mesh.vertices.rowwise() - shown->offset.transpose()) - fit).cwiseAbs().maxCoeff(),
            1e-12);
  // Another instance's fit differs by far more than that tolerance.
  execute(state, make_command("show_instance", {"4"}));  // by index, from 1
  EXPECT_EQ(state.shapes.shown_instance, 3);
  EXPECT_GT(
      ((instance_beside(state)->mesh.vertices.rowwise() - instance_beside(state)->offset.transpose()) - fit)
          .cwiseAbs()
          .maxCoeff(),
      1e-3);
  // Beside, along the screen's horizontal: the two shapes' extents along it do not overlap.
  const CameraFrame frame = camera_frame(state.view, state.viewport);
  const Eigen::Vector3d right = frame.up.cross(frame.eye - frame.target).normalized();
  EXPECT_LT(shown->offset.cross(right).norm(), 1e-9 * shown->offset.norm());
  EXPECT_GT(shown->offset.dot(right), 0.0);
  const Eigen::VectorXd live = shape_space_mesh(state).vertices * right;
  const Eigen::VectorXd beside = instance_beside(state)->mesh.vertices * right;
  EXPECT_GT(beside.minCoeff(), live.maxCoeff());
  // Orbiting turns about both shapes (the offset stays); a named view places it beside again.
  const Eigen::Vector3d placed = instance_beside(state)->offset;
  execute(state, make_command("orbit", {"60", "0"}));
  EXPECT_EQ(instance_beside(state)->offset, placed);
  execute(state, make_command("camera", {"front"}));  // looks along -Z: its horizontal is +X
  EXPECT_GT(instance_beside(state)->offset.x(), 0.0);
  EXPECT_LT(instance_beside(state)->offset.cwiseAbs().tail<2>().maxCoeff(), 1e-9);
  execute(state, make_command("show_instance", {"none"}));
  EXPECT_EQ(state.shapes.shown_instance, -1);
  EXPECT_FALSE(instance_beside(state));
}

TEST(ShapeSpace, BadInstanceNamesAreRefusedWithTheNamesListed) {
  AppState state;
  EXPECT_NE(refusal(state, make_command("show_instance", {"mug_000"})).find("no model"), std::string::npos);
  execute(state, make_command("load", {testing::small_model_path().string()}));
  for (const std::string bad : {"teapot", "0", "6", "2.5"}) {
    for (const char* verb : {"show_instance", "instance_latent"}) {
      const std::string message = refusal(state, make_command(verb, {bad}));
      EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << message;
      for (const std::string& name : state.shapes.model->training.instances)
        EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
  EXPECT_EQ(state.shapes.shown_instance, -1);
  EXPECT_NE(refusal(state, make_command("instance_latent", {"1"}, {{"space", "lid"}})).find("handle"),
            std::string::npos);
}

TEST(ShapeSpace, TheSlidersGoToATrainingInstancesLatent) {
  AppState state;
  execute(state, make_command("load", {testing::small_model_path().string()}));
  const core::CategoryModel& model = *state.shapes.model;
  const std::string name = model.training.instances[1];
  execute(state, make_command("instance_latent", {name}));  // the current space: holistic
  EXPECT_LT((state.shapes.latent(0).transpose() - model.holistic().training_latents.row(1)).norm(), 1e-12);
  execute(state, make_command("animate", {"handle", "1"}));
  execute(state, make_command("instance_latent", {"4"}, {{"space", "handle"}}));
  const int handle = state.shapes.space;
  ASSERT_EQ(model.spaces[static_cast<std::size_t>(handle)].name, "handle");
  const Eigen::MatrixXd& latents = model.spaces[static_cast<std::size_t>(handle)].training_latents;
  EXPECT_LT((state.shapes.latent(handle).transpose() - latents.row(3)).norm(), 1e-12);
  EXPECT_EQ(state.shapes.animated_space, -1);  // the sweep would move the slider off the instance at once
  // The instances lie apart in the space, so taking another row would fail the checks above.
  EXPECT_GT((latents.row(3) - latents.row(1)).norm(), 1e-3);
  EXPECT_GT((model.holistic().training_latents.row(1) - model.holistic().training_latents.row(2)).norm(),
            1e-3);
  // Standard deviations: the sliders hold latent / sqrt(variance).
  const Eigen::VectorXd& values = state.shapes.std_devs[static_cast<std::size_t>(handle)];
  EXPECT_NEAR(values[0] * std::sqrt(model.spaces[static_cast<std::size_t>(handle)].variances[0]),
              latents(3, 0), 1e-12);
}

}  // namespace
}  // namespace partreg::ui
