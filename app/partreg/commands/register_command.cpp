// `partreg register MODEL OBSERVED`: deform a category model onto an observed cloud or mesh.
#include <iostream>
#include <memory>
#include <sstream>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/core/deformation.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/metrics.hpp"
#include "partreg/core/part_selection.hpp"
#include "partreg/core/registration.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/output_format.hpp"

namespace partreg::app {
namespace {

struct RegisterOptions {
  std::string model_path, observed_path, variant = "holistic", json_path, points_out, mesh_out;
  std::string frames_path, frames_out, viewpoint, direction = "observed", loss = "huber", truth_path;
  std::size_t mesh_samples = 3000;
  core::RegistrationSettings settings;
};

void write_outputs(const core::CategoryModel& model, const core::RegistrationResult& result,
                   const RegisterOptions& options) {
  if (!options.mesh_out.empty() && model.canonical_mesh.faces.rows() == 0)  // before any output is written
    throw InputError("model '" + model.category + "' has no canonical mesh (it was trained on clouds)");
  if (!options.points_out.empty()) {
    io::PointAttributes attributes;
    attributes.integers["part"] = result.part;
    io::write_cloud(options.points_out, core::Cloud{result.deformed, {}}, attributes);
    std::cerr << "wrote " << options.points_out << '\n';
  }
  if (!options.mesh_out.empty()) {
    const core::Mesh mesh = core::deform_mesh(model, result);
    io::write_mesh(options.mesh_out, mesh, &model.mesh_vertex_part);
    std::cerr << "wrote " << options.mesh_out << '\n';
  }
  if (!options.frames_out.empty()) {
    const auto frames = io::read_frames_file(options.frames_path);
    io::write_frames_file(options.frames_out, core::transfer_frames(model, result, frames));
    std::cerr << "wrote " << options.frames_out << '\n';
  }
}

// Errors against the ground-truth instance, in data units and normalised by the model's diagonal.
nlohmann::json truth_errors(const core::CategoryModel& model, const core::RegistrationResult& result,
                            const RegisterOptions& options) {
  const core::Points truth = read_points_logged(options.truth_path, 20000, 2);
  const double diagonal = model.normalization.scale;
  const double eq5 = core::closest_point_error(result.deformed, truth);
  const double chamfer = core::chamfer_distance(result.deformed, truth);
  std::cerr << core::to_string(result.variant) << " against " << options.truth_path << ": Eq. 5 error " << eq5
            << " (data units squared), " << eq5 / (diagonal * diagonal) << " normalised; Chamfer " << chamfer
            << '\n';
  return {{"file", options.truth_path},
          {"eq5", eq5},
          {"eq5_normalised", eq5 / (diagonal * diagonal)},
          {"chamfer", chamfer},
          {"chamfer_normalised", chamfer / diagonal}};
}

// Every output is checked before any work: a bad name never leaves the outputs written before it.
void check_register_outputs(const RegisterOptions& options) {
  io::check_output(options.points_out, io::OutputKind::cloud, "--points-out");
  io::check_output(options.mesh_out, io::OutputKind::mesh, "--mesh-out");
  io::check_output(options.frames_out, io::OutputKind::json, "--frames-out");
  io::check_output(options.json_path, io::OutputKind::json, "--json");
}

void run_register(RegisterOptions& options) {
  options.settings.variant = core::parse_variant(options.variant);
  options.settings.direction = core::parse_direction(options.direction);
  options.settings.loss = core::parse_loss(options.loss);
  if (!options.viewpoint.empty())
    options.settings.viewpoint = core::parse_vector3(options.viewpoint, "--viewpoint");
  if (options.settings.restarts < 1) throw UsageError("--restarts must be at least 1");
  if (options.frames_out.empty() != options.frames_path.empty())
    throw UsageError("--frames and --frames-out go together");
  if (!options.frames_path.empty())
    io::read_frames_file(options.frames_path);  // refuse bad frames before working
  check_register_outputs(options);
  const core::CategoryModel model = io::read_model(options.model_path);
  const core::Points observed = read_points_logged(options.observed_path, options.mesh_samples, 1);
  const core::RegistrationResult result = core::register_observation(model, observed, options.settings);
  for (const core::SpaceFit& fit : result.fits)
    std::cerr << "space " << fit.space << ": " << fit.iterations << " steps, cost " << fit.cost << ", "
              << fit.seconds << " s\n";
  std::cerr << core::to_string(result.variant) << ": mean closest-point distance " << result.fit.mean
            << " (data units), " << result.fit.mean_normalised << " of the diagonal; 90th percentile "
            << result.fit.p90 << "; " << result.seconds << " s\n";
  nlohmann::json report =
      io::result_json(result, {options.model_path, options.observed_path, options.direction, options.loss});
  if (!options.truth_path.empty()) report["truth"] = truth_errors(model, result, options);
  write_outputs(model, result, options);
  write_json_or_stdout(report, options.json_path);
}

}  // namespace

void add_register_command(CLI::App& app) {
  auto o = std::make_shared<RegisterOptions>();
  CLI::App* command =
      app.add_subcommand("register", "Deform a category model onto an observed cloud or mesh");
  command->add_option("MODEL", o->model_path, "model file from partreg train")->required();
  command->add_option("OBSERVED", o->observed_path, "observed cloud or mesh (data units and frame)")
      ->required();
  command->add_option("--variant", o->variant, "holistic | partwise | hol+part")->capture_default_str();
  command->add_option("--json", o->json_path, "result JSON ('-' for stdout)");
  command->add_option("--points-out", o->points_out,
                      "the deformed canonical points with their part (.ply, .pcd, .vtp, .xyz)");
  command->add_option("--mesh-out", o->mesh_out, "the deformed canonical mesh (.obj, .ply, .vtp)");
  command->add_option("--frames", o->frames_path, "frames attached to the canonical (JSON)");
  command->add_option("--frames-out", o->frames_out, "where the transferred frames go");
  command->add_option("--viewpoint", o->viewpoint,
                      "X,Y,Z camera position: only canonical points facing it count");
  command->add_option("--restarts", o->settings.restarts, "initial rotations about the up axis")
      ->capture_default_str();
  command->add_option("--direction", o->direction, "canonical | observed | symmetric")->capture_default_str();
  command->add_option("--loss", o->loss, "squared | huber | cauchy | trimmed")->capture_default_str();
  command->add_flag("--scale", o->settings.estimate_scale, "also fit a uniform scale");
  command->add_flag("--align-axes", o->settings.align_principal_axes,
                    "start from the rotations that align principal axes (for poses far off)");
  command->add_option("--truth", o->truth_path,
                      "ground-truth instance (cloud or mesh, observed frame): report Eq. 5 and Chamfer");
  command->add_option("--samples", o->mesh_samples, "points sampled from an observed mesh")
      ->capture_default_str()
      ->check(point_count_range());
  command->callback([o] { run_register(*o); });
}

}  // namespace partreg::app
