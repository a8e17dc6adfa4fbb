// The real GLFW window under Xvfb: replays the labelling script in the window and compares its screenshot
// with the same baseline as the headless run (one renderer, one read-back).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "render/image_baseline.hpp"
#include "ui/gui_scripts.hpp"

namespace partreg::ui {
namespace {

TEST(GuiWindow, ReplaysAScriptInTheWindow) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run is not installed";
  const std::filesystem::path folder = testing::ui_fixture_folder();
  const std::filesystem::path script = folder / "window_label.txt", shot = folder / "window_label.png";
  std::filesystem::remove(shot);
  std::ofstream(script) << testing::label_script() << "screenshot " << shot.string() << "\n";
  const std::string command = "xvfb-run -a -s '-screen 0 1600x1000x24' " + std::string(PARTREG_BINARY_DIR) +
                              "/partreg-gui --size 1280x800 --script " + script.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  ASSERT_TRUE(std::filesystem::exists(shot));
  testing::expect_matches_baseline(render::read_png(shot), "gui_label_paint");
}

}  // namespace
}  // namespace partreg::ui
