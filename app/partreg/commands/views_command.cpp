// `partreg views INPUT --count 42 --out DIR`: partial views of a mesh or cloud, cast from a tessellated
// sphere.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <tuple>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/eval/views.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::app {
namespace {

struct ViewsOptions {
  int threads = 0;  // the command's thread budget
  std::string input_path;
  std::string out_path;
  int count = 42;
  std::string resolution = "160x120";
  eval::CameraSettings camera;
};

void parse_resolution(const std::string& text, eval::CameraSettings& camera) {
  std::tie(camera.width, camera.height) = parse_size(text, "--resolution");
  if (camera.width > 8192 || camera.height > 8192)
    throw UsageError("--resolution must be between 1x1 and 8192x8192");
}

eval::ViewCaster make_caster(const std::string& path) {
  if (io::is_mesh_file(path)) return eval::ViewCaster(io::read_mesh(path));
  return eval::ViewCaster(read_points_logged(path, 0, 1));
}

void run_views(ViewsOptions& options) {
  const core::ThreadBudget budget(options.threads);
  parse_resolution(options.resolution, options.camera);
  eval::check_camera(options.camera);  // before the output folder is made or the input read
  const std::vector<Eigen::Vector3d> directions = eval::sphere_directions(options.count);
  StagedFolder folder(options.out_path);  // refuses a folder holding other files before any work
  const eval::ViewCaster caster = make_caster(options.input_path);
  nlohmann::json listing = {{"input", options.input_path},
                            {"resolution", {options.camera.width, options.camera.height}},
                            {"fov_degrees", options.camera.fov_degrees},
                            {"views", nlohmann::json::array()}};
  // Many views of a large mesh or at a high resolution take seconds: a bar, each view's line a detail.
  ProgressDisplay display({"views", /*lines_are_detail=*/true, /*log_every_percent=*/10});
  const core::ProgressListener listener = display.listener();
  core::ProgressCounter progress(directions.size(), listener);
  for (std::size_t v = 0; v < directions.size(); ++v) {
    const eval::View view = caster.cast(directions[v], options.camera);
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu.ply", v);
    io::write_cloud_ply(folder.staging() / name, core::Cloud{view.points, view.normals});
    listing["views"].push_back({{"file", name},
                                {"points", view.points.rows()},
                                {"direction", {view.direction.x(), view.direction.y(), view.direction.z()}},
                                {"viewpoint", {view.viewpoint.x(), view.viewpoint.y(), view.viewpoint.z()}}});
    progress.step(std::string(name) + ": " + std::to_string(view.points.rows()) + " points");
  }
  display.finish();
  write_json_or_stdout(listing, (folder.staging() / "views.json").string(), /*log=*/false);
  folder.commit();
  std::cerr << "wrote " << directions.size() << " views and views.json (directions, viewpoints) to "
            << options.out_path << '\n';
}

}  // namespace

void add_views_command(CLI::App& app) {
  auto options = std::make_shared<ViewsOptions>();
  CLI::App* command = app.add_subcommand(
      "views", "Partial views of a mesh or cloud as a depth camera sees them from a tessellated sphere");
  add_threads_flag(command, options->threads);
  command->add_option("INPUT", options->input_path, "mesh (rays hit its surface) or cloud")->required();
  command->add_option("--out", options->out_path, "new folder: view_NNN.ply and views.json")->required();
  command->add_option("--count", options->count, "viewpoints: 12, 42, 162, ... (tessellated sphere)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  command->add_option("--resolution", options->resolution, "depth image size WxH")->capture_default_str();
  using Camera = eval::CameraSettings;
  command->add_option("--fov", options->camera.fov_degrees, "vertical field of view (degrees)")
      ->capture_default_str()
      ->check(finite_in(Camera::kMinFovDegrees, Camera::kMaxFovDegrees));
  command->callback([options] { run_views(*options); });
}

}  // namespace partreg::app
