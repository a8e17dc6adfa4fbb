// Scripted GUI sessions drawn headlessly (OSMesa) with their panels, compared with committed baselines.
#include <gtest/gtest.h>

#include "partreg/render/osmesa_context.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/gui_frame.hpp"
#include "partreg/ui/script.hpp"
#include "render/image_baseline.hpp"
#include "ui/gui_scripts.hpp"

namespace partreg::ui {
namespace {

// `adjust` changes what no script can (a background job's progress) before the frames are drawn.
render::Image replay(const std::string& script, void (*adjust)(AppState&) = nullptr) {
  render::OsMesaContext context;
  AppState state;
  for (const Command& command : parse_script(script)) execute(state, command);
  if (adjust) adjust(state);
  GuiFrame frame(state.viewport);
  std::vector<Command> emitted;
  for (int i = 0; i < 3; ++i) frame.draw(state, 1.0 / 60.0, emitted);
  EXPECT_TRUE(emitted.empty()) << "nothing clicks in a headless frame";
  return frame.read_pixels();
}

TEST(GuiRender, LabellingTheHandleByPainting) {
  testing::expect_matches_baseline(replay(testing::label_script()), "gui_label_paint");
}

TEST(GuiRender, MovingAShapeSlider) {
  testing::expect_matches_baseline(replay(testing::shape_script()), "gui_shape_slider");
}

TEST(GuiRender, SteppingARegistration) {
  testing::expect_matches_baseline(replay(testing::registration_script()), "gui_registration_step");
}

TEST(GuiRender, TrainingProgressShowsInEveryTab) {
  // A training started from the panels runs on a worker thread; its progress bar sits above the status line
  // whichever tab is open (here the registration tab of the stepping session).
  const auto training = [](AppState& state) { state.training = {true, 0.4, "CPD 4 of 10 (mug_003)"}; };
  testing::expect_matches_baseline(replay(testing::registration_script(), training), "gui_training_progress");
}

}  // namespace
}  // namespace partreg::ui
