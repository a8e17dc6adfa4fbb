// The verbs that read and write files: a model, a mesh to label or a cloud to register, frames, labels.
#include <string>

#include "partreg/core/errors.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/views_file.hpp"
#include "partreg/ui/labelling.hpp"
#include "verb_support.hpp"

namespace partreg::ui::detail {

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

namespace {

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

}  // namespace

std::vector<Verb> file_verbs() {
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
  };
}

}  // namespace partreg::ui::detail
