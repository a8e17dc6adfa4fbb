#pragma once
// What the groups of verbs share (internal to partreg_ui_state). Each group's file declares its verbs with
// their handlers (file_verbs.cpp, labelling_verbs.cpp, shape_verbs.cpp, registration_verbs.cpp,
// view_verbs.cpp); executor.cpp joins the groups into the one table.

#include <string>
#include <vector>

#include "partreg/core/space/category_model.hpp"
#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"
#include "partreg/ui/executor.hpp"
#include "partreg/ui/view.hpp"

namespace partreg::ui::detail {

/// A verb's argument as a finite number or a whole number; UsageError naming `what` otherwise.
double number(const std::string& text, const std::string& what);
int integer(const std::string& text, const std::string& what);

/// Frames the mode's geometry from the named view ("iso", "front", ...).
void fit_view(AppState& state, const std::string& name = "iso");
/// Frames the mode's geometry again without turning the camera.
void refit_keeping_orientation(AppState& state);

/// An outcome that only reports `text`.
Outcome message(const std::string& text);

/// The loaded model, for the verbs that need one (UsageError when none is).
const core::CategoryModel& require_model(const AppState& state);

/// The labelled mesh's surface under the pixel of the command's X Y arguments (InputError when none is).
Hit pick(const AppState& state, const Command& command);

/// Loads a model file into the shape-space mode (the `load` verb, and a finished training).
Outcome load_model(AppState& state, const std::string& path);

/// The verbs of each group, in the order docs/gui.md lists them.
std::vector<Verb> file_verbs();
std::vector<Verb> labelling_verbs();
std::vector<Verb> shape_verbs();
std::vector<Verb> registration_verbs();
std::vector<Verb> view_verbs();

}  // namespace partreg::ui::detail
