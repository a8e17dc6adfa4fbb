#include <gtest/gtest.h>

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

TEST(RegistrationStepper, RegisterNeedsAModelAndAnObservation) {
  AppState state;
  EXPECT_FALSE(execute_reporting(state, make_command("register", {"holistic"})));
  EXPECT_FALSE(execute_reporting(state, make_command("step", {"1"})));
  EXPECT_TRUE(state.status_is_error);
}

}  // namespace
}  // namespace partreg::ui
