// `partreg grasps sample` and `partreg grasps check`: parallel-jaw grasps on a mesh (eval/gripper.hpp), and
// the grasp transfer `register --grasps` runs (grasp_transfer.hpp).
#include <iomanip>
#include <iostream>
#include <memory>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/grasp_transfer.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/eval/gripper.hpp"
#include "partreg/io/geometry_io.hpp"
#include "partreg/io/grasps_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/output_format.hpp"

namespace partreg::app {
namespace {

// The surface grasps are sampled on: a model's canonical mesh (category data frame, with its vertices'
// parts) or a mesh file.
struct GraspSurface {
  core::Mesh mesh;
  std::vector<std::string> vertex_part;  // empty without parts
  double diagonal = 0.0;                 // a relative gripper's scale: the model's, or the mesh's own
};

double diagonal_of(const core::Mesh& mesh) {
  return (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
}

GraspSurface read_surface(const std::string& path) {
  GraspSurface surface;
  if (std::filesystem::path(path).extension() != ".prm") {  // the model files `partreg train` writes
    surface.mesh = io::read_mesh(path);
    surface.diagonal = diagonal_of(surface.mesh);
    return surface;
  }
  const core::CategoryModel model = io::read_model(path);
  if (model.canonical_mesh.faces.rows() == 0)
    throw InputError("model '" + model.category + "' has no canonical mesh to sample grasps on");
  surface.mesh = model.canonical_mesh;
  surface.mesh.vertices = model.normalization.undo(model.canonical_mesh.vertices);
  surface.diagonal = model.normalization.scale;
  if (model.has_parts() && model.mesh_vertex_part.size() == model.canonical_mesh.vertices.rows())
    for (Eigen::Index v = 0; v < surface.mesh.vertices.rows(); ++v)
      surface.vertex_part.push_back(model.part_names[static_cast<std::size_t>(model.mesh_vertex_part[v])]);
  return surface;
}

struct SampleOptions {
  std::string surface_path, gripper_path, out, part;
  int count = 50;
  std::uint64_t seed = 1;
};

void run_sample(const SampleOptions& options) {
  io::check_output(options.out, io::OutputKind::json, "--out");
  const core::Gripper relative = io::read_gripper_file(options.gripper_path);
  const GraspSurface surface = read_surface(options.surface_path);
  const core::Gripper gripper = relative.in_units(surface.diagonal);
  std::vector<bool> allowed;
  if (!options.part.empty()) {
    if (surface.vertex_part.empty())
      throw UsageError("--part " + options.part + ": " + options.surface_path + " has no parts");
    // A face is on the part when all its vertices are: grasps keep off the seams.
    for (Eigen::Index f = 0; f < surface.mesh.faces.rows(); ++f) {
      bool on_part = true;
      for (int k = 0; k < 3; ++k)
        on_part = on_part && surface.vertex_part[static_cast<std::size_t>(surface.mesh.faces(f, k))] == options.part;
      allowed.push_back(on_part);
    }
    if (std::find(allowed.begin(), allowed.end(), true) == allowed.end())
      throw UsageError("--part " + options.part + ": no such part in " + options.surface_path);
  }
  std::vector<core::Grasp> grasps = eval::sample_grasps(surface.mesh, gripper, options.count, options.seed, allowed);
  if (!surface.vertex_part.empty()) {
    // A grasp belongs to the part of the mesh vertex nearest its contacts' middle on the surface.
    const core::KdTree vertices(surface.mesh.vertices);
    for (core::Grasp& grasp : grasps)
      grasp.part = surface.vertex_part[static_cast<std::size_t>(vertices.nearest(grasp.contact(0)).first)];
  }
  std::cerr << "sampled " << grasps.size() << " grasps that hold (asked for " << options.count << ")\n";
  if (grasps.empty()) throw InputError("no grasp that the gripper holds was found on " + options.surface_path);
  io::write_grasps_file(options.out, grasps, gripper);
  std::cerr << "wrote " << options.out << '\n';
}

struct CheckOptions {
  std::string mesh_path, grasps_path, gripper_path, json_path;
};

void run_check(const CheckOptions& options) {
  io::check_output(options.json_path, io::OutputKind::json, "--json");
  GraspRequest request = read_grasp_request(options.grasps_path, options.gripper_path);
  if (!io::is_mesh_file(options.mesh_path))
    throw UsageError(options.mesh_path + ": the gripper test needs a surface (a mesh file), not a cloud");
  const eval::MeshRays object(io::read_mesh(options.mesh_path));
  request.gripper = request.gripper.in_units(diagonal_of(object.mesh()));
  nlohmann::json rows = nlohmann::json::array();
  int held = 0;
  std::cout << std::left << std::setw(16) << "grasp" << std::setw(7) << "holds" << std::setw(9) << "width"
            << std::setw(16) << "angles (deg)" << "reason\n";
  for (const core::Grasp& grasp : request.grasps) {
    const eval::GraspCheck check = eval::check_grasp(object, grasp, request.gripper);
    held += check.holds ? 1 : 0;
    std::cout << std::left << std::setw(16) << grasp.name << std::setw(7) << (check.holds ? "yes" : "no")
              << std::setw(9) << std::setprecision(4) << check.width << std::setw(16)
              << (std::to_string(int(std::round(check.angles_degrees[0]))) + " / " +
                  std::to_string(int(std::round(check.angles_degrees[1]))))
              << check.reason << '\n';
    rows.push_back({{"name", grasp.name},
                    {"part", grasp.part},
                    {"holds", check.holds},
                    {"reason", check.reason},
                    {"width", check.width},
                    {"angles_degrees", {check.angles_degrees[0], check.angles_degrees[1]}},
                    {"touched", {check.touched[0], check.touched[1]}},
                    {"collides", check.collides},
                    {"quality", eval::grasp_quality(check, request.gripper)}});
  }
  std::cerr << held << " of " << request.grasps.size() << " grasps hold on " << options.mesh_path << '\n';
  write_json_or_stdout({{"mesh", options.mesh_path}, {"held", held}, {"grasps", rows}}, options.json_path);
}

}  // namespace

GraspRequest read_grasp_request(const std::string& grasps_path, const std::string& gripper_path) {
  io::GraspsFile file = io::read_grasps_file(grasps_path);
  GraspRequest request{std::move(file.grasps), core::Gripper{}};
  if (!gripper_path.empty())
    request.gripper = io::read_gripper_file(gripper_path);
  else if (file.gripper)
    request.gripper = *file.gripper;
  else
    throw InputError(grasps_path + " names no gripper: give one with --gripper");
  return request;
}

void write_carried_grasps(const core::CategoryModel& model, const core::RegistrationResult& result,
                          const core::Points& observed, const GraspRequest& request, const std::string& path) {
  if (model.canonical_mesh.faces.rows() == 0)
    throw InputError("model '" + model.category + "' has no canonical mesh to re-seat grasps on");
  const core::Gripper gripper = request.gripper.in_units(model.observed_diagonal());
  const std::vector<core::Grasp> carried = core::transfer_grasps(model, result, request.grasps, gripper);
  const eval::MeshRays believed(core::deform_mesh(model, result));
  const std::vector<core::Grasp> seated = eval::reseat_grasps(believed, &observed, carried, gripper);
  const auto held = std::count_if(seated.begin(), seated.end(), [](const core::Grasp& g) { return g.quality > 0.0; });
  std::cerr << "grasps: " << held << " of " << seated.size()
            << " hold on the registered object (re-seated, ranked by quality)\n";
  io::write_grasps_file(path, seated, gripper);
  std::cerr << "wrote " << path << '\n';
}

void add_grasps_command(CLI::App& app) {
  CLI::App* grasps = app.add_subcommand("grasps", "Parallel-jaw grasps: sample them on a mesh, check them");
  grasps->require_subcommand(1);

  auto sample = std::make_shared<SampleOptions>();
  CLI::App* s = grasps->add_subcommand("sample", "Antipodal grasps a gripper holds, on a model's canonical mesh or a mesh");
  s->add_option("SURFACE", sample->surface_path, "model file (its canonical mesh) or mesh file")->required();
  s->add_option("--gripper", sample->gripper_path, "gripper file (JSON, docs/grasps.md)")->required();
  s->add_option("--out", sample->out, "grasps file to write (.json)")->required();
  s->add_option("--count", sample->count, "grasps wanted")->capture_default_str()->check(CLI::Range(1, 100000));
  s->add_option("--part", sample->part, "only on this part of a labelled model");
  s->add_option("--seed", sample->seed, "random seed")->capture_default_str();
  s->callback([sample] { run_sample(*sample); });

  auto check = std::make_shared<CheckOptions>();
  CLI::App* c = grasps->add_subcommand("check", "Whether a gripper holds a mesh with each grasp (ray-cast fingers)");
  c->add_option("MESH", check->mesh_path, "the object (mesh file, in the grasps' frame)")->required();
  c->add_option("GRASPS", check->grasps_path, "grasps file (JSON)")->required();
  c->add_option("--gripper", check->gripper_path, "gripper file (default: the grasps file's own)");
  c->add_option("--json", check->json_path, "per-grasp results ('-' for stdout)");
  c->callback([check] { run_check(*check); });
}

}  // namespace partreg::app
