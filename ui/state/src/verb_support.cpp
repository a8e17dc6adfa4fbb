#include "verb_support.hpp"

#include <cmath>
#include <exception>

#include "partreg/core/errors.hpp"

namespace partreg::ui::detail {

double number(const std::string& text, const std::string& what) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  throw UsageError(what + " must be a number, not '" + text + "'");
}

int integer(const std::string& text, const std::string& what) {
  const double value = number(text, what);
  if (value != std::floor(value)) throw UsageError(what + " must be a whole number, not '" + text + "'");
  return static_cast<int>(value);
}

void fit_view(AppState& state, const std::string& name) {
  Eigen::Vector3d low, high;
  mode_bounds(state, low, high);
  state.view = named_view(name, low, high, state.viewport);
  // A shown training instance goes beside the shape along the new view's horizontal: place it, measure again.
  if (state.shapes.shown_instance < 0) return;
  place_instance_beside(state);
  mode_bounds(state, low, high);
  state.view = named_view(name, low, high, state.viewport);
}

// Frames the mode's geometry again without turning the camera (a fit's target and distance do not depend
// on the orientation).
void refit_keeping_orientation(AppState& state) {
  Eigen::Vector3d low, high;
  mode_bounds(state, low, high);
  const OrbitView fitted = named_view("iso", low, high, state.viewport);
  state.view.target = fitted.target;
  state.view.distance = fitted.distance;
}

Outcome message(const std::string& text) { return Outcome{text, ""}; }

// The loaded model, for the verbs that need one.
const core::CategoryModel& require_model(const AppState& state) {
  if (!state.shapes.loaded()) throw UsageError("no model is loaded (load MODEL.prm first)");
  return *state.shapes.model;
}

Hit pick(const AppState& state, const Command& command) {
  const double x = number(command.arguments[0], "X"), y = number(command.arguments[1], "Y");
  if (!state.labelling.loaded()) throw UsageError("no mesh is loaded to label (load MESH first)");
  const std::optional<Hit> hit = intersect(state.labelling.mesh, pixel_ray(state.view, state.viewport, x, y));
  if (!hit)
    throw InputError("no surface under the pixel (" + command.arguments[0] + ", " + command.arguments[1] +
                     ")");
  return *hit;
}

}  // namespace partreg::ui::detail
