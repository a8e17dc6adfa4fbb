#pragma once
/// \file
/// One frame of the app: the scene drawn by the renderer, then the ImGui panels drawn over it by the
/// overlay renderer, in the renderer's own framebuffer. The window and the headless path both use it, so a
/// window screenshot and a headless one are the same pixels.

#include <memory>
#include <vector>

#include "partreg/render/image.hpp"
#include "partreg/render/renderer.hpp"
#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"
#include "partreg/ui/panels.hpp"

namespace partreg::ui {

class GuiFrame {
 public:
  /// Creates the renderer, the overlay renderer and an ImGui context (no .ini file, light style) in the
  /// current GL context.
  explicit GuiFrame(const Viewport& viewport,
                    render::Antialiasing antialiasing = render::Antialiasing::multisample);
  ~GuiFrame();
  GuiFrame(const GuiFrame&) = delete;
  GuiFrame& operator=(const GuiFrame&) = delete;

  /// Draws one frame of `state` (resizing to its viewport). Mouse and keyboard input must already be in
  /// ImGui::GetIO() (the window does that; headless frames have no mouse). Commands the panels emit are
  /// appended to `emitted`. `seconds` is the time since the last frame. Interactive frames skip
  /// multisampling (see render::FrameQuality): the window asks for them while something moves.
  void draw(AppState& state, double seconds, std::vector<Command>& emitted,
            render::FrameQuality quality = render::FrameQuality::full);
  /// True while the last frame's panels hold an item (a slider being dragged) or a shape animates: the next
  /// frames will change, so they may be drawn interactively.
  bool animating() const;
  /// The last frame, top row first.
  render::Image read_pixels() const;
  /// The GL framebuffer holding the last frame (a window blits it).
  unsigned framebuffer() const;
  int width() const;
  int height() const;
  /// True when ImGui uses the mouse (the viewport must then ignore it).
  bool wants_mouse() const;
  PanelState& panel_state() { return panel_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  PanelState panel_;
};

}  // namespace partreg::ui
