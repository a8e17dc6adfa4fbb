// The view verbs: the mode, the camera, the frame's size, the panels, screenshots and quitting.
#include <algorithm>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "verb_support.hpp"

namespace partreg::ui::detail {
namespace {

Outcome camera_command(AppState& state, const Command& command) {
  fit_view(state, command.arguments[0]);
  return message("camera " + command.arguments[0]);
}

Outcome orbit(AppState& state, const Command& command) {
  state.view.azimuth_deg += number(command.arguments[0], "D_AZIMUTH_DEG");
  state.view.elevation_deg =
      std::clamp(state.view.elevation_deg + number(command.arguments[1], "D_ELEVATION_DEG"), -89.9, 89.9);
  return {};
}

Outcome zoom(AppState& state, const Command& command) {
  const double factor = number(command.arguments[0], "FACTOR");
  if (factor <= 0.0) throw UsageError("FACTOR must be positive");
  state.view.distance /= factor;
  return {};
}

Outcome pan(AppState& state, const Command& command) {
  const CameraFrame frame = camera_frame(state.view, state.viewport);
  const Eigen::Vector3d backward = (frame.eye - frame.target).normalized();
  const Eigen::Vector3d right = frame.up.cross(backward).normalized(), up = backward.cross(right);
  const double pixel = pixel_size_at(state.view, state.viewport, state.view.distance);
  // Dragging right moves the scene right: the target goes left.
  state.view.target +=
      pixel * (-number(command.arguments[0], "DX") * right + number(command.arguments[1], "DY") * up);
  return {};
}

Outcome centre(AppState& state, const Command& command) {
  const Hit hit = pick(state, command);
  state.view.distance = (camera_frame(state.view, state.viewport).eye - hit.point).norm();
  state.view.target = hit.point;
  return message("centred on the picked point");
}

Outcome resize(AppState& state, const Command& command) {
  const int width = integer(command.arguments[0], "WIDTH"), height = integer(command.arguments[1], "HEIGHT");
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw UsageError("sizes are 16 to 8192 pixels");
  state.viewport.width = width;
  state.viewport.height = height;
  return {};
}

}  // namespace

std::vector<Verb> view_verbs() {
  return {
      {"mode",
       1,
       1,
       {},
       "labelling | shape | registration",
       [](AppState& s, const Command& c) {
         s.mode = core::parse_enum<Mode>(c.arguments[0]);
         fit_view(s);
         return message("");
       }},
      {"camera", 1, 1, {}, "front | side | top | iso", camera_command},
      {"orbit", 2, 2, {}, "D_AZIMUTH_DEG D_ELEVATION_DEG", orbit},
      {"zoom", 1, 1, {}, "FACTOR  (>1 moves closer)", zoom},
      {"pan", 2, 2, {}, "DX DY  (pixels)", pan},
      {"centre", 2, 2, {}, "X Y  (orbit about the surface point under the pixel)", centre},
      {"resize", 2, 2, {}, "WIDTH HEIGHT", resize},
      {"panels",
       1,
       1,
       {},
       "on | off",
       [](AppState& s, const Command& c) {
         if (c.arguments[0] != "on" && c.arguments[0] != "off") throw UsageError("panels on | off");
         s.show_panels = c.arguments[0] == "on";
         s.viewport.panel_width = s.show_panels ? Viewport{}.panel_width : 0;
         return message("");
       }},
      {"screenshot",
       1,
       1,
       {},
       "PATH.png",
       [](AppState&, const Command& c) {
         if (io::lower_extension(c.arguments[0]) != ".png") throw UsageError("screenshots are .png files");
         return Outcome{"", c.arguments[0]};
       }},
      {"quit",
       0,
       0,
       {},
       "",
       [](AppState& s, const Command&) {
         s.quit_requested = true;
         return message("");
       }},
  };
}

}  // namespace partreg::ui::detail
