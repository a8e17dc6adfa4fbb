// The GLFW window: feeds mouse and keyboard to ImGui and, where ImGui does not want them, to the viewport
// as commands (orbit, pan, zoom, paint, fill, centre, named views), then draws a GuiFrame and blits it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <iostream>
#include <optional>

#include "background_jobs.hpp"
#include "gui_app.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/gui_frame.hpp"

#ifdef PARTREG_GUI_HAS_WINDOW
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "partreg/render/glfw_context.hpp"
#endif

namespace partreg::app {

#ifndef PARTREG_GUI_HAS_WINDOW
int run_window(const GuiOptions&, ui::AppState&, const std::vector<ui::Command>&) {
  throw UsageError("this build has no window (GLFW was not found); use --headless --script FILE");
}
#else
namespace {

// Scroll and characters arrive by callback; the rest is polled each frame. `any` says whether anything at
// all happened since the last frame (the loop sleeps when nothing does).
struct WindowInput {
  double scroll = 0.0;
  std::vector<unsigned> characters;
  std::vector<std::pair<int, bool> > keys;
  bool any = false;
};

WindowInput* input_of(GLFWwindow* window) {
  return static_cast<WindowInput*>(glfwGetWindowUserPointer(window));
}

void install_callbacks(GLFWwindow* window, WindowInput& input) {
  glfwSetWindowUserPointer(window, &input);
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    input_of(w)->scroll += dy;
    input_of(w)->any = true;
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned c) {
    input_of(w)->characters.push_back(c);
    input_of(w)->any = true;
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (key >= 0 && key < 512 && action != GLFW_REPEAT)
      input_of(w)->keys.emplace_back(key, action == GLFW_PRESS);
    input_of(w)->any = true;
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double, double) { input_of(w)->any = true; });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int, int, int) { input_of(w)->any = true; });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { input_of(w)->any = true; });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { input_of(w)->any = true; });
}

void map_keys(ImGuiIO& io) {
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
}

std::string text(double value) { return std::to_string(value); }

// The viewport's share of the input, as commands.
class ViewportMouse {
 public:
  void update(GLFWwindow* window, const ui::GuiFrame& frame, const ui::PanelState& panel, WindowInput& input,
              std::vector<ui::Command>& out) {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                       glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool free = !frame.wants_mouse();
    const double dx = x - last_x_, dy = y - last_y_;
    if (free && left && !was_left_) {
      const double now = glfwGetTime();
      if (now - last_click_ < 0.3) out.push_back(ui::make_command("centre", {text(x), text(y)}));
      last_click_ = now;
      if (panel.tool == ui::Tool::fill) out.push_back(ui::make_command("fill", {text(x), text(y)}));
    }
    if (free && left && panel.tool == ui::Tool::paint && (!was_left_ || dx != 0.0 || dy != 0.0))
      out.push_back(ui::make_command("paint", {text(x), text(y)}));
    if (free && left && was_left_ && panel.tool == ui::Tool::orbit && (dx != 0.0 || dy != 0.0))
      out.push_back(ui::make_command("orbit", {text(-0.4 * dx), text(0.4 * dy)}));
    if (free && right && was_right_ && (dx != 0.0 || dy != 0.0))
      out.push_back(ui::make_command("pan", {text(dx), text(dy)}));
    if (free && input.scroll != 0.0)
      out.push_back(ui::make_command("zoom", {text(std::pow(1.1, input.scroll))}));
    last_x_ = x, last_y_ = y, was_left_ = left, was_right_ = right;
  }

 private:
  double last_x_ = 0.0, last_y_ = 0.0, last_click_ = -1.0;
  bool was_left_ = false, was_right_ = false;
};

void feed_imgui(GLFWwindow* window, WindowInput& input, std::vector<ui::Command>& out) {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  io.MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = glfwGetMouseButton(window, b) == GLFW_PRESS;
  io.MouseWheel = static_cast<float>(input.scroll);
  for (const unsigned c : input.characters) io.AddInputCharacter(c);
  for (const auto& [key, down] : input.keys) {
    io.KeysDown[key] = down;
    if (!down || io.WantCaptureKeyboard) continue;
    // Keys for the viewport: named views and undo/redo.
    const char* views[] = {"front", "side", "top", "iso"};
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_4)
      out.push_back(ui::make_command("camera", {views[key - GLFW_KEY_1]}));
    if (key == GLFW_KEY_Z && io.KeyCtrl) out.push_back(ui::make_command("undo"));
    if (key == GLFW_KEY_Y && io.KeyCtrl) out.push_back(ui::make_command("redo"));
  }
  io.KeyCtrl = glfwGetKey(window, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
               glfwGetKey(window, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  io.KeyShift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
}

// Commands that move what the viewport shows while the mouse drags: their frames may be drawn interactively.
bool moves_view(const std::vector<ui::Command>& commands) {
  return std::any_of(commands.begin(), commands.end(), [](const ui::Command& command) {
    return command.verb == "orbit" || command.verb == "pan" || command.verb == "zoom" ||
           command.verb == "paint";
  });
}

// When the window may sleep: after a few frames in which nothing happened (ImGui settles hover highlights
// and the full-quality frame after an interactive one over a frame or two). It then waits for an event, so
// an idle window costs nothing.
class FramePacer {
 public:
  /// Waits for an event when idle, else only polls. Returns false when it woke with nothing to draw.
  bool wait(const WindowInput& input, bool busy) {
    if (quiet_frames_ < kQuietFrames || busy) {
      glfwPollEvents();
      return true;
    }
    glfwWaitEventsTimeout(0.5);
    return input.any;
  }
  /// After a frame: whether anything happened or is still moving.
  void drawn(bool active) { quiet_frames_ = active ? 0 : quiet_frames_ + 1; }

 private:
  static constexpr int kQuietFrames = 3;
  int quiet_frames_ = 0;
};

// Draws the frame as it is now at full quality, then writes it: the same read-back as the headless path. A
// file that cannot be written is reported in the status line.
void write_screenshot(ui::GuiFrame& frame, ui::AppState& state, const std::string& path) {
  std::vector<ui::Command> ignored;
  for (int i = 0; i < kSettleFrames; ++i) frame.draw(state, 1.0 / 60.0, ignored);
  try {
    render::write_png(path, frame.read_pixels());
    state.status = "wrote " + path;
    state.status_is_error = false;
  } catch (const std::exception& e) {
    state.status = e.what();
    state.status_is_error = true;
  }
}

}  // namespace

int run_window(const GuiOptions& options, ui::AppState& state, const std::vector<ui::Command>& script) {
  render::GlfwContext context(options.width, options.height, "partreg-gui");
  GLFWwindow* window = context.window();
  ui::GuiFrame frame(state.viewport, options.antialiasing);
  map_keys(ImGui::GetIO());
  WindowInput input;
  install_callbacks(window, input);
  ViewportMouse mouse;
  BackgroundRegistration registration;
  BackgroundTraining training;
  std::size_t next = 0;  // the script runs one command per frame, after its tab has been drawn
  int settle = 0;
  FramePacer pacer;
  auto last = std::chrono::steady_clock::now();
  while (!state.quit_requested) {
    const bool busy =
        registration.running() || training.running() || next < script.size() || frame.animating();
    if (!pacer.wait(input, busy) && !glfwWindowShouldClose(window)) continue;
    if (glfwWindowShouldClose(window)) {
      if (!state.labelling.dirty || frame.panel_state().confirmed_quit) break;
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      frame.panel_state().confirm_quit = true;  // the panels ask first
    }
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    std::vector<ui::Command> commands;
    if (width > 0 && height > 0 && (width != state.viewport.width || height != state.viewport.height))
      commands.push_back(ui::make_command("resize", {std::to_string(width), std::to_string(height)}));
    feed_imgui(window, input, commands);
    mouse.update(window, frame, frame.panel_state(), input, commands);
    const bool active = input.any || !commands.empty() || frame.animating();
    // Multisampling costs llvmpipe two to three times as long: frames drawn while something moves skip it.
    const bool moving = frame.animating() || moves_view(commands);
    input = WindowInput{};
    install_callbacks(window, input);
    const auto now = std::chrono::steady_clock::now();
    frame.draw(state, std::min(std::chrono::duration<double>(now - last).count(), 0.1), commands,
               moving ? render::FrameQuality::interactive : render::FrameQuality::full);
    last = now;
    pacer.drawn(active || moving);
    context.present(frame.framebuffer(), frame.width(), frame.height());
    for (const ui::Command& command : commands) {
      if (command.verb == "register")
        registration.start(state, command);
      else if (command.verb == "train")
        training.start(state, command);
      else if (ui::Outcome outcome;
               ui::execute_reporting(state, command, &outcome) && !outcome.screenshot_path.empty())
        write_screenshot(frame, state, outcome.screenshot_path);
    }
    registration.collect(state);
    training.collect(state);
    if (frame.panel_state().confirmed_quit) break;
    if (next < script.size() && ++settle >= kSettleFrames) {
      settle = 0;
      const ui::Command& command = script[next++];
      ui::Outcome outcome;
      if (!ui::execute_reporting(state, command, &outcome)) {
        std::cerr << "partreg-gui: line " << command.line << ": " << state.status << '\n';
        return 1;
      }
      if (!outcome.screenshot_path.empty()) {
        write_screenshot(frame, state, outcome.screenshot_path);
        if (state.status_is_error) {
          std::cerr << "partreg-gui: line " << command.line << ": " << state.status << '\n';
          return 1;
        }
        std::cerr << command.line << ": wrote " << outcome.screenshot_path << '\n';
      }
      if (next == script.size() && !options.script_path.empty()) break;  // a script run ends with its script
    }
  }
  return 0;
}
#endif

}  // namespace partreg::app
