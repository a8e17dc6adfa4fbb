#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "partreg/ui/executor.hpp"
#include "partreg/ui/script.hpp"
#include "ui/ui_fixtures.hpp"

namespace partreg::ui {
namespace {

TEST(RegistrationStepper, StepsThroughTheHistoryToTheResult) {
  AppState state;
  for (const Command& c : parse_script("load " + testing::small_model_path().string() + "\nload " +
                                       testing::observed_cloud_path().string() + "\nregister hol+part"))
    execute(state, c);
  ASSERT_TRUE(state.registration.result);
  const core::RegistrationResult& result = *state.registration.result;
  const int steps = static_cast<int>(result.history.size());
  ASSERT_GT(steps, 2);
  EXPECT_EQ(state.registration.step, steps - 1);
  // At the last step the replayed points are the result's deformed canonical (data units, 1e-6 of a mug).
  const core::Points last = registration_points(state);
  EXPECT_LT((last - result.deformed).cwiseAbs().maxCoeff(), 1e-6 * state.shapes.model->normalization.scale);
  execute(state, make_command("goto_step", {"first"}));
  EXPECT_EQ(state.registration.step, 0);
  const core::Points first = registration_points(state);
  EXPECT_GT((first - result.deformed).cwiseAbs().maxCoeff(), 1e-3 * state.shapes.model->normalization.scale);
  execute(state, make_command("step", {"-5"}));
  EXPECT_EQ(state.registration.step, -1);  // clamped before the first step
  execute(state, make_command("step", {"1000"}));
  EXPECT_EQ(state.registration.step, steps - 1);
}

TEST(RegistrationStepper, APartialViewBringsItsViewpointFromViewsJson) {
  // `partreg views` writes views.json beside the clouds; loading one of them picks up its camera position.
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "partreg_ui_viewpoint";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(testing::observed_cloud_path(), folder / "view_003.ply",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(folder / "views.json") << R"({"views": [{"file": "view_002.ply", "viewpoint": [9, 9, 9]},
                       {"file": "view_003.ply", "viewpoint": [0.5, -1, 2]}]})";
  AppState state;
  execute(state, make_command("load", {(folder / "view_003.ply").string()}));
  ASSERT_TRUE(state.registration.viewpoint);
  EXPECT_EQ(*state.registration.viewpoint, Eigen::Vector3d(0.5, -1, 2));
  // Another cloud without a listing has none; the register option sets one.
  execute(state, make_command("load", {testing::observed_cloud_path().string()}));
  EXPECT_FALSE(state.registration.viewpoint);
  execute(state, make_command("load", {testing::small_model_path().string()}));
  execute(state, make_command("register", {"holistic"}, {{"viewpoint", "1,2,3"}}));
  EXPECT_EQ(*state.registration.viewpoint, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(execute_reporting(state, make_command("register", {"holistic"}, {{"viewpoint", "1,2"}})));
  std::filesystem::remove_all(folder);
}

TEST(RegistrationStepper, FramesOnTheCanonicalAreLoadedForTheLastStep) {
  AppState state;
  const std::string frames = std::string(PARTREG_SOURCE_DIR) + "/assets/frames/mug_handle_grasp.json";
  execute(state, make_command("load_frames", {frames}));
  ASSERT_EQ(state.registration.frames.size(), 1u);
  EXPECT_FALSE(execute_reporting(state, make_command("load_frames", {"/nonexistent/frames.json"})));
  EXPECT_EQ(state.registration.frames.size(), 1u);  // a failed load changes nothing
}

TEST(RegistrationStepper, RegisterNeedsAModelAndAnObservation) {
  AppState state;
  EXPECT_FALSE(execute_reporting(state, make_command("register", {"holistic"})));
  EXPECT_FALSE(execute_reporting(state, make_command("step", {"1"})));
  EXPECT_TRUE(state.status_is_error);
}

}  // namespace
}  // namespace partreg::ui
