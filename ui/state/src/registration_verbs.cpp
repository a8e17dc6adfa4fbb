// The registration verbs: running it, saving its result, changing the observation, stepping through its
// history.
#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/io/result_file.hpp"
#include "partreg/ui/tools.hpp"
#include "verb_support.hpp"

namespace partreg::ui {
namespace detail {
namespace {

Outcome run_registration(AppState& state, const Command& command) {
  const RegistrationJob job = prepare_registration(state, command);
  return apply_registration(state, job, job.run());
}

// The result files `partreg register` writes, into a new folder (all or nothing).
Outcome save_result(AppState& state, const Command& command) {
  const RegistrationDocument& registration = state.registration;
  if (!registration.result) throw UsageError("nothing to save: register first");
  const nlohmann::json report = io::result_json(*registration.result, registration.settings,
                                                {state.shapes.model_path, registration.observed_path});
  const auto written = io::write_result_folder(command.arguments.at(0), *state.shapes.model,
                                               *registration.result, report, registration.frames);
  return message("saved " + std::to_string(written.size()) + " files to " + command.arguments.at(0));
}

Outcome move_step(AppState& state, int target) {
  if (!state.registration.result) throw UsageError("nothing to step through (register VARIANT first)");
  const int last = static_cast<int>(state.registration.result->history.size()) - 1;
  state.registration.step = std::clamp(target, -1, last);
  state.mode = Mode::registration;
  return message("step " + std::to_string(state.registration.step + 1) + " of " + std::to_string(last + 1));
}

// The register verb's options: every registration setting but the variant, which is its argument.
std::vector<std::string> register_options() {
  std::vector<std::string> names;
  for (const core::RegistrationOption& option : core::registration_options())
    if (option.name != "variant") names.push_back(option.name);
  return names;
}

}  // namespace

std::vector<Verb> registration_verbs() {
  return {
      {"register", 1, 1, register_options(),
       "VARIANT [NAME=VALUE ...]  (every registration setting, as partreg register's flags)",
       run_registration},
      {"save_result",
       1,
       1,
       {},
       "FOLDER  (result.json, points.ply, mesh.ply, frames.json, as `partreg register` writes)",
       save_result},
      {"partial_view",
       1,
       1,
       {"count"},
       "I [count=42]  (what a depth camera sees of the observation from view I)",
       [](AppState& s, const Command& c) {
         return message(
             take_partial_view(s, integer(c.arguments[0], "I"), integer(c.option("count", "42"), "count")));
       }},
      {"perturb",
       2,
       2,
       {"seed"},
       "noise|outliers|rotation|translation LEVEL [seed=S]  (the paper's units)",
       [](AppState& s, const Command& c) {
         const int seed = integer(c.option("seed", "1"), "seed");
         return message(perturb_observation(s, c.arguments[0], number(c.arguments[1], "LEVEL"),
                                            static_cast<std::uint64_t>(seed)));
       }},
      {"step",
       1,
       1,
       {},
       "N  (forward N history steps; negative goes back)",
       [](AppState& s, const Command& c) {
         return move_step(s, s.registration.step + integer(c.arguments[0], "N"));
       }},
      {"goto_step",
       1,
       1,
       {},
       "I | first | last",
       [](AppState& s, const Command& c) {
         const std::string& where = c.arguments[0];
         if (where == "first") return move_step(s, 0);
         if (where == "last") return move_step(s, 1 << 30);
         return move_step(s, integer(where, "I") - 1);
       }},
  };
}

}  // namespace detail

RegistrationJob prepare_registration(AppState& state, const Command& command) {
  detail::require_model(state);
  if (state.registration.observed.rows() == 0)
    throw UsageError("no observation is loaded (load CLOUD first)");
  RegistrationJob job{state.shapes.model, state.registration.observed, {}};
  job.settings.viewpoint = state.registration.viewpoint;  // from views.json, or an earlier viewpoint=
  core::set_registration_option(job.settings, "variant", command.arguments.at(0));
  for (const auto& [name, value] : command.options) core::set_registration_option(job.settings, name, value);
  state.registration.viewpoint = job.settings.viewpoint;  // viewpoint=none forgets it for later runs too
  return job;
}

Outcome apply_registration(AppState& state, const RegistrationJob& job, core::RegistrationResult result) {
  state.registration.settings = job.settings;
  state.registration.step = static_cast<int>(result.history.size()) - 1;
  state.registration.result = std::move(result);
  state.mode = Mode::registration;
  std::ostringstream text;
  text << "registered (" << core::enum_name(job.settings.variant) << ") in "
       << state.registration.result->seconds << " s, " << state.registration.result->history.size()
       << " steps";
  return detail::message(text.str());
}

}  // namespace partreg::ui
