#include "partreg/ui/scene_builder.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/render/palette.hpp"

namespace partreg::ui {
namespace {

render::Color label_color(const io::PartLabels& labels, int part) {
  if (part < 0 || part >= static_cast<int>(labels.colors.size())) return render::neutral_color();
  const auto& c = labels.colors[static_cast<std::size_t>(part)];
  return render::Color(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f);
}

// One colour per face needs unshared vertices: three per face, flat shaded.
render::MeshItem labelled_mesh(const LabelDocument& document) {
  const core::Mesh& mesh = document.mesh;
  render::MeshItem item;
  const Eigen::Index faces = mesh.faces.rows();
  item.mesh.vertices.resize(3 * faces, 3);
  item.mesh.faces.resize(faces, 3);
  item.vertex_colors.resize(3 * faces, 3);
  for (Eigen::Index f = 0; f < faces; ++f) {
    const render::Color color = label_color(document.labels, document.labels.labels[f]);
    for (int c = 0; c < 3; ++c) {
      item.mesh.vertices.row(3 * f + c) = mesh.vertices.row(mesh.faces(f, c));
      item.mesh.faces(f, c) = static_cast<int>(3 * f + c);
      item.vertex_colors.row(3 * f + c) = color.transpose();
    }
  }
  item.shading = render::Shading::flat;
  return item;
}

// Part colours washed towards grey: a training instance reads as a reference, not as the shape being edited.
render::Colors muted_part_colors(const Eigen::VectorXi& part) {
  const render::Colors colors = render::part_colors(part);
  return 0.45f * colors + render::Colors::Constant(colors.rows(), 3, 0.55f * 0.75f);
}

void add_instance_beside(const AppState& state, render::Scene& scene) {
  std::optional<InstanceBeside> shown = instance_beside(state);
  if (!shown) return;
  if (shown->mesh.faces.rows() > 0) {
    render::MeshItem item;
    item.mesh = std::move(shown->mesh);
    if (shown->part.size() == item.mesh.vertices.rows()) item.vertex_colors = muted_part_colors(shown->part);
    scene.meshes.push_back(std::move(item));
    return;
  }
  render::PointSet points;
  points.positions = std::move(shown->points);
  points.colors = muted_part_colors(shown->part);
  scene.point_sets.push_back(std::move(points));
}

void add_shape_space(AppState& state, render::Scene& scene) {
  const core::CategoryModel& model = *state.shapes.model;
  core::Mesh mesh = shape_space_mesh(state);
  if (mesh.faces.rows() > 0) {
    render::MeshItem item;
    item.mesh = std::move(mesh);
    if (model.mesh_vertex_part.size() == item.mesh.vertices.rows())
      item.vertex_colors = render::part_colors(model.mesh_vertex_part);
    scene.meshes.push_back(std::move(item));
  } else {
    // A model without a mesh: its canonical points, deformed by the holistic space.
    render::PointSet points;
    points.positions = model.holistic().deformed(state.shapes.latent(0));
    points.colors = render::part_colors(model.canonical_part);
    scene.point_sets.push_back(std::move(points));
  }
  // After the sliders' shape, which so keeps its place in the renderer's per-mesh buffers.
  add_instance_beside(state, scene);
}

// The canonical's frames (grasps) where the registration carries them: RGB triads sized to the shape. The
// transfer uses the final result, so they show at the last step only.
void add_frames(const AppState& state, const core::Points& points, render::Scene& scene) {
  const RegistrationDocument& registration = state.registration;
  if (registration.frames.empty() || !registration.result || !state.shapes.loaded()) return;
  if (registration.step != static_cast<int>(registration.result->history.size()) - 1) return;
  const double length = 0.15 * (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  for (const core::Frame& frame :
       core::transfer_frames(*state.shapes.model, *registration.result, registration.frames))
    scene.line_sets.push_back(render::make_triad(frame.position, frame.rotation, length));
}

void add_registration(const AppState& state, render::Scene& scene) {
  const core::Points& observed = state.registration.observed;
  if (observed.rows() > 0) {
    render::PointSet cloud;
    cloud.positions = observed;
    cloud.color = render::observed_color();
    scene.point_sets.push_back(std::move(cloud));
  }
  Eigen::VectorXi part;
  const core::Points all_points = registration_points(state, &part);
  // Rows a part-wise registration has not reached yet are NaN: leave them out.
  std::vector<int> reached;
  for (Eigen::Index i = 0; i < all_points.rows(); ++i)
    if (all_points.row(i).allFinite()) reached.push_back(static_cast<int>(i));
  if (reached.empty()) return;
  core::Points points(static_cast<Eigen::Index>(reached.size()), 3);
  Eigen::VectorXi reached_part(points.rows());
  for (std::size_t k = 0; k < reached.size(); ++k) {
    points.row(static_cast<Eigen::Index>(k)) = all_points.row(reached[k]);
    reached_part[static_cast<Eigen::Index>(k)] = part.size() > reached[k] ? part[reached[k]] : 0;
  }
  render::PointSet canonical;
  canonical.positions = points;
  canonical.colors = render::part_colors(reached_part);
  scene.point_sets.push_back(canonical);
  add_frames(state, points, scene);
  if (observed.rows() == 0) return;
  // Correspondences of every 4th canonical point: enough to see the pull without hiding the shapes.
  const core::KdTree observed_tree(observed);
  std::vector<int> rows;
  for (Eigen::Index i = 0; i < points.rows(); i += 4) rows.push_back(static_cast<int>(i));
  core::Points starts(static_cast<Eigen::Index>(rows.size()), 3), ends(starts.rows(), 3);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    starts.row(static_cast<Eigen::Index>(k)) = points.row(rows[k]);
    ends.row(static_cast<Eigen::Index>(k)) =
        observed.row(observed_tree.nearest(points.row(rows[k]).transpose()).first);
  }
  scene.line_sets.push_back(render::make_correspondences(starts, ends, render::Color(0.3f, 0.3f, 0.3f)));
}

}  // namespace

render::Scene build_scene(AppState& state) {
  render::Scene scene;
  switch (state.mode) {
    case Mode::labelling:
      if (state.labelling.loaded()) scene.meshes.push_back(labelled_mesh(state.labelling));
      break;
    case Mode::shape_space:
      if (state.shapes.loaded()) add_shape_space(state, scene);
      break;
    case Mode::registration:
      add_registration(state, scene);
      break;
  }
  return scene;
}

render::Camera render_camera(const AppState& state) {
  const CameraFrame frame = camera_frame(state.view, state.viewport);
  render::Camera camera;
  camera.eye = frame.eye;
  camera.target = frame.target;
  camera.up = frame.up;
  camera.fov_y_deg = frame.fov_y_deg;
  return camera;
}

}  // namespace partreg::ui
