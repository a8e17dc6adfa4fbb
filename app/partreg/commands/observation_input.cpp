#include "partreg/commands/observation_input.hpp"

#include <iostream>
#include <sstream>

#include "partreg/commands/common.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/scene/scene_input.hpp"
#include "partreg/scene/scene_registration.hpp"

namespace partreg::app {
namespace {

void log_cut(const scene::SceneCut& cut) {
  std::cerr << "support plane: normal (" << cut.up.transpose() << ") towards the camera, " << cut.plane[3]
            << " m from it, " << cut.plane_points.rows() << " points; " << cut.outliers_removed
            << " outliers removed\n";
  for (std::size_t c = 0; c < cut.clusters.size(); ++c)
    std::cerr << "  cluster " << c << ": " << cut.clusters[c].points << " points at ("
              << cut.clusters[c].centroid.transpose() << ") m, " << cut.clusters[c].off_axis_degrees
              << " degrees off the optical axis\n";
  std::cerr << "object: " << (cut.chosen >= 0 ? "cluster " + std::to_string(cut.chosen) + ", " : "")
            << cut.choice << "; " << cut.object.points.rows() << " points\n";
}

}  // namespace

void add_observation_flags(CLI::App* command, ObservationInput& input, bool with_scene_flag) {
  CLI::Option* depth = command->add_option(
      "--depth", input.depth, "depth image: 16-bit PNG (depth_scale units per metre, 0 = none) or .npy float metres");
  CLI::Option* intrinsics = command->add_option(
      "--intrinsics", input.intrinsics, "camera intrinsics JSON (fx, fy, cx, cy, width, height, depth_scale; or Open3D's)");
  depth->needs(intrinsics);
  command->add_option("--mask", input.mask, "the object's pixels (PNG, non-zero = object) in the depth image")
      ->needs(depth);
  // A scene is the observation and the camera its viewpoint: the command line refuses the others with it.
  std::vector<CLI::Option*> scene_options = {depth};
  if (with_scene_flag) {
    CLI::Option* scene = command->add_option("--scene", input.scene, "scene cloud in the camera frame, metres (PCD, PLY, ...)");
    scene->excludes(depth);
    scene_options.push_back(scene);
  }
  for (const char* other : {"OBSERVED", "--viewpoint"})
    if (CLI::Option* given = command->get_option_no_throw(other))
      for (CLI::Option* option : scene_options) option->excludes(given);
  command->add_option("--pick", input.pick,
                      "the object: U,V (a pixel) or X,Y,Z (camera frame, m); default: the cluster nearest the "
                      "image centre above the table");
  add_scene_flags(command, input.settings);
}

scene::Pick parse_pick(const std::string& text) {
  scene::Pick pick;
  if (text.empty()) return pick;
  const std::vector<double> values = parse_numbers(text).value_or(std::vector<double>{});
  if (values.size() == 2)
    pick.pixel = Eigen::Vector2d(values[0], values[1]);
  else if (values.size() == 3)
    pick.point = Eigen::Vector3d(values[0], values[1], values[2]);
  else
    throw UsageError("--pick '" + text + "': expected U,V (a pixel) or X,Y,Z (metres)");
  return pick;
}

scene::SceneCut cut_observation(const ObservationInput& input) {
  if (!input.depth.empty() && !input.scene.empty()) throw UsageError("give --depth or a scene cloud, not both");
  if (!input.depth.empty() && input.intrinsics.empty()) throw UsageError("--depth needs --intrinsics");
  if (!input.mask.empty() && input.depth.empty()) throw UsageError("--mask goes with --depth");
  const scene::Pick pick = parse_pick(input.pick);  // a bad pick is refused before anything is read
  if (!input.mask.empty() && (pick.pixel || pick.point)) throw UsageError("--mask and --pick each choose the object: give one");
  const scene::SceneView view = input.depth.empty() ? scene::read_scene_cloud(input.scene, input.intrinsics)
                                                    : scene::read_depth_view(input.depth, input.intrinsics, input.mask);
  std::cerr << "read " << (input.depth.empty() ? input.scene : input.depth) << ": " << view.measured.points.rows()
            << " measured points\n";
  const scene::SceneCut cut = scene::cut_scene(view, pick, input.settings.segmentation);
  log_cut(cut);
  return cut;
}

nlohmann::json cut_json(const scene::SceneCut& cut) {
  nlohmann::json clusters = nlohmann::json::array();
  for (const scene::Cluster& c : cut.clusters)
    clusters.push_back({{"points", c.points},
                        {"centroid", {c.centroid.x(), c.centroid.y(), c.centroid.z()}},
                        {"off_axis_degrees", c.off_axis_degrees}});
  return {{"plane", {cut.plane[0], cut.plane[1], cut.plane[2], cut.plane[3]}},
          {"up", {cut.up.x(), cut.up.y(), cut.up.z()}},
          {"plane_points", cut.plane_points.rows()},
          {"outliers_removed", cut.outliers_removed},
          {"clusters", clusters},
          {"chosen", cut.chosen},
          {"choice", cut.choice},
          {"object_points", cut.object.points.rows()}};
}

Observed read_observed(const std::string& observed_path, const ObservationInput& input,
                       const core::RegistrationSettings& settings, std::size_t mesh_samples) {
  if (observed_path.empty() == !input.is_scene())
    throw UsageError("give OBSERVED, or a scene as --depth D --intrinsics K or --scene S (one of them)");
  Observed observed;
  if (!input.is_scene()) {
    observed.points = read_points_logged(observed_path, mesh_samples, 1);
    return observed;
  }
  if (settings.viewpoint)
    throw UsageError("--viewpoint: a depth image's or scene's viewpoint is the camera (its origin)");
  observed.cut = cut_observation(input);
  observed.points = observed.cut->object.points;
  return observed;
}

core::RegistrationResult register_observed(const core::CategoryModel& model, const Observed& observed,
                                           const core::RegistrationSettings& settings,
                                           const ObservationInput& input, const core::ProgressListener& progress) {
  if (!observed.cut) return core::register_observation(model, observed.points, settings, progress);
  core::RegistrationResult result =
      scene::register_cut(model, *observed.cut, settings, input.settings.registration, progress);
  std::cerr << "registered up axis " << scene::up_axis_angle_degrees(model, result, observed.cut->up)
            << " degrees from the table's normal (camera frame; viewpoint: the camera)\n";
  return result;
}

}  // namespace partreg::app
