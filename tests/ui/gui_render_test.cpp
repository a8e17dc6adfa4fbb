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

render::Image replay(const std::string& script) {
  render::OsMesaContext context;
  AppState state;
  for (const Command& command : parse_script(script)) execute(state, command);
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

}  // namespace
}  // namespace partreg::ui
