// `partreg register MODEL OBSERVED`: deform a category model onto an observed cloud or mesh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/grasp_transfer.hpp"
#include "partreg/commands/observation_input.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/kdtree.hpp"
#include "partreg/core/geometry/truth_errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/deformation.hpp"
#include "partreg/core/registration/registration.hpp"
#include "partreg/eval/baselines.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/frames_file.hpp"
#include "partreg/io/mesh_io.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/output_format.hpp"
#include "partreg/io/registration_outputs.hpp"
#include "partreg/io/result_file.hpp"
#include "partreg/io/warm_start_file.hpp"

namespace partreg::app {
namespace {

struct RegisterOptions {
  std::string model_path, observed_path, json_path, points_out, mesh_out;
  std::string frames_path, frames_out, truth_path, init;
  std::string grasps_path, grasps_out, gripper_path;
  std::size_t mesh_samples = 3000;
  int threads = 0;
  core::RegistrationSettings settings;
  ObservationInput scene_input;  // --depth/--scene: the object is cut out of a scene (observation_input.hpp)
  std::string fail_on;  ///< empty, or the verdict at which the command exits 3
};

void write_outputs(const core::CategoryModel& model, const core::RegistrationResult& result,
                   const core::Points& observed, const std::vector<core::Frame>& frames,
                   const RegisterOptions& options) {
  if (!options.mesh_out.empty() && model.canonical_mesh.faces.rows() == 0)  // before any output is written
    throw InputError("model '" + model.category + "' has no canonical mesh (it was trained on clouds)");
  if (!options.points_out.empty()) {
    io::write_registered_points(options.points_out, model, result, observed);
    std::cerr << "wrote " << options.points_out << '\n';
  }
  if (!options.mesh_out.empty()) {
    io::write_registered_mesh(options.mesh_out, model, result, observed);
    std::cerr << "wrote " << options.mesh_out << '\n';
  }
  if (!options.frames_out.empty()) {
    io::write_frames_file(options.frames_out, core::transfer_frames(model, result, frames));
    std::cerr << "wrote " << options.frames_out << '\n';
  }
}

// partreg's holistic pose: the result's holistic fit where it has one, else a holistic registration's.
Eigen::Matrix4d holistic_pose(const core::CategoryModel& model, const core::Points& observed,
                              const core::RegistrationResult& result, core::RegistrationSettings settings) {
  for (const core::SpaceFit& fit : result.fits)
    if (fit.space == model.holistic().name) return fit.T_observed_canonical;
  settings.variant = core::Variant::holistic;
  return core::register_observation(model, observed, settings).fits.front().T_observed_canonical;
}

// The baselines of the evaluation on this observation and truth (eval/baselines.hpp), with the model's
// training fits as the oracle's templates (the training instances themselves are not in the model).
nlohmann::json baseline_errors(const core::CategoryModel& model, const core::Points& observed,
                               const core::RegistrationResult& result, const RegisterOptions& options,
                               const core::KdTree& truth, double diagonal, double partreg_figure) {
  const eval::BaselineObservation seen{&observed, &truth, diagonal, nullptr,
                                       holistic_pose(model, observed, result, options.settings)};
  const core::InitialisationSettings init = core::with_model_defaults(options.settings, model).initialisation;
  const std::vector<eval::BaselineScore> scores = eval::score_baselines(
      model, eval::model_templates(model), seen, eval::start_rotations(init.restarts, *init.up));
  nlohmann::json json = nlohmann::json::object();
  std::cerr << "baselines on the same observation, symmetric RMS of the diagonal:";
  for (const eval::BaselineScore& score : scores) {
    nlohmann::json entry = io::truth_errors_json(score.errors);
    entry["shape"] = score.shape;
    json[core::enum_name(score.baseline)] = entry;
    std::cerr << ' ' << core::enum_name(score.baseline) << ' ' << score.errors.symmetric_rms_per_diagonal;
  }
  const double oracle = scores.front().errors.symmetric_rms_per_diagonal;
  json["ratio_to_oracle_template"] = partreg_figure / oracle;
  std::cerr << "; " << core::enum_name(result.variant) << " / oracle-template " << partreg_figure / oracle
            << " (templates: the model's training fits)\n";
  return json;
}

// Errors against the ground-truth instance, normalised by its own diagonal (truth_errors.hpp), and the
// baselines on the same observation.
nlohmann::json truth_errors(const core::CategoryModel& model, const core::Points& observed,
                            const core::RegistrationResult& result, const RegisterOptions& options) {
  // A folder of part meshes is a truth with its own parts: each part is also scored against its own.
  const bool has_parts = std::filesystem::is_directory(options.truth_path);
  if (has_parts && model.part_names.empty())
    throw InputError("--truth " + options.truth_path +
                     " is a folder of part meshes but the model has no parts");
  const core::TrainingInstance labelled =
      has_parts ? io::read_part_folder(options.truth_path, model.part_names, {core::kTruthSamples, 2})
                : core::TrainingInstance{};
  const core::Points truth =
      has_parts ? labelled.points : read_points_logged(options.truth_path, core::kTruthSamples, 2);
  const double diagonal = core::truth_diagonal(truth);
  const core::KdTree truth_tree(truth);
  const core::TruthErrors errors =
      core::measure_against_truth(result.deformed, result.part, model.part_names, truth_tree, diagonal,
                                  nullptr, has_parts ? &labelled.part : nullptr);
  if (has_parts)
    std::cerr << "read " << options.truth_path << ": " << truth.rows() << " points sampled from its "
              << model.part_names.size() << " part meshes\n";
  std::cerr << core::enum_name(result.variant) << " against " << options.truth_path << ": symmetric RMS "
            << errors.symmetric_rms_per_diagonal << " of its diagonal; Eq. 5 " << errors.eq5
            << " (data units squared), " << errors.eq5_per_diagonal2 << " of the diagonal squared; Chamfer "
            << errors.chamfer << '\n';
  if (errors.own_part_rms_mean_per_diagonal) {
    std::cerr << "each part against its own: mean " << *errors.own_part_rms_mean_per_diagonal
              << " of the diagonal (";
    for (const auto& [part, figure] : errors.own_part_rms_per_diagonal)
      std::cerr << (part == errors.own_part_rms_per_diagonal.begin()->first ? "" : ", ") << part << ' '
                << figure;
    std::cerr << ")\n";
  }
  nlohmann::json json = io::truth_errors_json(errors);
  json["file"] = options.truth_path;
  json["baselines"] = baseline_errors(model, observed, result, options, truth_tree, diagonal,
                                      errors.symmetric_rms_per_diagonal);
  return json;
}

// The verdict closes the command's output (its last line on stderr), after every output was written; exit 3
// when it is at least as bad as --fail-on asks.
void report_verdict(const core::RegistrationResult& result, const RegisterOptions& options) {
  const core::TrustFigures& f = result.figures;
  for (const std::string& reason : result.assessment.reasons) std::cerr << "  " << reason << '\n';
  const std::string verdict = core::enum_name(result.assessment.verdict);
  std::cerr << "verdict: " << verdict << " (" << 100.0 * f.inlier_share << "% of the observed points within "
            << 100.0 * options.settings.verdict.inlier_distance << "% of the diagonal of the model, RMS "
            << 100.0 * f.observed_rms << "%; latent " << f.latent_distance << " sd; pose ambiguity "
            << f.pose_ambiguity << "; largest seam gap " << 100.0 * f.seam_gap_max << "%; stretch "
            << f.mesh_stretch << "x; scale " << f.scale;
  if (f.free_space_violation) std::cerr << "; in free space " << 100.0 * *f.free_space_violation << "%";
  std::cerr << ")\n";
  if (!options.fail_on.empty() && result.assessment.verdict >= core::parse_enum<core::Verdict>(options.fail_on))
    throw RejectedResult("the verdict is " + verdict + " (--fail-on " + options.fail_on + ")");
}

// Every output is checked before any work: a bad name never leaves the outputs written before it.
void check_register_outputs(const RegisterOptions& options) {
  io::check_output(options.points_out, io::OutputKind::cloud, "--points-out");
  io::check_output(options.mesh_out, io::OutputKind::mesh, "--mesh-out");
  io::check_output(options.frames_out, io::OutputKind::json, "--frames-out");
  io::check_output(options.json_path, io::OutputKind::json, "--json");
  io::check_output(options.grasps_out, io::OutputKind::json, "--grasps-out");
  io::check_distinct_outputs({{"--points-out", options.points_out},
                              {"--mesh-out", options.mesh_out},
                              {"--frames-out", options.frames_out},
                              {"--grasps-out", options.grasps_out},
                              {"--json", options.json_path}});
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The registration, from --init's warm start when one is given.
core::RegistrationResult register_with_start(const core::CategoryModel& model, const core::Points& observed,
                                             const RegisterOptions& options,
                                             const std::optional<core::WarmStart>& start,
                                             const core::ProgressListener& listener) {
  if (!start) return core::register_observation(model, observed, options.settings, listener);
  const core::RegistrationResult result =
      core::register_observation(model, observed, options.settings, *start, listener);
  std::cerr << "start: " << core::enum_name(result.start) << " (warm score " << result.warm_score
            << ", warm-limit " << options.settings.initialisation.warm_limit << ")\n";
  return result;
}

void run_register(const RegisterOptions& options) {
  const Clock::time_point started = Clock::now();
  if (options.frames_out.empty() != options.frames_path.empty())
    throw UsageError("--frames and --frames-out go together");
  if (options.grasps_out.empty() != options.grasps_path.empty())
    throw UsageError("--grasps and --grasps-out go together");
  check_register_outputs(options);
  const core::ThreadBudget budget(options.threads);
  // Frames are read before the work, so bad frames are refused before anything runs.
  const std::vector<core::Frame> frames =
      options.frames_path.empty() ? std::vector<core::Frame>{} : io::read_frames_file(options.frames_path);
  const std::optional<GraspRequest> grasps =
      options.grasps_path.empty() ? std::nullopt
                                  : std::optional(read_grasp_request(options.grasps_path, options.gripper_path));
  const std::optional<core::WarmStart> start =
      options.init.empty() ? std::nullopt : std::optional(io::read_warm_start(options.init));
  const core::CategoryModel model = io::read_model(options.model_path);
  const Observed seen =
      read_observed(options.observed_path, options.scene_input, options.settings, options.mesh_samples);
  if (seen.cut && start) throw UsageError("--init starts a plain observation, not a depth image or scene");
  const core::Points& observed = seen.points;
  const double read_seconds = seconds_since(started);
  ProgressDisplay progress({"spaces fitted", /*lines_are_detail=*/true, /*log_every_percent=*/0});
  const core::RegistrationResult result =
      seen.cut ? register_observed(model, seen, options.settings, options.scene_input, progress.listener())
               : register_with_start(model, observed, options, start, progress.listener());
  progress.finish();
  for (const core::SpaceFit& fit : result.fits) {
    std::cerr << "space " << fit.space << ": " << fit.iterations << " steps ("
              << core::enum_name(fit.stop_reason) << "), cost " << fit.cost << ", " << fit.seconds << " s\n";
    // A runner-up scoring close to the winner says the pose is ambiguous (docs/registration.md).
    if (fit.hypotheses > 1)
      std::cerr << "  pose: best of " << fit.hypotheses << " hypotheses, score " << fit.score
                << (std::isfinite(fit.runner_up_score)
                        ? "; runner-up " + std::to_string(fit.runner_up_score) + " (" +
                              std::to_string(fit.runner_up_score / fit.score) + "x)"
                        : std::string("; no runner-up"))
                << "\n";
  }
  std::cerr << core::enum_name(result.variant) << ": mean closest-point distance " << result.fit.mean
            << " (data units), " << result.fit.mean_normalised << " of the model's diagonal; 90th percentile "
            << result.fit.p90 << "; " << result.seconds << " s\n";
  if (result.fit.strays > 0)
    std::cerr << "  " << result.fit.strays
              << " observed points stood alone, far from the fit, and were left out (stray-limit)\n";
  if (result.mixture.applied)
    std::cerr << "  noise " << result.mixture.noise << " of the model's diagonal (above mixture-noise): the space "
              << "fit ended in a Gaussian mixture, sigma " << result.mixture.sigma << "\n";
  nlohmann::json report =
      io::result_json(result, options.settings,
                      {options.model_path, seen.cut ? options.scene_input.source() : options.observed_path});
  if (seen.cut) report["scene"] = cut_json(*seen.cut);
  const Clock::time_point figures_started = Clock::now();
  if (result.variant != core::Variant::holistic) {
    // Whether the parts stay together: neighbouring parts' positions of the same boundary points.
    const core::SeamGap gap = core::seam_gap(model, result);
    std::cerr << "seam gap: mean " << gap.mean << ", largest " << gap.max << " of the model's diagonal over "
              << gap.points << " boundary points\n";
    report["seam_gap"] = {{"mean_normalised", gap.mean}, {"max_normalised", gap.max}, {"points", gap.points}};
  }
  if (model.canonical_mesh.faces.rows() > 0) {
    // How evenly the mesh came through: the largest edge stretch of the deformed canonical mesh.
    const double stretch = result.figures.mesh_stretch;
    std::cerr << "mesh stretch: largest edge " << stretch << "x its canonical length\n";
    report["mesh_stretch"] = stretch;
  }
  const double figures_seconds = seconds_since(figures_started);
  if (!options.truth_path.empty()) report["truth"] = truth_errors(model, observed, result, options);
  const Clock::time_point transfer_started = Clock::now();
  write_outputs(model, result, observed, frames, options);
  if (grasps) write_carried_grasps(model, result, observed, *grasps, options.grasps_out);
  io::add_stage_seconds(report, "read", read_seconds, seconds_since(started));
  io::add_stage_seconds(report, "figures", figures_seconds, seconds_since(started));
  io::add_stage_seconds(report, "transfer", seconds_since(transfer_started), seconds_since(started));
  write_json_or_stdout(report, options.json_path);
  report_verdict(result, options);
}

}  // namespace

void add_register_command(CLI::App& app) {
  auto o = std::make_shared<RegisterOptions>();
  CLI::App* command =
      app.add_subcommand("register", "Deform a category model onto an observed cloud or mesh");
  command->add_option("MODEL", o->model_path, "model file from partreg train")->required();
  command->add_option("OBSERVED", o->observed_path,
                      "observed cloud or mesh (data units and frame); or a scene: --depth or --scene");
  command->add_option("--json", o->json_path, "result JSON ('-' for stdout)");
  command->add_option("--points-out", o->points_out,
                      "the deformed canonical points with their part (.ply, .pcd, .vtp, .xyz)");
  command->add_option("--mesh-out", o->mesh_out, "the deformed canonical mesh (.obj, .ply, .vtp)");
  command->add_option("--frames", o->frames_path, "frames attached to the canonical (JSON)");
  command->add_option("--frames-out", o->frames_out, "where the transferred frames go");
  command->add_option("--grasps", o->grasps_path, "parallel-jaw grasps on the canonical (JSON, docs/grasps.md)");
  command->add_option("--grasps-out", o->grasps_out,
                      "where the grasps go: carried, re-seated on the registered object, ranked");
  command->add_option("--gripper", o->gripper_path, "gripper file (default: the grasps file's own)");
  add_registration_flags(command, o->settings);
  add_observation_flags(command, o->scene_input);
  command->add_option("--fail-on", o->fail_on, "exit 3 when the result's verdict is at least this bad")
      ->check(CLI::IsMember({"doubtful", "failed"}));
  add_threads_flag(command, o->threads);
  command->add_option("--init", o->init,
                      "start at this pose instead of searching: a result JSON of an earlier registration (its "
                      "pose and latent), a JSON 4x4 T_observed_canonical, or 16 numbers (rows); the search "
                      "runs only when the fit from it scores above --warm-limit");
  command->add_option(
      "--truth", o->truth_path,
      "ground-truth instance (cloud or mesh, or a folder of part meshes named as the model's "
      "parts; observed frame): report the errors against it (with parts: each part against its own)");
  command->add_option("--samples", o->mesh_samples, "points sampled from an observed mesh")
      ->capture_default_str()
      ->check(sample_count_range());
  command->callback([o] { run_register(*o); });
}

}  // namespace partreg::app
