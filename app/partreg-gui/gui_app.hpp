#pragma once
/// \file
/// The two ways partreg-gui runs: replaying a script headlessly (OSMesa) and the GLFW window.

#include <string>
#include <vector>

#include "partreg/render/renderer.hpp"
#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"

namespace partreg::app {

struct GuiOptions {
  std::string input;        ///< a model, mesh or cloud to load first (may be empty)
  std::string script_path;  ///< commands to replay (may be empty in the window)
  bool headless = false;
  int width = 1280, height = 800;
  render::Antialiasing antialiasing = render::Antialiasing::multisample;
};

/// Frames drawn before a screenshot so that ImGui's layout (tab selection, auto-sized items) has settled.
inline constexpr int kSettleFrames = 3;

/// Runs the window until it is closed or the script asks to quit. Returns the exit code.
int run_window(const GuiOptions& options, ui::AppState& state, const std::vector<ui::Command>& script);

}  // namespace partreg::app
