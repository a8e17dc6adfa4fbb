#include "partreg/ui/app_state.hpp"

#include <cmath>

#include "partreg/core/errors.hpp"

namespace partreg::ui {
namespace {

void extend(const core::Points& points, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) continue;
    low = low.cwiseMin(points.row(i).transpose());
    high = high.cwiseMax(points.row(i).transpose());
  }
}

}  // namespace

Eigen::VectorXd ShapeDocument::latent(int s) const {
  const core::ShapeSpace& space = model->spaces.at(static_cast<std::size_t>(s));
  return std_devs.at(static_cast<std::size_t>(s)).cwiseProduct(space.variances.cwiseSqrt());
}

core::Mesh shape_space_mesh(const AppState& state) {
  const ShapeDocument& shapes = state.shapes;
  if (!shapes.loaded() || shapes.model->canonical_mesh.faces.rows() == 0) return {};
  std::vector<Eigen::VectorXd> latents;
  for (int s = 0; s < static_cast<int>(shapes.model->spaces.size()); ++s) latents.push_back(shapes.latent(s));
  core::Mesh mesh;
  mesh.faces = shapes.model->canonical_mesh.faces;
  mesh.vertices = shapes.deformation->deform(latents, shapes.space == 0);
  return mesh;
}

namespace {

// What the sliders show: the deformed mesh's vertices, or the holistic space's points without a mesh.
core::Points sliders_shape(const AppState& state) {
  const core::Mesh mesh = shape_space_mesh(state);
  if (mesh.faces.rows() > 0) return mesh.vertices;
  return state.shapes.model->holistic().deformed(state.shapes.latent(0));
}

Eigen::Vector3d view_right(const CameraFrame& frame) {
  return frame.up.cross(frame.eye - frame.target).normalized();
}

}  // namespace

std::optional<InstanceBeside> instance_beside(const AppState& state) {
  const ShapeDocument& shapes = state.shapes;
  if (!shapes.loaded() || shapes.shown_instance < 0) return std::nullopt;
  const core::CategoryModel& model = *shapes.model;
  InstanceBeside shown;
  shown.name = model.training.instances.at(static_cast<std::size_t>(shapes.shown_instance));
  const core::Points& fitted = shapes.deformation->fitted_instance(shapes.shown_instance);
  shown.offset = shapes.instance_offset;
  const core::Points moved = fitted.rowwise() + shown.offset.transpose();
  if (model.canonical_mesh.faces.rows() > 0) {
    shown.mesh.vertices = moved;
    shown.mesh.faces = model.canonical_mesh.faces;
    shown.part = model.mesh_vertex_part;
  } else {
    shown.points = moved;
    shown.part = model.canonical_part;
  }
  const CameraFrame frame = camera_frame(state.view, state.viewport);
  const Eigen::Vector3d up = (frame.eye - frame.target).cross(view_right(frame)).normalized();
  const Eigen::VectorXd height = moved * up;
  const Eigen::Vector3d centre = moved.colwise().mean().transpose();
  shown.label_anchor = centre + (height.maxCoeff() - centre.dot(up)) * up;
  return shown;
}

void place_instance_beside(AppState& state) {
  if (!state.shapes.loaded()) return;
  const Eigen::Vector3d right = view_right(camera_frame(state.view, state.viewport));
  const Eigen::VectorXd along = sliders_shape(state) * right;
  state.shapes.instance_offset = 1.2 * (along.maxCoeff() - along.minCoeff()) * right;
}

core::Points registration_points(const AppState& state, Eigen::VectorXi* part) {
  const RegistrationDocument& registration = state.registration;
  if (!registration.result || !state.shapes.loaded()) return {};
  const core::CategoryModel& model = *state.shapes.model;
  const auto& history = registration.result->history;
  if (part) *part = model.canonical_part;
  // The last step shows the result itself: the refinement beyond the shape space follows the last step.
  if (registration.step >= static_cast<int>(history.size()) - 1) return registration.result->deformed;
  core::Points points = core::Points::Constant(model.canonical.rows(), 3, std::nan(""));
  // Replays the history up to the current step: each step moves the rows of its space.
  for (int i = 0; i <= registration.step && i < static_cast<int>(history.size()); ++i) {
    const core::HistoryStep& step = history[static_cast<std::size_t>(i)];
    const core::ShapeSpace& space = model.space(step.space);
    const core::Points in_data = model.normalization.undo(space.deformed(step.latent));
    const Eigen::Matrix3d rotation = step.T_observed_canonical.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = step.T_observed_canonical.topRightCorner<3, 1>();
    for (Eigen::Index r = 0; r < in_data.rows(); ++r) {
      const int row = space.point_indices.empty() ? static_cast<int>(r) : space.point_indices[r];
      points.row(row) = (rotation * in_data.row(r).transpose() + translation).transpose();
    }
  }
  if (registration.step < 0) {
    // Before the first step: the canonical where the registration starts (the data frame).
    points = model.normalization.undo(model.canonical);
  }
  return points;
}

void mode_bounds(AppState& state, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  high = -low;
  switch (state.mode) {
    case Mode::labelling:
      extend(state.labelling.mesh.vertices, low, high);
      break;
    case Mode::shape_space:
      if (state.shapes.loaded()) {
        const core::Mesh mesh = shape_space_mesh(state);
        extend(mesh.faces.rows() > 0 ? mesh.vertices : state.shapes.model->canonical, low, high);
        if (const std::optional<InstanceBeside> shown = instance_beside(state))
          extend(shown->mesh.faces.rows() > 0 ? shown->mesh.vertices : shown->points, low, high);
      }
      break;
    case Mode::registration:
      extend(state.registration.observed, low, high);
      extend(registration_points(state), low, high);
      break;
  }
  if (!(low.array() <= high.array()).all()) {
    low = Eigen::Vector3d::Constant(-0.5);
    high = Eigen::Vector3d::Constant(0.5);
  }
}

}  // namespace partreg::ui
