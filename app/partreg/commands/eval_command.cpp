// `partreg eval DATASET --out DIR`: the paper's evaluation protocol on a category, with CSV, tables and
// plots. `partreg report CSV... --out DIR`: the same tables and plots from one or more runs (shards,
// categories).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/grasp_transfer.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/eval/protocol.hpp"
#include "partreg/eval/report.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/grasps_file.hpp"
#include "partreg/scene/scene_options.hpp"
#include "partreg/scene_eval/depth_scenes.hpp"

namespace partreg::app {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

struct EvalOptions {
  std::string dataset_path, out_path, canonical, protocol = "paper", shard = "1/1";
  std::vector<std::string> variants = core::enum_names<core::Variant>();
  std::vector<std::filesystem::path> labels_paths;
  bool no_viewpoint = false, no_baselines = false;
  int folds = -1, views = -1;
  std::vector<int> levels;          // 1-based indices of the paper's five levels; empty = the protocol's
  std::vector<std::string> sweeps;  // perturbation names; empty = the protocol's
  bool wide_rotation = false;
  std::string grasps_path, gripper_path;  // --grasps FILE or --gripper alone: grasps judged on the truth
  int grasp_count = 30;
  io::DatasetOptions dataset;
  eval::EvalSettings settings;
  scene_eval::DepthSceneSettings scenes;  // --scenes N > 0: depth scenes beside the point-sampled views
};

void parse_shard(const std::string& text, eval::EvalSettings& settings) {
  std::smatch match;
  // At most six digits each: a longer number would overflow std::stoi (and no run has a million shards).
  if (!std::regex_match(text, match, std::regex(R"((\d{1,6})/(\d{1,6}))")))
    throw UsageError("--shard must look like 2/4 (the second of four, at most 999999), not '" + text + "'");
  settings.shard = std::stoi(match[1]) - 1;
  settings.shard_count = std::stoi(match[2]);
  if (settings.shard_count < 1 || settings.shard < 0 || settings.shard >= settings.shard_count)
    throw UsageError("--shard " + text + " is out of range");
}

// Synthetic categories keep ground-truth correspondences in DATASET/ground_truth/<instance>.ply.
std::map<std::string, core::Points> read_correspondences(const fs::path& folder, const io::Dataset& dataset) {
  std::map<std::string, core::Points> correspondences;
  for (const core::TrainingInstance& instance : dataset.instances) {
    const fs::path file = folder / "ground_truth" / (instance.name + ".ply");
    if (!fs::exists(file)) return {};
    correspondences[instance.name] = io::read_cloud_file(file).cloud.points;
  }
  std::cerr << "ground-truth correspondences found: the correspondence error is reported\n";
  return correspondences;
}

eval::EvalInput load_input(EvalOptions& options) {
  io::Dataset dataset = io::read_dataset(options.dataset_path, options.dataset);
  eval::EvalInput input;
  if (!options.labels_paths.empty())
    input.fixed_canonical =
        apply_labels_files(dataset, options.labels_paths, options.canonical, options.dataset);
  std::cerr << "dataset " << dataset.name << ": " << dataset.instances.size() << " instances"
            << (dataset.part_names.empty() ? ", no parts" : "") << '\n';
  input.category = dataset.name;
  input.part_names = dataset.part_names;
  input.correspondences = read_correspondences(options.dataset_path, dataset);
  input.instances = std::move(dataset.instances);
  return input;
}

std::vector<std::string> sweep_names(const eval::Protocol& protocol) {
  std::vector<std::string> names;
  for (const eval::Perturbation kind : protocol.sweeps) names.push_back(core::enum_name(kind));
  return names;
}

void configure(EvalOptions& options) {
  eval::EvalSettings& settings = options.settings;
  settings.protocol = eval::protocol_by_name(options.protocol);
  if (options.folds >= 0) settings.protocol.folds = options.folds;
  if (options.views >= 0) settings.protocol.views = options.views;
  if (!options.levels.empty()) {
    settings.protocol.levels.clear();
    for (int level : options.levels) {
      if (level < 1 || level > 5)
        throw UsageError("--levels takes the paper's levels 1 to 5, not " + std::to_string(level));
      settings.protocol.levels.push_back(level - 1);
    }
  }
  if (!options.sweeps.empty()) {
    settings.protocol.sweeps.clear();
    for (const std::string& name : options.sweeps) {
      const eval::Perturbation kind = core::parse_enum<eval::Perturbation>(name);
      if (kind == eval::Perturbation::none && options.sweeps.size() > 1)
        throw UsageError("--sweeps: 'none' (clean observations only) goes alone");
      if (kind != eval::Perturbation::none) settings.protocol.sweeps.push_back(kind);
    }
  }
  settings.protocol.wide_rotation = options.wide_rotation;
  settings.variants.clear();
  for (const std::string& name : options.variants) {
    try {
      settings.variants.push_back(core::parse_enum<core::Variant>(name));
    } catch (const UsageError& error) {
      throw UsageError(std::string("--variants: ") + error.what());
    }
  }
  if (settings.variants.empty()) throw UsageError("--variants needs at least one variant");
  settings.use_viewpoint = !options.no_viewpoint;
  settings.baselines = !options.no_baselines;
  if (!options.grasps_path.empty() || !options.gripper_path.empty()) {
    eval::GraspEvaluation grasps;
    grasps.count = options.grasp_count;
    if (!options.grasps_path.empty()) {
      const GraspRequest request = read_grasp_request(options.grasps_path, options.gripper_path);
      grasps.given = request.grasps, grasps.gripper = request.gripper;
    } else {
      grasps.gripper = io::read_gripper_file(options.gripper_path);
    }
    settings.grasps = grasps;
  }
  if (settings.registration.initialisation.up) settings.training.up = *settings.registration.initialisation.up;
  parse_shard(options.shard, settings);
  scene_eval::check_settings(options.scenes);
  if (options.scenes.scenes > 0) settings.extra = std::make_shared<scene_eval::DepthScenes>(options.scenes);
}

// run.json's record of the depth scenes (null when none ran).
nlohmann::json scenes_json(const scene_eval::DepthSceneSettings& scenes) {
  if (scenes.scenes == 0) return nullptr;
  return {{"per_instance", scenes.scenes},
          {"object_size", scenes.object_size},
          {"neighbours", scenes.neighbours},
          {"elevations_degrees", scenes.elevations_degrees},
          {"distance", scenes.layout.distance},
          {"spacing", scenes.layout.spacing},
          {"intrinsics",
           {{"fx", scenes.intrinsics.fx},
            {"fy", scenes.intrinsics.fy},
            {"width", scenes.intrinsics.width},
            {"height", scenes.intrinsics.height}}},
          {"cut", settings_json(core::option_values(scene::scene_options(), scenes.cut))}};
}

// results.csv, tables.md and the sweep plots of every category, into `folder`.
void write_reports(const fs::path& folder, const std::vector<eval::EvalRow>& rows) {
  eval::write_rows_csv(folder / "results.csv", rows);
  std::ofstream tables(folder / "tables.md");
  if (!(tables << eval::markdown_report(rows)).flush())
    throw InputError("cannot write tables.md (disk full?)");
  for (const std::string& category : eval::categories_of(rows))
    for (bool partial : {false, true})
      eval::write_sweep_plot(folder / (category + (partial ? "_partial" : "_full") + "_sweeps.png"), rows,
                             category, partial);
}

void run_eval(EvalOptions& options) {
  configure(options);
  const core::ThreadBudget budget(options.settings.threads);  // training; registrations run in the arena
  StagedFolder folder(options.out_path);  // refuses a folder holding other files before any work
  const eval::EvalInput input = load_input(options);
  try {
    eval::tested_instances(input, options.settings);  // fails early on too few instances
  } catch (const UsageError& error) {
    // Its only usage check the command line has not made already (--shard) is the fold count.
    throw UsageError(std::string("--folds: ") + error.what());
  }
  const auto start = Clock::now();
  // The time left counts registrations only: the folds' training is reported `aside`.
  ProgressDisplay progress({"rows", /*lines_are_detail=*/false, /*log_every_percent=*/5});
  const std::vector<eval::EvalRow> rows = eval::run_evaluation(input, options.settings, progress.listener());
  progress.finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  write_reports(folder.staging(), rows);
  // Registrations only: the baseline rows have their own times (tables.md).
  const std::vector<std::string> variants = eval::variants_of(rows);
  double registration_seconds = 0.0;
  std::size_t registrations = 0;
  for (const eval::EvalRow& row : rows)
    if (std::find(variants.begin(), variants.end(), row.variant) != variants.end())
      registration_seconds += row.seconds, ++registrations;
  const nlohmann::json run = {
      {"results_format", eval::kRowsFormat},
      {"dataset", options.dataset_path},
      {"protocol", options.protocol},
      {"sweeps", sweep_names(options.settings.protocol)},
      {"wide_rotation", options.settings.protocol.wide_rotation},
      {"shard", options.shard},
      {"threads", options.settings.threads},
      {"variants", options.variants},
      {"baselines", options.settings.baselines},
      {"grasps", options.settings.grasps ? nlohmann::json{{"file", options.grasps_path},
                                                          {"gripper", options.gripper_path},
                                                          {"sampled_per_fold", options.grasps_path.empty()
                                                                                   ? options.grasp_count
                                                                                   : 0}}
                                         : nlohmann::json(nullptr)},
      {"samples", options.dataset.points_per_instance},
      {"truth_samples", options.settings.truth_points},
      {"depth_scenes", scenes_json(options.scenes)},
      // The settings every row used (a row's variant and viewpoint are its own), and every fold's training.
      {"registration", settings_json(core::registration_option_values(options.settings.registration),
                                     {"variant", "viewpoint"})},
      {"training", settings_json(core::training_option_values(options.settings.training))},
      {"registrations", registrations},
      {"rows", rows.size()},
      {"seconds", seconds},
      {"mean_registration_seconds", registrations == 0 ? 0.0 : registration_seconds / registrations}};
  write_json_or_stdout(run, (folder.staging() / "run.json").string(), /*log=*/false);
  folder.commit();
  std::cerr << registrations << " registrations and " << rows.size() - registrations << " baseline rows in "
            << clock_text(seconds) << " ("
            << (registrations == 0 ? 0.0 : registration_seconds / registrations)
            << " s per registration); wrote results.csv, "
            << "tables.md and plots to " << options.out_path << '\n';
}

struct ReportOptions {
  std::vector<std::string> csv_paths;
  std::string out_path;
};

void run_report(const ReportOptions& options) {
  std::vector<eval::EvalRow> rows;
  for (const std::string& path : options.csv_paths) {
    const fs::path file = fs::is_directory(path) ? fs::path(path) / "results.csv" : fs::path(path);
    std::vector<eval::EvalRow> more = eval::read_rows_csv(file);
    rows.insert(rows.end(), more.begin(), more.end());
  }
  StagedFolder folder(options.out_path);
  write_reports(folder.staging(), rows);
  const nlohmann::json run = {
      {"results_format", eval::kRowsFormat}, {"merged", options.csv_paths}, {"rows", rows.size()}};
  write_json_or_stdout(run, (folder.staging() / "run.json").string(), /*log=*/false);
  folder.commit();
  std::cerr << "merged " << rows.size() << " rows from " << options.csv_paths.size() << " runs into "
            << options.out_path << '\n';
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* command = app.add_subcommand("eval", "The paper's evaluation (leave-one-out, views, sweeps)");
  command->add_option("DATASET", o->dataset_path, "category folder (as for train)")->required();
  command->add_option("--out", o->out_path, "new folder: results.csv, tables.md, plots, run.json")
      ->required();
  command->add_option("--labels", o->labels_paths, kLabelsHelp);
  command->add_option("--canonical", o->canonical,
                      "the canonical: with one labels file the instance it was made for (default: from the "
                      "file); with several, one of their instances (default: the first file's)");
  command->add_option("--protocol", o->protocol, "paper | quick")->capture_default_str();
  command->add_option("--variants", o->variants, core::enum_choices<core::Variant>(", "))
      ->delimiter(',')
      ->capture_default_str();
  add_threads_flag(command, o->settings.threads);
  command->add_option("--folds", o->folds, "0 = leave-one-out (the protocol's choice by default)")
      ->check(CLI::Range(0, 100000));
  command->add_option("--views", o->views, "partial views per instance: 0, 12, 42, 162, ...")
      ->check(CLI::Range(0, 100000));
  command->add_option("--levels", o->levels, "which of the paper's five sweep levels (1-5), e.g. 1,3,5")
      ->delimiter(',');
  command
      ->add_option(
          "--sweeps", o->sweeps,
          "perturbation sweeps to run: noise, outliers, rotation, translation (the paper's, default) "
          "and yaw (0 to 330 degrees about the up axis); none: clean observations only")
      ->delimiter(',');
  command->add_flag("--wide-rotation", o->wide_rotation,
                    "the rotation sweep goes on past the paper's 0.65 rad, up to pi/2");
  command
      ->add_option("--scenes", o->scenes.scenes,
                   "depth scenes per tested instance: on a table beside two training instances, cut out as "
                   "register --depth cuts it and by hand (its true mask); 0 = none")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  command
      ->add_option("--scene-size", o->scenes.object_size,
                   "the tested instance's bounding-box diagonal on the scene's table (m)")
      ->capture_default_str();
  // The scene cut's settings, as register --depth takes them.
  add_scene_flags(command, o->scenes.cut);
  command->add_option("--shard", o->shard, "run only shard i of n (tested instances dealt round-robin)")
      ->capture_default_str();
  // Every registration setting but the variant (one row per --variants entry) and the viewpoint (each
  // partial view's own camera, unless --no-viewpoint).
  add_registration_flags(command, o->settings.registration, {"variant", "viewpoint"});
  // Every training setting of the folds' models; --up (above) is the category's up axis for both.
  add_training_flags(command, o->settings.training, {"up"});
  command->add_option("--grasps", o->grasps_path,
                      "grasps on the canonical (JSON) carried to every observation and judged on the true mesh");
  command->add_option("--gripper", o->gripper_path,
                      "gripper (JSON); alone, grasps are sampled on each fold's canonical mesh");
  command->add_option("--grasp-count", o->grasp_count, "grasps sampled per fold without --grasps")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  command->add_flag("--no-viewpoint", o->no_viewpoint, "do not tell the registration where the camera was");
  command->add_flag("--no-baselines", o->no_baselines,
                    "skip the baseline rows (oracle-template, rigid-canonical, mean-shape, true-shape)");
  command
      ->add_option("--samples", o->dataset.points_per_instance,
                   "surface samples per mesh instance (what the folds train on)")
      ->capture_default_str()
      ->check(sample_count_range());
  command
      ->add_option(
          "--truth-samples", o->settings.truth_points,
          "surface samples of a mesh instance's truth, drawn apart from the training sample (0: score "
          "against the training sample)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--seed", o->settings.seed, "seed of views, samples and perturbations")
      ->capture_default_str()
      ->check(seed_check());
  command->callback([o] { run_eval(*o); });

  auto r = std::make_shared<ReportOptions>();
  CLI::App* report =
      app.add_subcommand("report", "Tables and plots from eval runs (merges shards and categories)");
  report->add_option("RUNS", r->csv_paths, "eval output folders or their results.csv files")->required();
  report->add_option("--out", r->out_path, "new folder for the merged results.csv, tables.md and plots")
      ->required();
  report->callback([r] { run_report(*r); });
}

}  // namespace partreg::app
