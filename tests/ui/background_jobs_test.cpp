// The window's background jobs without a window: a registration and a training run on worker threads and
// enter the state when collected; a training reports its progress, refuses a second start and loads its
// model.
#include "background_jobs.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "ui/ui_fixtures.hpp"

namespace partreg::app {
namespace {

// Collects once a frame (every 5 ms) until the job has ended or a minute has passed.
template <typename Job>
void collect_until_done(Job& job, ui::AppState& state) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (job.running() && std::chrono::steady_clock::now() < deadline) {
    job.collect(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

TEST(BackgroundRegistration, RunsOffTheCallingThreadAndAppliesItsResult) {
  ui::AppState state;
  ui::execute(state, ui::make_command("load", {testing::small_model_path().string()}));
  ui::execute(state, ui::make_command("load", {testing::observed_cloud_path().string()}));
  BackgroundRegistration registration;
  registration.start(state, ui::make_command("register", {"hol+part"}));
  ASSERT_TRUE(registration.running()) << state.status;
  EXPECT_NE(state.status.find("registering (hol+part)"), std::string::npos) << state.status;
  EXPECT_TRUE(state.registering.running);  // the panels draw its progress bar
  EXPECT_FALSE(state.registration.result);  // nothing enters the state before collect() sees it end
  collect_until_done(registration, state);
  ASSERT_FALSE(registration.running());
  EXPECT_FALSE(state.registering.running);
  ASSERT_TRUE(state.registration.result) << state.status;
  EXPECT_EQ(state.registration.settings.variant, core::Variant::hol_part);
  EXPECT_NE(state.status.find("registered (hol+part)"), std::string::npos) << state.status;
}

TEST(SharedProgress, KeepsTheLastReportForTheUiThread) {
  const auto shared = std::make_shared<SharedProgress>();
  const core::ProgressListener listener = SharedProgress::listener(shared);
  listener(core::Progress{1, 3, "fitted holistic"});
  listener(core::Progress{2, 3, "fitted handle"});
  EXPECT_NEAR(shared->progress.fraction, 2.0 / 3.0, 1e-12);
  EXPECT_EQ(shared->progress.line, "fitted handle");
}

TEST(BackgroundRegistration, AResultForAModelNoLongerLoadedIsDiscarded) {
  ui::AppState state;
  ui::execute(state, ui::make_command("load", {testing::small_model_path().string()}));
  ui::execute(state, ui::make_command("load", {testing::observed_cloud_path().string()}));
  BackgroundRegistration registration;
  registration.start(state, ui::make_command("register", {"holistic"}));
  ui::execute(state, ui::make_command("load", {testing::small_model_path().string()}));  // a new model
  collect_until_done(registration, state);
  EXPECT_FALSE(state.registration.result);
  EXPECT_TRUE(state.status_is_error);
  EXPECT_NE(state.status.find("discarded"), std::string::npos) << state.status;
}

TEST(BackgroundTraining, RunsOffTheCallingThreadWithProgressAndLoadsItsModel) {
  const std::filesystem::path folder = testing::mug_dataset("background_dataset", 3);
  const std::string model = (testing::ui_fixture_folder() / "background.prm").string();
  std::filesystem::remove(model);
  ui::AppState state;
  BackgroundTraining training;
  const ui::Command command = ui::make_command("train", {folder.string()}, {{"out", model}});
  training.start(state, command);
  ASSERT_TRUE(training.running()) << state.status;
  EXPECT_TRUE(state.training.running);
  EXPECT_FALSE(state.status_is_error);
  // A second Train while one runs is refused, and the first goes on.
  training.start(state, command);
  EXPECT_TRUE(state.status_is_error);
  EXPECT_NE(state.status.find("already running"), std::string::npos) << state.status;
  EXPECT_TRUE(training.running());

  // The window collects once a frame; the shown fraction never goes back.
  std::vector<double> fractions;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (training.running() && std::chrono::steady_clock::now() < deadline) {
    training.collect(state);
    if (state.training.running) fractions.push_back(state.training.fraction);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(training.running()) << "training did not end in 5 minutes";
  ASSERT_FALSE(fractions.empty());
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GE(fractions[i], fractions[i - 1]);
  EXPECT_LE(fractions.back(), 1.0);
  EXPECT_FALSE(state.training.running);
  EXPECT_FALSE(state.status_is_error) << state.status;
  ASSERT_TRUE(state.shapes.loaded());
  EXPECT_EQ(state.shapes.model_path, model);
  EXPECT_EQ(state.shapes.model->training.instances.size(), 3u);
  EXPECT_EQ(state.mode, ui::Mode::shape_space);
}

TEST(BackgroundTraining, AFailureIsReportedAndNothingIsLoaded) {
  ui::AppState state;
  BackgroundTraining training;
  training.start(state, ui::make_command("train", {(testing::ui_fixture_folder() / "no_such").string()}));
  EXPECT_FALSE(training.running());
  EXPECT_TRUE(state.status_is_error);
  // A dataset of one instance starts, then fails in the worker: the status says why.
  const std::filesystem::path folder = testing::mug_dataset("one_mug_dataset", 1);
  training.start(state, ui::make_command("train", {folder.string()},
                                         {{"out", (testing::ui_fixture_folder() / "never.prm").string()}}));
  ASSERT_TRUE(training.running()) << state.status;
  while (training.running()) {
    training.collect(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(state.status_is_error);
  EXPECT_NE(state.status.find("training failed"), std::string::npos) << state.status;
  EXPECT_FALSE(state.shapes.loaded());
  EXPECT_FALSE(state.training.running);
}

TEST(BackgroundTraining, DestroyingItCancelsARunningTraining) {
  const std::filesystem::path folder = testing::mug_dataset("cancelled_dataset", 3);
  const std::filesystem::path model = testing::ui_fixture_folder() / "cancelled.prm";
  std::filesystem::remove(model);
  {
    ui::AppState state;
    BackgroundTraining training;
    training.start(state, ui::make_command("train", {folder.string()}, {{"out", model.string()}}));
    ASSERT_TRUE(training.running());
  }  // returns once the worker stopped at its next step
  EXPECT_FALSE(std::filesystem::exists(model));
}

}  // namespace
}  // namespace partreg::app
