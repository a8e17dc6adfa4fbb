#include "partreg/render/figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "partreg/core/errors.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/render/text.hpp"

namespace partreg::render {
namespace {

constexpr int kGap = 8;  // pixels between panels and around labels

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

int widest(const std::vector<std::string>& labels, int scale) {
  int width = 0;
  for (const std::string& label : labels) width = std::max(width, text_width(label, scale));
  return width;
}

// The model's canonical (mesh when there is one, else points) moved by `result`, coloured by part.
Scene deformed_canonical(const core::CategoryModel& model, const core::RegistrationResult& result) {
  Scene scene;
  if (model.canonical_mesh.faces.rows() > 0) {
    MeshItem item;
    item.mesh = core::deform_mesh(model, result);
    if (model.mesh_vertex_part.size() == item.mesh.vertices.rows())
      item.vertex_colors = part_colors(model.mesh_vertex_part);
    scene.meshes.push_back(item);
  } else {
    PointSet points;
    points.positions = core::deform_points(model, result, model.normalization.undo(model.canonical));
    points.colors = part_colors(model.canonical_part);
    scene.point_sets.push_back(points);
  }
  return scene;
}

Scene shifted(Scene scene, const Eigen::Vector3d& offset) {
  for (PointSet& set : scene.point_sets) set.positions.rowwise() += offset.transpose();
  for (MeshItem& item : scene.meshes) item.mesh.vertices.rowwise() += offset.transpose();
  for (LineSet& set : scene.line_sets) {
    set.starts.rowwise() += offset.transpose();
    set.ends.rowwise() += offset.transpose();
  }
  return scene;
}

// Extent of a box along a unit direction.
double extent_along(const Bounds& box, const Eigen::Vector3d& direction) {
  return (box.max - box.min).cwiseAbs().dot(direction.cwiseAbs());
}

// A registration result that applies given latents of the model's spaces with the identity pose: the
// shape-space walk reuses the deformation of registered results.
core::RegistrationResult walk_result(const core::CategoryModel& model, const std::string& space,
                                     const Eigen::VectorXd& latent) {
  core::RegistrationResult result;
  result.variant = space == "holistic" ? core::Variant::holistic : core::Variant::partwise;
  for (const core::ShapeSpace& each : model.spaces) {
    if ((space == "holistic") != (each.name == "holistic")) continue;
    core::SpaceFit fit;
    fit.space = each.name;
    fit.latent = each.name == space ? latent : Eigen::VectorXd::Zero(each.dimensions());
    result.fits.push_back(fit);
  }
  return result;
}

}  // namespace

Image render_grid(const Grid& grid, const FigureSettings& settings,
                  const core::ProgressListener& progress) {
  const int columns = std::max(grid.columns, 1);
  const int rows = (static_cast<int>(grid.panels.size()) + columns - 1) / columns;
  const int scale = settings.text_scale;
  const int left = grid.row_labels.empty() ? 0 : widest(grid.row_labels, scale) + 2 * kGap;
  const int top = grid.column_labels.empty() ? 0 : text_line_height(scale) + kGap;
  const Rgba8 paper =
      settings.background == Background::white ? Rgba8{255, 255, 255, 255} : Rgba8{255, 255, 255, 0};
  const long long width = left + static_cast<long long>(columns) * settings.panel_width + (columns - 1) * kGap;
  const long long height = top + static_cast<long long>(rows) * settings.panel_height + (rows - 1) * kGap;
  // The whole canvas is allocated at once: a clear refusal beats std::bad_alloc.
  constexpr long long kMaxCanvasPixels = 256LL << 20;
  if (width > 65535 || height > 65535 || width * height > kMaxCanvasPixels)
    throw UsageError("a figure of " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels is too large (at most 256 megapixels, 65535 a side): choose a smaller --size");
  Image canvas(static_cast<int>(width), static_cast<int>(height), paper);

  RenderSettings render_settings;
  render_settings.width = settings.panel_width;
  render_settings.height = settings.panel_height;
  render_settings.antialiasing = settings.antialiasing;
  render_settings.background = settings.background;
  HeadlessRenderer renderer(render_settings);
  Scene all;  // every panel's geometry together, for the shared camera
  for (const Panel& panel : grid.panels)
    all.point_sets.push_back({panel.scene.all_points(), {}, Color::Zero(), 0.0});
  const core::Points shared_points = all.all_points();
  const double aspect = static_cast<double>(settings.panel_width) / settings.panel_height;
  core::ProgressCounter rendered(grid.panels.size(), progress);
  for (std::size_t i = 0; i < grid.panels.size(); ++i) {
    const Panel& panel = grid.panels[i];
    const Camera camera =
        fit_camera(settings.shared_camera ? shared_points : panel.scene.all_points(), settings.view, aspect,
                   /*margin=*/1.05, settings.fov_y_deg);
    const Image image = renderer.render(panel.scene, camera);
    const int x = left + static_cast<int>(i) % columns * (settings.panel_width + kGap);
    const int y = top + static_cast<int>(i) / columns * (settings.panel_height + kGap);
    blit(canvas, image, x, y);
    if (!panel.title.empty()) draw_text(canvas, x + kGap, y + kGap, panel.title, scale);
    rendered.step(panel.title);
  }
  for (std::size_t r = 0; r < grid.row_labels.size() && static_cast<int>(r) < rows; ++r)
    draw_text(canvas, kGap,
              top + static_cast<int>(r) * (settings.panel_height + kGap) + settings.panel_height / 2 -
                  text_line_height(scale) / 2,
              grid.row_labels[r], scale);
  for (std::size_t c = 0; c < grid.column_labels.size() && static_cast<int>(c) < columns; ++c) {
    const int centre = left + static_cast<int>(c) * (settings.panel_width + kGap) + settings.panel_width / 2;
    draw_text(canvas, centre - text_width(grid.column_labels[c], scale) / 2, kGap / 2, grid.column_labels[c],
              scale);
  }
  return canvas;
}

Panel comparison_panel(const core::CategoryModel& model, const core::Points& observed,
                       const core::RegistrationResult& result, const std::string& title, View view) {
  PointSet observed_points;
  observed_points.positions = observed;
  observed_points.color = observed_color();
  Panel panel;
  panel.title = title;
  panel.scene.point_sets.push_back(observed_points);
  // The deformed canonical goes to the right of the observation, one box width and a gap further.
  Scene deformed = deformed_canonical(model, result);
  Bounds both = panel.scene.bounds();
  both.extend(deformed.bounds());
  const Eigen::Vector3d right = named_orbit(view).camera().right();
  deformed = shifted(deformed, 1.15 * extent_along(both, right) * right);
  for (MeshItem& item : deformed.meshes) panel.scene.meshes.push_back(std::move(item));
  for (PointSet& set : deformed.point_sets) panel.scene.point_sets.push_back(std::move(set));
  return panel;
}

Panel overlay_panel(const core::CategoryModel& model, const core::Points& observed,
                    const core::RegistrationResult& result, const std::string& title) {
  Panel panel;
  panel.title = title;
  panel.scene = deformed_canonical(model, result);
  PointSet observed_points;
  observed_points.positions = observed;
  observed_points.color = observed_color();
  panel.scene.point_sets.push_back(observed_points);
  return panel;
}

Grid shape_space_grid(const core::CategoryModel& model, const std::string& space_name,
                      const std::vector<double>& std_devs) {
  const core::ShapeSpace& space = model.space(space_name);
  if (space.dimensions() == 0) throw InputError("space '" + space_name + "' has no principal directions");
  const Eigen::VectorXd explained = space.explained_fraction();
  // The deformed canonical is affine in the latent (the blend weights between parts depend only on the
  // canonical; each space's field is linear in its weights): deform at the mean and at +1 standard deviation
  // along each direction, then every cell is a combination, q + 1 deformations instead of one per cell.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(space.dimensions());
  const Scene mean = deformed_canonical(model, walk_result(model, space_name, zero));
  Grid grid;
  grid.columns = static_cast<int>(std_devs.size());
  for (double s : std_devs) grid.column_labels.push_back(s == 0.0 ? "mean" : format("%+g sd", s));
  for (int k = 0; k < space.dimensions(); ++k) {
    grid.row_labels.push_back("PC" + std::to_string(k + 1) + format(" (%.0f%%)", 100.0 * explained[k]));
    Eigen::VectorXd one_sd = zero;
    one_sd[k] = std::sqrt(std::max(space.variances[k], 0.0));
    const Scene step = deformed_canonical(model, walk_result(model, space_name, one_sd));
    for (double s : std_devs) {
      Scene cell = mean;
      for (std::size_t m = 0; m < cell.meshes.size(); ++m)
        cell.meshes[m].mesh.vertices += s * (step.meshes[m].mesh.vertices - mean.meshes[m].mesh.vertices);
      for (std::size_t p = 0; p < cell.point_sets.size(); ++p)
        cell.point_sets[p].positions += s * (step.point_sets[p].positions - mean.point_sets[p].positions);
      grid.panels.push_back({"", std::move(cell)});
    }
  }
  return grid;
}

}  // namespace partreg::render
