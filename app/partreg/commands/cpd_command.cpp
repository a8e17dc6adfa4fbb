// `partreg cpd SOURCE TARGET`: Coherent Point Drift between two files (clouds, or meshes sampled to points).
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/cpd/cpd.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/io/atomic_file.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/output_format.hpp"

namespace partreg::app {
namespace {

struct CpdOptions {
  int threads = 0;  // the command's thread budget
  std::string source_path;
  std::string target_path;
  std::string mode = "nonrigid";
  std::string out_path;
  std::string json_path;
  std::size_t points = 1000;
  std::uint64_t seed = 1;
  core::NonrigidCpdSettings nonrigid;
  bool scale = false;
  bool exact = false;
  bool exact_points = false;  ///< --points given: clouds are brought to that many points too
  std::optional<int> coarse_points;  ///< --coarse-points; unset: each mode's default
};

nlohmann::json common_json(const CpdOptions& options, double sigma2, int iterations,
                           core::CpdStopReason reason, double seconds) {
  return {{"mode", options.mode},
          {"source", options.source_path},
          {"target", options.target_path},
          {"settings",
           {{"outlier_weight", options.nonrigid.outlier_weight},
            {"tolerance", options.nonrigid.tolerance},
            {"max_iterations", options.nonrigid.max_iterations},
            {"points", options.points},
            {"seed", options.seed}}},
          {"iterations", iterations},
          {"sigma2", sigma2},
          {"stop_reason", core::to_string(reason)},
          {"seconds", seconds}};
}

struct Registered {
  core::Points moved;
  nlohmann::json report;
};

Registered run_mode(const CpdOptions& options, const core::Points& source, const core::Points& target,
                    const core::ProgressListener& progress) {
  const auto& s = options.nonrigid;
  if (options.mode == "rigid") {
    core::RigidCpdSettings settings;
    settings.outlier_weight = s.outlier_weight;
    settings.tolerance = s.tolerance;
    settings.max_iterations = s.max_iterations;
    settings.estimate_scale = options.scale;
    settings.coarse_points = options.coarse_points.value_or(settings.coarse_points);
    settings.progress = progress;
    const auto result = core::register_rigid(source, target, settings);
    auto report = common_json(options, result.sigma2, result.iterations, result.stop_reason, result.seconds);
    report["T_target_source"] = matrix_json(result.T_target_source());
    report["scale"] = result.scale;
    return {result.moved, report};
  }
  if (options.mode == "affine") {
    core::AffineCpdSettings settings;
    settings.outlier_weight = s.outlier_weight;
    settings.tolerance = s.tolerance;
    settings.max_iterations = s.max_iterations;
    settings.coarse_points = options.coarse_points.value_or(settings.coarse_points);
    settings.progress = progress;
    const auto result = core::register_affine(source, target, settings);
    auto report = common_json(options, result.sigma2, result.iterations, result.stop_reason, result.seconds);
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
    transform.topLeftCorner<3, 3>() = result.linear;
    transform.topRightCorner<3, 1>() = result.translation;
    report["T_target_source"] = matrix_json(transform);
    return {result.moved, report};
  }
  core::NonrigidCpdSettings settings = s;
  if (options.exact) settings.solver = core::NonrigidCpdSettings::Solver::exact;
  settings.coarse_points = options.coarse_points.value_or(settings.coarse_points);
  settings.progress = progress;
  const auto result = core::register_nonrigid(source, target, settings);
  auto report = common_json(options, result.sigma2, result.iterations, result.stop_reason, result.seconds);
  report["settings"]["beta"] = s.beta;
  report["settings"]["lambda"] = s.lambda;
  report["settings"]["solver"] = options.exact ? "exact" : "fast";
  return {result.moved, report};
}

void run_cpd(const CpdOptions& options) {
  const core::ThreadBudget budget(options.threads);
  if (options.mode != "rigid" && options.mode != "affine" && options.mode != "nonrigid")
    throw UsageError("--mode must be rigid, affine or nonrigid, not '" + options.mode + "'");
  io::check_output(options.out_path, io::OutputKind::cloud, "--out");
  io::check_output(options.json_path, io::OutputKind::json, "--json");
  io::check_distinct_outputs({{"--out", options.out_path}, {"--json", options.json_path}});
  const core::Points source =
      read_points_logged(options.source_path, options.points, options.seed, options.exact_points);
  const core::Points target =
      read_points_logged(options.target_path, options.points, options.seed + 1, options.exact_points);
  // A bar over EM's iteration cap on a terminal (EM usually stops before it); each iteration's sigma2 with
  // --verbose.
  ProgressDisplay progress({"EM iterations", /*lines_are_detail=*/true, /*log_every_percent=*/0});
  const Registered registered = run_mode(options, source, target, progress.listener());
  progress.finish();
  const auto& report = registered.report;
  std::cerr << "cpd " << options.mode << ": " << source.rows() << " -> " << target.rows() << " points, "
            << report["iterations"] << " iterations (" << report["stop_reason"].get<std::string>()
            << "), sigma2 " << report["sigma2"] << ", " << report["seconds"] << " s\n";

  core::Cloud moved;
  moved.points = registered.moved;
  io::write_cloud(options.out_path, moved);
  std::cerr << "wrote " << options.out_path << '\n';
  write_json_or_stdout(report, options.json_path);
}

}  // namespace

void add_cpd_command(CLI::App& app) {
  auto options = std::make_shared<CpdOptions>();
  CLI::App* command =
      app.add_subcommand("cpd", "Coherent Point Drift from SOURCE onto TARGET (clouds or meshes)");
  add_threads_flag(command, options->threads);
  // No CLI::ExistingFile: a missing input is a runtime failure (exit 1) here as in every command.
  command->add_option("SOURCE", options->source_path, "cloud or mesh to move")->required();
  command->add_option("TARGET", options->target_path, "cloud or mesh to reach")->required();
  command->add_option("--mode", options->mode, "rigid | affine | nonrigid")->capture_default_str();
  command->add_option("--out", options->out_path, "the moved source points, target frame (.ply, .pcd, .vtp, .xyz)")
      ->required();
  command->add_option("--json", options->json_path, "write the result as JSON here ('-' for stdout)");
  command
      ->add_option("--points", options->points,
                   "points of each input: meshes are sampled, clouds farthest-point downsampled (default: "
                   "clouds as they are, meshes 1000)")
      ->capture_default_str()
      ->check(point_count_range());
  command->add_option("--seed", options->seed, "sampling seed")->capture_default_str()->check(seed_check());
  command
      ->add_option("--beta", options->nonrigid.beta, "kernel width, normalised units (target diagonal = 1)")
      ->capture_default_str();
  command->add_option("--lambda", options->nonrigid.lambda, "smoothness weight (unitless)")
      ->capture_default_str();
  command->add_option("--w", options->nonrigid.outlier_weight, "outlier weight in [0, 1)")
      ->capture_default_str();
  command->add_option("--tolerance", options->nonrigid.tolerance, "relative change that stops the iterations")
      ->capture_default_str();
  command->add_option("--max-iterations", options->nonrigid.max_iterations, "iteration cap")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  command->add_option("--coarse-points", options->coarse_points,
                      "fast path: EM first settles on random subsets of this many points of each set, "
                      "then polishes on all (default: rigid and affine 1000, nonrigid 4000; 0 = never, "
                      "else >= 50)");
  command->add_flag("--scale", options->scale, "rigid mode: estimate a uniform scale too");
  command->add_flag("--exact", options->exact,
                    "nonrigid mode: the exact solver (full kernel, no truncation)");
  command->callback([options, command] {
    options->exact_points = command->count("--points") > 0;
    run_cpd(*options);
  });
}

}  // namespace partreg::app
