// `partreg render FILES... --out IMAGE.png`: any clouds and meshes partreg reads, drawn headlessly.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/render_common.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/output_format.hpp"
#include "partreg/render/headless.hpp"

namespace partreg::app {
namespace {

struct RenderOptions {
  std::vector<std::string> files;
  std::string out, size = "1280x960", view = "iso", color_by = "file", background = "white";
  std::string eye, target, up = "0,1,0";
  bool wireframe = false, flat = false;
  double point_radius = 0.0;
  std::string antialias = "msaa";
};

// Adds one file to the scene, coloured by its index, by part or not at all. Returns what it read (and a
// warning line after it when parts were asked for and the file has none).
std::string add_file(render::Scene& scene, const std::string& path, int index, const RenderOptions& options) {
  std::ostringstream line;
  render::Colors colors;
  Eigen::VectorXi part;
  // By part, files without parts are grey: the part palette is the file palette.
  const render::Color file_color =
      options.color_by == "file" ? render::file_color(index) : render::neutral_color();
  if (io::is_mesh_file(path)) {
    render::MeshItem item;
    io::MeshFile file = io::read_mesh_file(path);  // a .vtp or .ply file's parts come with it
    item.mesh = std::move(file.mesh);
    const auto found = file.vertex_attributes.integers.find("part");
    if (options.color_by == "part" && found != file.vertex_attributes.integers.end()) part = found->second;
    item.color = file_color;
    item.shading = options.flat ? render::Shading::flat : render::Shading::smooth;
    item.wireframe = options.wireframe;
    line << "read " << path << ": " << item.mesh.vertices.rows() << " vertices, " << item.mesh.faces.rows()
         << " triangles";
    if (part.size() > 0) item.vertex_colors = render::part_colors(part);
    scene.meshes.push_back(std::move(item));
  } else {
    io::CloudFile file = io::read_cloud_file(path);
    render::PointSet points;
    points.positions = std::move(file.cloud.points);
    points.color = file_color;
    points.radius = options.point_radius;
    const auto found = file.attributes.integers.find("part");
    if (options.color_by == "part" && found != file.attributes.integers.end()) part = found->second;
    line << "read " << path << ": " << points.positions.rows() << " points";
    if (part.size() > 0) points.colors = render::part_colors(part);
    scene.point_sets.push_back(std::move(points));
  }
  if (options.color_by == "part" && part.size() == 0)
    line << "\npartreg: warning: " << path << " has no part labels; drawn in grey";
  return line.str();
}

render::Camera camera_of(const RenderOptions& options, const render::Scene& scene, double aspect) {
  render::Camera camera =
      render::fit_camera(scene.all_points(), core::parse_enum<render::View>(options.view), aspect);
  if (options.eye.empty() != options.target.empty()) throw UsageError("--eye and --target go together");
  if (!options.eye.empty()) {
    camera.eye = parse_vector3(options.eye, "--eye");
    camera.target = parse_vector3(options.target, "--target");
    camera.up = parse_vector3(options.up, "--up");
    camera.view_matrix();  // refuses a degenerate camera before any work
  }
  return camera;
}

void run_render(const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.color_by != "part" && options.color_by != "file" && options.color_by != "none")
    throw UsageError("--color-by takes part, file or none, not '" + options.color_by + "'");
  render::RenderSettings settings;
  std::tie(settings.width, settings.height) = parse_size(options.size, "--size");
  settings.antialiasing = core::parse_enum<render::Antialiasing>(options.antialias);
  settings.background = core::parse_enum<render::Background>(options.background);
  core::parse_enum<render::View>(options.view);
  check_output_folder(options.out);
  render::Scene scene;
  // Large meshes take a second or more to read and draw: a step per file read, one for the drawing.
  ProgressDisplay display({"steps", /*lines_are_detail=*/false, /*log_every_percent=*/0});
  const core::ProgressListener listener = display.listener();
  core::ProgressCounter progress(options.files.size() + 1, listener);
  for (std::size_t i = 0; i < options.files.size(); ++i)
    progress.step(add_file(scene, options.files[i], static_cast<int>(i), options));
  const render::Camera camera =
      camera_of(options, scene, static_cast<double>(settings.width) / settings.height);
  if (verbosity() == Verbosity::verbose) {
    const Eigen::IOFormat triple(4, Eigen::DontAlignCols, ", ", ", ", "", "", "(", ")");
    std::ostringstream line;
    line << "camera at " << camera.eye.transpose().format(triple) << ", looking at "
         << camera.target.transpose().format(triple) << ", up " << camera.up.transpose().format(triple);
    display.print(line.str());
  }
  render::HeadlessRenderer renderer(settings);
  const render::Image image = renderer.render(scene, camera);
  progress.step("drew " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " pixels");
  display.finish();
  render::write_png(options.out, image);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << "wrote " << options.out << " (" << settings.width << "x" << settings.height << ", " << seconds
            << " s)\n";
}

}  // namespace

void check_output_folder(const std::string& path) { io::check_output(path, io::OutputKind::image, "--out"); }

void add_render_commands(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand("render", "Draw clouds and meshes into a PNG, headlessly (OSMesa)");
  command->add_option("FILES", o->files, "clouds (PCD, PLY, VTP, XYZ) and meshes (OBJ, PLY, VTP, STL, ...)");
  command->add_option("--out", o->out, "the PNG to write")->required();
  command->add_option("--size", o->size, "image size WIDTHxHEIGHT (pixels)")->capture_default_str();
  command->add_option("--view", o->view, "iso | front | side | top (+Y up)")->capture_default_str();
  command->add_option("--color-by", o->color_by, "part (unlabelled files grey) | file | none")
      ->capture_default_str();
  command->add_option("--background", o->background, "white | transparent")->capture_default_str();
  command->add_option("--eye", o->eye, "X,Y,Z camera position (with --target; overrides --view)")
      ->check(vector3_check(false));
  command->add_option("--target", o->target, "X,Y,Z point the camera looks at")->check(vector3_check(false));
  command->add_option("--up", o->up, "X,Y,Z up direction of the camera")
      ->capture_default_str()
      ->check(vector3_check(true));
  command->add_option("--point-radius", o->point_radius, "splat radius in data units (0: automatic)")
      ->capture_default_str()
      ->check(finite_in(0.0, 1e12));
  command->add_option("--antialias", o->antialias, "msaa (4 samples) | edge (fast) | none")
      ->capture_default_str();
  command->add_flag("--wireframe", o->wireframe, "draw mesh edges over the surfaces");
  command->add_flag("--flat", o->flat, "flat shading of meshes (one normal per triangle)");
  command->callback([o] { run_render(*o); });
  add_figure_command(app);
}

}  // namespace partreg::app
