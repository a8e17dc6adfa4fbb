#pragma once
/// \file
/// Everything the desktop app shows and edits, as plain data: the labelling document (a canonical mesh and
/// its part labels, with undo), the shape-space document (a model and slider values), the registration
/// document (an observation and the stepped result), the camera and the status line. Only execute()
/// (executor.hpp) changes it; panels and scripts read it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "partreg/core/options/enum_names.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/core/space/category_model.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/ui/live_deformation.hpp"
#include "partreg/ui/view.hpp"

namespace partreg::ui {

/// What the viewport shows.
enum class Mode { labelling, shape_space, registration };
}  // namespace partreg::ui

template <>
struct partreg::core::EnumNames<partreg::ui::Mode> {
  using E = partreg::ui::Mode;
  static constexpr const char* what = "mode";
  static constexpr std::array<std::pair<E, const char*>, 3> table{
      {{E::labelling, "labelling"}, {E::shape_space, "shape"}, {E::registration, "registration"}}};
};

namespace partreg::ui {

/// A canonical mesh being labelled (data units), one label per face.
/// Faces sharing an edge with each face, as a flat list (CSR): neighbours of f are
/// neighbours[start[f] .. start[f + 1]).
struct FaceAdjacency {
  std::vector<int> start, neighbours;
};

struct LabelDocument {
  std::string mesh_path;
  core::Mesh mesh;
  io::PartLabels labels;
  int current_part = -1;          ///< part that paint, fill and selections assign (-1: none chosen)
  double brush_radius_px = 12.0;  ///< default paint radius (pixels at the picked depth)
  bool dirty = false;             ///< changed since loaded or saved
  std::vector<io::PartLabels> undo_stack, redo_stack;
  /// Built on the first brush stroke or fill and kept while the mesh is (the mesh never changes after load).
  std::shared_ptr<const FaceAdjacency> adjacency;

  bool loaded() const { return mesh.faces.rows() > 0; }
};

/// A category model and the shape-space sliders.
struct ShapeDocument {
  std::string model_path;
  std::shared_ptr<const core::CategoryModel> model;
  int space = 0;                          ///< index into model->spaces; 0 = holistic
  std::vector<Eigen::VectorXd> std_devs;  ///< per space, one slider value per dimension (standard deviations)
  std::shared_ptr<LiveDeformation> deformation;
  int animated_space = -1;       ///< the space whose slider `animated_dimension` sweeps by itself (-1: none)
  int animated_dimension = -1;   ///< 0-based
  double animation_phase = 0.0;  ///< radians; the slider shows 2 sin(phase), a full sweep every 4 s
  int shown_instance = -1;       ///< training instance drawn beside the sliders' shape (-1: none)
  /// Added to the shown instance to put it beside the sliders' shape (normalised units). Fixed when it is
  /// chosen or a named view is taken (place_instance_beside), so orbiting turns about both shapes.
  Eigen::Vector3d instance_offset = Eigen::Vector3d::Zero();

  bool loaded() const { return model != nullptr; }
  /// The latent of space `s` (slider values times the square roots of the variances).
  Eigen::VectorXd latent(int s) const;
};

/// An observation and the registration stepped through.
struct RegistrationDocument {
  std::string observed_path;
  core::Points observed;  ///< data units, observed frame
  /// Where the camera was (observed frame, data units): from the views.json that `partreg views` writes
  /// beside the file, or the register command's viewpoint= option. Registration then counts only the
  /// canonical points facing it.
  std::optional<Eigen::Vector3d> viewpoint;
  core::RegistrationSettings
      settings;  ///< what the result was registered with (variant, objective; saved with it)
  std::optional<core::RegistrationResult> result;
  int step = -1;  ///< index into result->history (-1: before the first step)
  /// Frames attached to the canonical (canonical data frame; `partreg register --frames` files), drawn where
  /// the registration carries them at its last step.
  std::vector<core::Frame> frames;
};

/// A job running off the UI thread, as the panels show it (the window copies it in once a frame).
struct JobProgress {
  bool running = false;
  double fraction = 0.0;  ///< share done, in [0, 1]
  std::string line;       ///< the job's last progress line
};

struct AppState {
  Viewport viewport;
  OrbitView view;
  Mode mode = Mode::labelling;
  LabelDocument labelling;
  ShapeDocument shapes;
  RegistrationDocument registration;
  JobProgress training;  ///< a `train` from the panels running in the window (scripts train synchronously)
  JobProgress registering;  ///< a `register` from the panels running in the window (spaces fitted so far)
  std::string status;    ///< the last command's message
  bool status_is_error = false;
  bool quit_requested = false;
  bool show_panels = true;
};

/// The canonical mesh deformed by the sliders (normalised units; empty when no model or no mesh).
core::Mesh shape_space_mesh(const AppState& state);

/// The training instance `state.shapes.shown_instance`, drawn beside the sliders' shape: its holistic fit
/// (canonical mesh moved by G(V, C) W_i, or canonical points by G(C, C) W_i without a mesh), moved by
/// `state.shapes.instance_offset`. Normalised units.
struct InstanceBeside {
  std::string name;
  core::Mesh mesh;               ///< no faces for a model without a mesh: then `points`
  core::Points points;           ///< the fitted canonical points (without a mesh)
  Eigen::VectorXi part;          ///< part per mesh vertex, or per point
  Eigen::Vector3d offset;        ///< what was added to put it beside the sliders' shape (instance_offset)
  Eigen::Vector3d label_anchor;  ///< just above its top, in the middle: where its name is written
};
/// The shown instance, or nothing when none is shown (or no model is loaded).
std::optional<InstanceBeside> instance_beside(const AppState& state);

/// Sets `state.shapes.instance_offset` for the current view: along the view's horizontal (to the right) by
/// 1.2 times the sliders' shape's width there, which leaves a gap between the two.
void place_instance_beside(AppState& state);

/// The canonical points as the registration had them after history step `state.registration.step`
/// (observed frame, data units), with their parts; rows a part space has not reached yet stay at the last
/// holistic step. Empty without a result.
core::Points registration_points(const AppState& state, Eigen::VectorXi* part = nullptr);

/// The box the current mode's geometry spans (for the named views); a unit box when there is nothing.
void mode_bounds(AppState& state, Eigen::Vector3d& low, Eigen::Vector3d& high);

}  // namespace partreg::ui
