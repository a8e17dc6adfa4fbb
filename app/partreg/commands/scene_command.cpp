// `partreg scene MESH... --out DIR`: objects on a table as a structured-light depth camera sees them, with
// each object's true pose, mask and mesh in the camera frame (test scenes for `segment` and `register --depth`).
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/scene/camera_io.hpp"
#include "partreg/scene/depth_render.hpp"
#include "partreg/scene/table_scene.hpp"

namespace partreg::app {
namespace {

struct SceneOptions {
  std::vector<std::string> meshes;
  std::string out_path, sizes = "0.15", up = "0,1,0", resolution = "640x480";
  double focal = 615.0;
  scene::TableLayout layout;
  scene::SensorSettings sensor;
  double depth_scale = 1000.0;
};

std::vector<double> list_of(const std::string& text, const std::string& option) {
  const std::optional<std::vector<double>> values = parse_numbers(text);
  if (!values) throw UsageError(option + ": '" + text + "' is not a list of numbers");
  return *values;
}

std::vector<scene::TableObject> read_objects(const SceneOptions& options) {
  std::vector<double> sizes = list_of(options.sizes, "--size");
  if (sizes.size() != 1 && sizes.size() != options.meshes.size())
    throw UsageError("--size: give one size or one per mesh");
  const std::vector<double> up = list_of(options.up, "--up");
  if (up.size() != 3 || Eigen::Vector3d(up[0], up[1], up[2]).norm() == 0)
    throw UsageError("--up: expected X,Y,Z of non-zero length");
  std::vector<scene::TableObject> objects;
  for (std::size_t i = 0; i < options.meshes.size(); ++i) {
    scene::TableObject object{io::read_mesh(options.meshes[i]), {up[0], up[1], up[2]}, sizes[sizes.size() > 1 ? i : 0]};
    if (!(object.size > 0 && object.size < 10)) throw UsageError("--size: sizes are metres in (0, 10)");
    objects.push_back(std::move(object));
  }
  return objects;
}

nlohmann::json matrix(const Eigen::Matrix4d& T) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

void run_scene(const SceneOptions& options) {
  scene::Intrinsics k;
  std::tie(k.width, k.height) = parse_size(options.resolution, "--resolution");
  k.fx = k.fy = options.focal;
  k.cx = (k.width - 1) / 2.0, k.cy = (k.height - 1) / 2.0;
  k.depth_scale = options.depth_scale;
  if (!(options.focal > 0 && options.focal < 1e5) || k.width > 8192 || k.height > 8192 || !(options.depth_scale > 0))
    throw UsageError("--focal, --resolution (up to 8192x8192) and --depth-scale must be positive");
  const scene::TableScene table = scene::lay_out_table(read_objects(options), options.layout);
  std::vector<core::Mesh> meshes;
  for (const scene::PlacedObject& object : table.objects) meshes.push_back(object.mesh);
  meshes.push_back(table.table);
  const scene::RenderedDepth rendered = scene::render_depth(meshes, k, options.sensor);
  StagedFolder folder(options.out_path);
  const std::filesystem::path dir = folder.staging();
  scene::write_depth_png(dir / "depth.png", rendered.depth, k.depth_scale);
  scene::write_depth_png(dir / "depth_true.png", rendered.clean, k.depth_scale);
  write_json_or_stdout(scene::intrinsics_json(k), (dir / "intrinsics.json").string(), false);
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t i = 0; i < table.objects.size(); ++i) {
    const std::string n = std::to_string(i);
    const scene::PixelMask mask = scene::surface_mask(rendered, static_cast<int>(i));
    scene::write_mask_png(dir / ("mask_" + n + ".png"), mask);
    io::write_mesh(dir / ("object_" + n + ".ply"), table.objects[i].mesh);
    int visible = 0, measured = 0;
    for (std::size_t p = 0; p < mask.selected.size(); ++p)
      visible += mask.selected[p], measured += mask.selected[p] && rendered.depth.metres[p] > 0;
    objects.push_back({{"mesh", options.meshes[i]}, {"T_camera_object", matrix(table.objects[i].T_camera_object)},
                       {"scale", table.objects[i].scale}, {"mask", "mask_" + n + ".png"},
                       {"truth", "object_" + n + ".ply"}, {"pixels", visible}, {"measured_pixels", measured}});
    std::cerr << "object " << i << " (" << options.meshes[i] << "): " << visible << " pixels, " << measured
              << " measured\n";
  }
  const nlohmann::json report = {
      {"depth", "depth.png"}, {"true_depth", "depth_true.png"}, {"intrinsics", "intrinsics.json"},
      {"objects", objects}, {"table_plane", {table.plane[0], table.plane[1], table.plane[2], table.plane[3]}},
      {"T_world_camera", matrix(table.T_world_camera)},
      {"sensor", {{"noise", options.sensor.noise}, {"baseline", options.sensor.baseline},
                  {"disparity_step", options.sensor.disparity_step}, {"grazing_degrees", options.sensor.grazing_degrees},
                  {"edge_jump", options.sensor.edge_jump}, {"projector_shadows", options.sensor.projector_shadows},
                  {"seed", options.sensor.seed}}}};
  write_json_or_stdout(report, (dir / "scene.json").string(), false);
  folder.commit();
  std::cerr << "wrote " << options.out_path << " (depth.png, intrinsics.json, scene.json, masks, true meshes)\n";
}

}  // namespace

void add_scene_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* command = app.add_subcommand("scene", "Render objects on a table as a depth camera sees them");
  command->add_option("MESH", o->meshes, "object meshes; the first stands in the middle")->required();
  command->add_option("--out", o->out_path, "output folder (new or empty)")->required();
  command->add_option("--size", o->sizes, "each object's bounding-box diagonal (m): one, or one per mesh")
      ->capture_default_str();
  command->add_option("--up", o->up, "the meshes' up axis in their own frame")->capture_default_str();
  command->add_option("--resolution", o->resolution, "image size WxH (pixels)")->capture_default_str();
  command->add_option("--focal", o->focal, "fx = fy (pixels); the principal point is the image centre")
      ->capture_default_str();
  command->add_option("--depth-scale", o->depth_scale, "PNG units per metre (1000: millimetres)")
      ->capture_default_str();
  command->add_option("--distance", o->layout.distance, "camera to the middle object's foot (m)")->capture_default_str();
  command->add_option("--elevation", o->layout.elevation_degrees, "camera above the table (degrees)")
      ->capture_default_str();
  command->add_option("--spacing", o->layout.spacing, "between neighbouring objects (m)")->capture_default_str();
  command->add_option("--table-width", o->layout.table_width, "the table top across the image (m)")
      ->capture_default_str();
  command->add_option("--table-depth", o->layout.table_depth, "the table top away from the camera (m)")
      ->capture_default_str();
  command->add_option("--noise", o->sensor.noise, "depth noise's standard deviation at 1 m (m; grows as depth^2)")
      ->capture_default_str();
  command->add_option("--baseline", o->sensor.baseline, "projector offset along +x (m)")->capture_default_str();
  command->add_option("--disparity-step", o->sensor.disparity_step, "disparity quantum (pixels; 0 = none)")
      ->capture_default_str();
  command->add_option("--grazing", o->sensor.grazing_degrees, "surfaces seen beyond this angle are lost (degrees)")
      ->capture_default_str();
  command->add_option("--edge-jump", o->sensor.edge_jump, "pixels beside a depth jump above this are lost (m)")
      ->capture_default_str();
  command->add_flag_callback("--no-shadows", [o] { o->sensor.projector_shadows = false; },
                             "keep the pixels the projector cannot light");
  command->add_option("--seed", o->sensor.seed, "noise and yaw seed")->capture_default_str();
  command->callback([o] {
    o->layout.seed = o->sensor.seed;
    run_scene(*o);
  });
}

}  // namespace partreg::app
