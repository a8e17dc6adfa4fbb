#pragma once
/// \file
/// What the viewport shows for the app state, as a renderer scene and camera.

#include "partreg/render/scene.hpp"
#include "partreg/ui/app_state.hpp"

namespace partreg::ui {

/// The scene of the current mode: the labelled mesh with one colour per face (labelling), the canonical
/// mesh deformed by the sliders coloured by part (shape space), or the observed cloud in red with the
/// registration's canonical points at the current step, coloured by part, and lines to their closest
/// observed points (registration).
render::Scene build_scene(AppState& state);

/// The renderer's camera for the state's orbit view and viewport.
render::Camera render_camera(const AppState& state);

}  // namespace partreg::ui
