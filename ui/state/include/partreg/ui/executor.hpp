#pragma once
/// \file
/// Applying commands to the app state. A command that fails (a file that does not load, a labels file for
/// another mesh, an unknown part) throws and leaves the state as it was; the caller shows the message.

#include <string>

#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"

namespace partreg::ui {

/// What the caller must do after a command that the state cannot do itself.
struct Outcome {
  std::string message;          ///< one line for the status bar (may be empty)
  std::string screenshot_path;  ///< non-empty: render the current frame and write it here
};

/// Applies `command`. Throws InputError (bad files, nothing under the brush) or UsageError (bad arguments,
/// unknown parts or spaces); the state is then unchanged.
Outcome execute(AppState& state, const Command& command);

/// execute() that catches InputError and UsageError into state.status (status_is_error) instead.
/// Returns false when the command failed.
bool execute_reporting(AppState& state, const Command& command, Outcome* outcome = nullptr);

}  // namespace partreg::ui
