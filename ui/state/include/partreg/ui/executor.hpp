#pragma once
/// \file
/// Applying commands to the app state. A command that fails (a file that does not load, a labels file for
/// another mesh, an unknown part) throws and leaves the state as it was; the caller shows the message.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "partreg/core/registration/registration.hpp"
#include "partreg/ui/app_state.hpp"
#include "partreg/ui/commands.hpp"
#include "partreg/ui/tools.hpp"

namespace partreg::ui {

/// What the caller must do after a command that the state cannot do itself.
struct Outcome {
  std::string message;          ///< one line for the status bar (may be empty)
  std::string screenshot_path;  ///< non-empty: render the current frame and write it here
};

/// One verb of the app's command language, declared once: what it takes (checked when a script line or a
/// panel's command is parsed) and what it does.
struct Verb {
  std::string name;                                       ///< e.g. "paint"
  int min_arguments = 0;                                  ///< positional arguments, at least
  int max_arguments = 0;                                  ///< and at most
  std::vector<std::string> options;                       ///< the `key=value` options it accepts
  std::string synopsis;                                   ///< its arguments, for help and docs/gui.md
  std::function<Outcome(AppState&, const Command&)> run;  ///< applies it (throws as execute() says)
};

/// Every verb, in the order docs/gui.md lists them.
const std::vector<Verb>& verbs();

/// The verb called `name`, or null.
const Verb* find_verb(const std::string& name);

/// A `register` command made ready to run anywhere: it holds everything the registration reads, so the
/// window can run it off the UI thread and keep drawing.
struct RegistrationJob {
  std::shared_ptr<const core::CategoryModel> model;
  core::Points observed;  ///< data units
  core::RegistrationSettings settings;
  /// Runs the registration (the slow part; touches no state), telling `progress` of each space fitted.
  core::RegistrationResult run(const core::ProgressListener& progress = {}) const {
    return core::register_observation(*model, observed, settings, progress);
  }
};

/// Checks a `register` command against the state and prepares its job (UsageError when no model or no
/// observation is loaded, or for bad options).
RegistrationJob prepare_registration(AppState& state, const Command& command);

/// Puts a finished registration into the state (the step at its end) and says what it did.
Outcome apply_registration(AppState& state, const RegistrationJob& job, core::RegistrationResult result);

/// Checks a `train` command and prepares its job (copies of the labels it needs), so the window can run it
/// off the UI thread. Throws UsageError / InputError when it cannot start.
TrainingJob prepare_training(const AppState& state, const Command& command);

/// Loads the model a finished training job wrote (what `train` does after training) and reports `summary`.
Outcome apply_training(AppState& state, const TrainingJob& job, const std::string& summary);

/// Moves an animated shape slider on by `seconds` (called once per drawn frame; nothing when none runs).
void advance_animation(AppState& state, double seconds);

/// Applies `command`. Throws InputError (bad files, nothing under the brush) or UsageError (bad arguments,
/// unknown parts or spaces); the state is then unchanged.
Outcome execute(AppState& state, const Command& command);

/// execute() that catches InputError and UsageError into state.status (status_is_error) instead.
/// Returns false when the command failed.
bool execute_reporting(AppState& state, const Command& command, Outcome* outcome = nullptr);

}  // namespace partreg::ui
