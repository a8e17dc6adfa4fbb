#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "partreg/io/cloud_io.hpp"
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
  execute(state, make_command("register", {"holistic"}, {{"viewpoint", "none"}}));  // the panel's checkbox
  EXPECT_FALSE(state.registration.viewpoint);
  EXPECT_FALSE(state.registration.settings.viewpoint);
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

TEST(RegistrationStepper, SavesTheResultFilesAsPartregRegisterDoes) {
  AppState state;
  const std::string frames = std::string(PARTREG_SOURCE_DIR) + "/assets/frames/mug_handle_grasp.json";
  EXPECT_FALSE(execute_reporting(state, make_command("save_result", {"anywhere"})));  // nothing registered
  for (const Command& c : parse_script("load " + testing::small_model_path().string() + "\nload " +
                                       testing::observed_cloud_path().string() + "\nload_frames " + frames +
                                       "\nregister partwise direction=canonical loss=cauchy"))
    execute(state, c);
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "partreg_ui_saved_result";
  std::filesystem::remove_all(folder);
  execute(state, make_command("save_result", {folder.string()}));
  for (const char* name : {"result.json", "points.ply", "mesh.ply", "frames.json"})
    EXPECT_TRUE(std::filesystem::exists(folder / name)) << name;
  const nlohmann::json result = nlohmann::json::parse(std::ifstream(folder / "result.json"));
  EXPECT_EQ(result["variant"], "partwise");
  EXPECT_EQ(result["settings"]["direction"], "canonical");
  EXPECT_EQ(result["settings"]["loss"], "cauchy");
  EXPECT_EQ(result["spaces"].size(), state.registration.result->fits.size());
  const io::CloudFile points = io::read_cloud_file(folder / "points.ply");
  EXPECT_EQ(points.cloud.points.rows(), state.shapes.model->canonical.rows());
  EXPECT_EQ(points.attributes.integers.count("part"), 1u);
  // A folder that holds files is never overwritten, and a failed save leaves no staging folder behind.
  EXPECT_FALSE(execute_reporting(state, make_command("save_result", {folder.string()})));
  EXPECT_NE(state.status.find("not empty"), std::string::npos) << state.status;
  std::size_t entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder.parent_path()))
    if (entry.path().filename().string().find("partreg_ui_saved_result.partial") != std::string::npos)
      ++entries;
  EXPECT_EQ(entries, 0u);
  std::filesystem::remove_all(folder);
}

TEST(RegistrationStepper, RegisterNeedsAModelAndAnObservation) {
  AppState state;
  EXPECT_FALSE(execute_reporting(state, make_command("register", {"holistic"})));
  EXPECT_FALSE(execute_reporting(state, make_command("step", {"1"})));
  EXPECT_TRUE(state.status_is_error);
}

}  // namespace
}  // namespace partreg::ui
