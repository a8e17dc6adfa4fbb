// The shape-space verbs: the sliders, their animation, the training instances beside them, and training.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/ui/tools.hpp"
#include "verb_support.hpp"

namespace partreg::ui {
namespace detail {
namespace {

int space_index(const AppState& state, const std::string& name) {
  const auto& spaces = require_model(state).spaces;
  for (std::size_t s = 0; s < spaces.size(); ++s)
    if (spaces[s].name == name) return static_cast<int>(s);
  state.shapes.model->space(name);  // throws the list of names
  throw UsageError("no space " + name);
}

Outcome set_latent(AppState& state, const Command& command) {
  const int s = space_index(state, command.arguments[0]);
  const int k = integer(command.arguments[1], "K");
  const double value = number(command.arguments[2], "VALUE");
  Eigen::VectorXd& values = state.shapes.std_devs[static_cast<std::size_t>(s)];
  if (k < 1 || k > values.size())
    throw UsageError("space " + command.arguments[0] + " has dimensions 1 to " +
                     std::to_string(values.size()));
  values[k - 1] = value;
  state.shapes.space = s;
  state.mode = Mode::shape_space;
  return message(command.arguments[0] + " latent " + std::to_string(k) + " = " + command.arguments[2] +
                 " sd");
}

Outcome animate(AppState& state, const Command& command) {
  require_model(state);
  if (command.arguments[0] == "off") {
    state.shapes.animated_space = state.shapes.animated_dimension = -1;
    return message("animation stopped");
  }
  if (command.arguments.size() < 2) throw UsageError("animate takes SPACE K, or off");
  const int s = space_index(state, command.arguments[0]);
  const int k = integer(command.arguments[1], "K");
  if (k < 1 || k > state.shapes.std_devs[static_cast<std::size_t>(s)].size())
    throw UsageError("space " + command.arguments[0] + " has dimensions 1 to " +
                     std::to_string(state.shapes.std_devs[static_cast<std::size_t>(s)].size()));
  state.shapes.space = s;
  state.shapes.animated_space = s;
  state.shapes.animated_dimension = k - 1;
  state.shapes.animation_phase = 0.0;
  state.mode = Mode::shape_space;
  return message("animating " + command.arguments[0] + " direction " + command.arguments[1]);
}

// A training instance by name, or by its place in the training list (from 1).
int instance_index(const AppState& state, const std::string& which) {
  require_model(state);
  const std::vector<std::string>& names = state.shapes.model->training.instances;
  const auto found = std::find(names.begin(), names.end(), which);
  if (found != names.end()) return static_cast<int>(found - names.begin());
  std::size_t used = 0;
  int index = 0;
  try {
    index = std::stoi(which, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == which.size() && index >= 1 && index <= static_cast<int>(names.size())) return index - 1;
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  throw UsageError("no training instance '" + which + "' (instances: " + known + "; or 1 to " +
                   std::to_string(names.size()) + ")");
}

Outcome show_instance(AppState& state, const Command& command) {
  require_model(state);
  const std::string& which = command.arguments[0];
  const int index = which == "none" ? -1 : instance_index(state, which);
  state.shapes.shown_instance = index;
  state.mode = Mode::shape_space;
  place_instance_beside(state);
  refit_keeping_orientation(state);
  if (index < 0) return message("no training instance shown");
  return message("showing training instance " + state.shapes.model->training.instances[index] +
                 " beside the sliders' shape");
}

// The sliders of a space set to where a training instance lies in it (latent over standard deviation).
Outcome instance_latent(AppState& state, const Command& command) {
  const int index = instance_index(state, command.arguments[0]);
  const int s =
      command.option("space").empty() ? state.shapes.space : space_index(state, command.option("space"));
  const core::ShapeSpace& space = state.shapes.model->spaces[static_cast<std::size_t>(s)];
  Eigen::VectorXd& values = state.shapes.std_devs[static_cast<std::size_t>(s)];
  for (int k = 0; k < space.dimensions(); ++k) {
    const double sd = std::sqrt(space.variances[k]);
    values[k] = sd > 0.0 ? space.training_latents(index, k) / sd : 0.0;  // a flat direction stays at 0
  }
  if (state.shapes.animated_space == s) state.shapes.animated_space = state.shapes.animated_dimension = -1;
  state.shapes.space = s;
  state.mode = Mode::shape_space;
  return message(space.name + " sliders at training instance " +
                 state.shapes.model->training.instances[static_cast<std::size_t>(index)]);
}

Outcome reset_latents(AppState& state, const Command& command) {
  require_model(state);
  for (std::size_t s = 0; s < state.shapes.std_devs.size(); ++s)
    if (command.arguments.empty() || static_cast<int>(s) == space_index(state, command.arguments[0]))
      state.shapes.std_devs[s].setZero();
  return message("sliders reset");
}

Outcome sample_latents(AppState& state, const Command& command) {
  require_model(state);
  std::mt19937_64 generator(static_cast<std::uint64_t>(integer(command.arguments[0], "SEED")));
  std::normal_distribution<double> normal(0.0, 1.0);
  for (double& value : state.shapes.std_devs[static_cast<std::size_t>(state.shapes.space)])
    value = normal(generator);
  state.mode = Mode::shape_space;
  return message("sampled the sliders of " + state.shapes.model->spaces[state.shapes.space].name);
}

// The train verb's options: where the model goes, and every training setting.
std::vector<std::string> train_options() {
  std::vector<std::string> names{"out"};
  for (const core::TrainingOption& option : core::training_options()) names.push_back(option.name);
  return names;
}

}  // namespace

std::vector<Verb> shape_verbs() {
  return {
      {"space",
       1,
       1,
       {},
       "holistic | PART",
       [](AppState& s, const Command& c) {
         s.shapes.space = space_index(s, c.arguments[0]);
         s.mode = Mode::shape_space;
         return message("space " + c.arguments[0]);
       }},
      {"set_latent", 3, 3, {}, "SPACE K VALUE  (K from 1; VALUE in standard deviations)", set_latent},
      {"reset_latents", 0, 1, {}, "[SPACE]", reset_latents},
      {"sample_latents",
       1,
       1,
       {},
       "SEED  (every slider of the current space drawn from N(0, 1))",
       sample_latents},
      {"animate", 1, 2, {}, "SPACE K | off  (slider K sweeps -2..+2 sd, 4 s a cycle)", animate},
      {"show_instance",
       1,
       1,
       {},
       "NAME | INDEX | none  (a training instance drawn beside the sliders' shape; INDEX from 1)",
       show_instance},
      {"instance_latent",
       1,
       1,
       {"space"},
       "NAME | INDEX [space=SPACE]  (the sliders set to that training instance's latent)",
       instance_latent},
      {"train",
       1,
       1,
       train_options(),
       "DATASET [out=MODEL.prm] [NAME=VALUE ...]  (every training setting, as partreg train's flags; the "
       "labelled mesh becomes the canonical)",
       [](AppState& s, const Command& c) {
         const TrainingJob job = prepare_training(s, c);
         return apply_training(s, job, job.run());
       }},
  };
}

}  // namespace detail

TrainingJob prepare_training(const AppState& state, const Command& command) {
  TrainingJob job = prepare_training_job(state, command.arguments.at(0), command.option("out", "model.prm"));
  for (const auto& [name, value] : command.options)
    if (name != "out") core::training_option(name).set(job.settings, value);
  return job;
}

Outcome apply_training(AppState& state, const TrainingJob& job, const std::string& summary) {
  detail::load_model(state, job.model_path);
  return detail::message(summary);
}

void advance_animation(AppState& state, double seconds) {
  ShapeDocument& shapes = state.shapes;
  if (!shapes.loaded() || shapes.animated_space < 0) return;
  shapes.animation_phase += seconds * 2.0 * M_PI / 4.0;
  shapes.std_devs[static_cast<std::size_t>(shapes.animated_space)][shapes.animated_dimension] =
      2.0 * std::sin(shapes.animation_phase);
}

}  // namespace partreg::ui
