#include "partreg/ui/executor.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/result_file.hpp"
#include "partreg/io/views_file.hpp"
#include "partreg/ui/labelling.hpp"
#include "partreg/ui/tools.hpp"

namespace partreg::ui {
namespace {

using Handler = std::function<Outcome(AppState&, const Command&)>;

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

void fit_view(AppState& state, const std::string& name = "iso") {
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

// --- files

Outcome load_model(AppState& state, const std::string& path) {
  auto model = std::make_shared<core::CategoryModel>(io::read_model(path));
  ShapeDocument shapes;
  shapes.model_path = path;
  shapes.model = model;
  for (const core::ShapeSpace& space : model->spaces)
    shapes.std_devs.push_back(Eigen::VectorXd::Zero(space.dimensions()));
  shapes.deformation = std::make_shared<LiveDeformation>(model.get());
  state.shapes = std::move(shapes);
  state.registration.result.reset();
  state.registration.step = -1;
  state.mode = Mode::shape_space;
  fit_view(state);
  return message("loaded the model " + path + " (" + model->category + ", " +
                 std::to_string(model->spaces.size()) + " spaces)");
}

Outcome load_observed(AppState& state, const std::string& path, int mesh_points) {
  if (mesh_points < 10) throw UsageError("points= must be at least 10");
  core::Cloud cloud = io::read_as_cloud(path, static_cast<std::size_t>(mesh_points), 1);
  state.registration.observed_path = path;
  state.registration.observed = std::move(cloud.points);
  state.registration.viewpoint = io::viewpoint_from_listing(path);  // views.json beside it, when there is one
  state.registration.result.reset();
  state.registration.step = -1;
  state.mode = Mode::registration;
  fit_view(state);
  return message("loaded " + std::to_string(state.registration.observed.rows()) + " observed points from " +
                 path + (state.registration.viewpoint ? " (viewpoint from views.json)" : ""));
}

Outcome load(AppState& state, const Command& command) {
  const std::string& path = command.arguments[0];
  if (io::lower_extension(path) == ".prm") return load_model(state, path);
  if (io::is_mesh_file(path)) {
    LabelDocument document = load_label_document(path);
    state.labelling = std::move(document);
    state.mode = Mode::labelling;
    fit_view(state);
    return message("loaded " + path + " (" + std::to_string(state.labelling.mesh.faces.rows()) +
                   " faces) for labelling");
  }
  return load_observed(state, path, 5000);
}

// --- labelling

Hit pick(const AppState& state, const Command& command) {
  const double x = number(command.arguments[0], "X"), y = number(command.arguments[1], "Y");
  if (!state.labelling.loaded()) throw UsageError("no mesh is loaded to label (load MESH first)");
  const std::optional<Hit> hit = intersect(state.labelling.mesh, pixel_ray(state.view, state.viewport, x, y));
  if (!hit)
    throw InputError("no surface under the pixel (" + command.arguments[0] + ", " + command.arguments[1] +
                     ")");
  return *hit;
}

Outcome paint(AppState& state, const Command& command) {
  const Hit hit = pick(state, command);
  const double radius_px =
      number(command.option("radius", std::to_string(state.labelling.brush_radius_px)), "radius");
  if (radius_px <= 0.0) throw UsageError("radius must be positive");
  const double radius = radius_px * pixel_size_at(state.view, state.viewport, hit.distance);
  state.mode = Mode::labelling;
  const int changed = paint_faces(state.labelling, hit.face, hit.point, radius);
  return message("painted " + std::to_string(changed) + " faces");
}

Outcome fill(AppState& state, const Command& command) {
  const Hit hit = pick(state, command);
  state.mode = Mode::labelling;
  return message("filled " + std::to_string(fill_faces(state.labelling, hit.face)) + " faces");
}

template <typename Parse>
Handler selector(Parse parse) {
  return [parse](AppState& state, const Command& command) {
    const int changed = select_faces(state.labelling, parse(command.arguments[0]));
    return message("selected " + std::to_string(changed) + " faces");
  };
}

// --- shape spaces

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

// --- registration

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

// --- camera

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

// The register verb's options: every registration setting but the variant, which is its argument.
std::vector<std::string> register_options() {
  std::vector<std::string> names;
  for (const core::RegistrationOption& option : core::registration_options())
    if (option.name != "variant") names.push_back(option.name);
  return names;
}

// The train verb's options: where the model goes, and every training setting.
std::vector<std::string> train_options() {
  std::vector<std::string> names{"out"};
  for (const core::TrainingOption& option : core::training_options()) names.push_back(option.name);
  return names;
}

std::vector<Verb> make_verbs() {
  return {
      {"load", 1, 1, {}, "PATH  (a model .prm, a mesh to label, or a cloud to register)", load},
      {"load_observed",
       1,
       1,
       {"points"},
       "PATH [points=N]  (a cloud or a mesh sampled to N points)",
       [](AppState& s, const Command& c) {
         return load_observed(s, c.arguments[0], integer(c.option("points", "5000"), "points"));
       }},
      {"load_labels",
       1,
       1,
       {},
       "PATH  (a labels file for the loaded mesh)",
       [](AppState& s, const Command& c) {
         load_labels(s.labelling, c.arguments[0]);
         s.mode = Mode::labelling;
         return message("loaded the labels " + c.arguments[0]);
       }},
      {"save_labels",
       1,
       1,
       {},
       "PATH",
       [](AppState& s, const Command& c) {
         save_labels(s.labelling, c.arguments[0]);
         return message("saved " + c.arguments[0]);
       }},
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
      {"create_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         create_part(s.labelling, c.arguments[0]);
         return message("created part " + c.arguments[0]);
       }},
      {"select_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         s.labelling.current_part = find_part(s.labelling, c.arguments[0]);
         return message("painting " + c.arguments[0]);
       }},
      {"rename_part",
       2,
       2,
       {},
       "NAME NEW_NAME",
       [](AppState& s, const Command& c) {
         rename_part(s.labelling, c.arguments[0], c.arguments[1]);
         return message("renamed " + c.arguments[0] + " to " + c.arguments[1]);
       }},
      {"recolor_part",
       4,
       4,
       {},
       "NAME R G B  (0-255)",
       [](AppState& s, const Command& c) {
         recolor_part(s.labelling, c.arguments[0], integer(c.arguments[1], "R"), integer(c.arguments[2], "G"),
                      integer(c.arguments[3], "B"));
         return message("");
       }},
      {"merge_part",
       2,
       2,
       {},
       "FROM INTO",
       [](AppState& s, const Command& c) {
         merge_parts(s.labelling, c.arguments[0], c.arguments[1]);
         return message("merged " + c.arguments[0] + " into " + c.arguments[1]);
       }},
      {"delete_part",
       1,
       1,
       {},
       "NAME",
       [](AppState& s, const Command& c) {
         delete_part(s.labelling, c.arguments[0]);
         return message("deleted " + c.arguments[0]);
       }},
      {"paint", 2, 2, {"radius"}, "X Y [radius=PIXELS]  (pixels from the top-left corner)", paint},
      {"fill", 2, 2, {}, "X Y", fill},
      {"select_box", 1, 1, {}, "X0,Y0,Z0,X1,Y1,Z1", selector(core::parse_box)},
      {"select_plane", 1, 1, {}, "PX,PY,PZ,NX,NY,NZ", selector(core::parse_plane)},
      {"select_sphere", 1, 1, {}, "CX,CY,CZ,R", selector(core::parse_sphere)},
      {"brush",
       1,
       1,
       {},
       "RADIUS_PIXELS",
       [](AppState& s, const Command& c) {
         const double radius = number(c.arguments[0], "RADIUS_PIXELS");
         if (radius <= 0.0) throw UsageError("the brush radius must be positive");
         s.labelling.brush_radius_px = radius;
         return message("");
       }},
      {"undo",
       0,
       0,
       {},
       "",
       [](AppState& s, const Command&) { return message(undo(s.labelling) ? "undone" : "nothing to undo"); }},
      {"redo",
       0,
       0,
       {},
       "",
       [](AppState& s, const Command&) { return message(redo(s.labelling) ? "redone" : "nothing to redo"); }},
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
      {"register", 1, 1, register_options(),
       "VARIANT [NAME=VALUE ...]  (every registration setting, as partreg register's flags)",
       run_registration},
      {"save_result",
       1,
       1,
       {},
       "FOLDER  (result.json, points.ply, mesh.ply, frames.json, as `partreg register` writes)",
       save_result},
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
      {"load_frames",
       1,
       1,
       {},
       "PATH  (frames on the canonical, e.g. grasps: drawn at the registration's end)",
       [](AppState& s, const Command& c) {
         s.registration.frames = io::read_frames_file(c.arguments[0]);
         return message("loaded " + std::to_string(s.registration.frames.size()) + " frames from " +
                        c.arguments[0]);
       }},
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

}  // namespace

const std::vector<Verb>& verbs() {
  static const std::vector<Verb> table = make_verbs();
  return table;
}

const Verb* find_verb(const std::string& name) {
  for (const Verb& verb : verbs())
    if (verb.name == name) return &verb;
  return nullptr;
}

Outcome execute(AppState& state, const Command& command) {
  const Verb* verb = find_verb(command.verb);
  if (!verb) throw UsageError("unknown command '" + command.verb + "'");
  Outcome outcome = verb->run(state, command);
  if (!outcome.message.empty() || state.status_is_error) state.status = outcome.message;
  state.status_is_error = false;
  return outcome;
}

bool execute_reporting(AppState& state, const Command& command, Outcome* outcome) {
  try {
    Outcome result = execute(state, command);
    if (outcome) *outcome = std::move(result);
    return true;
  } catch (const InputError& error) {
    state.status = error.what();
  } catch (const UsageError& error) {
    state.status = error.what();
  }
  state.status_is_error = true;
  return false;
}

RegistrationJob prepare_registration(AppState& state, const Command& command) {
  require_model(state);
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
  return message(text.str());
}

TrainingJob prepare_training(const AppState& state, const Command& command) {
  TrainingJob job = prepare_training_job(state, command.arguments.at(0), command.option("out", "model.prm"));
  for (const auto& [name, value] : command.options)
    if (name != "out") core::training_option(name).set(job.settings, value);
  return job;
}

Outcome apply_training(AppState& state, const TrainingJob& job, const std::string& summary) {
  load_model(state, job.model_path);
  return message(summary);
}

void advance_animation(AppState& state, double seconds) {
  ShapeDocument& shapes = state.shapes;
  if (!shapes.loaded() || shapes.animated_space < 0) return;
  shapes.animation_phase += seconds * 2.0 * M_PI / 4.0;
  shapes.std_devs[static_cast<std::size_t>(shapes.animated_space)][shapes.animated_dimension] =
      2.0 * std::sin(shapes.animation_phase);
}

}  // namespace partreg::ui
