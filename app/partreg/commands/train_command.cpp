// `partreg train DATASET --out MODEL`: learn a category's shape spaces from a folder of aligned instances.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/commands/setting_flags.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/parallel.hpp"
#include "partreg/core/training/training.hpp"
#include "partreg/core/training/training_options.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/io/output_format.hpp"

namespace partreg::app {
namespace {

struct TrainOptions {
  int threads = 0;  // the command's thread budget
  std::string dataset_path;
  std::string out_path;
  std::string canonical;
  std::vector<std::filesystem::path> labels_paths;
  std::vector<std::string> held_out;  // instances left out of training (to register them as new ones)
  std::string json_path;
  io::DatasetOptions dataset;
  core::TrainingSettings settings;
};

nlohmann::json label_agreement_json(const core::TrainingReport& report) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [instance, agreement] : report.label_agreement)
    json[instance] = {{"by_surface", agreement.by_surface},
                      {"by_sampled_part", agreement.by_sampled_part},
                      {"shared_surface", agreement.shared_surface}};
  return json;
}

nlohmann::json summary_json(const core::CategoryModel& model, const core::TrainingReport& report,
                            const core::TrainingSettings& settings) {
  const nlohmann::json record = io::training_record_json(model.training);
  return {{"category", model.category},
          {"canonical", model.training.canonical},
          {"canonical_choice", report.canonical_choice},
          {"instances", model.training.instances},
          {"spaces", spaces_json(model)},
          {"label_agreement", label_agreement_json(report)},
          {"seam_weight", record["seam_weight"]},
          {"seam_weight_choice", record["seam_weight_choice"]},
          {"seam_weight_trials", record["seam_weight_trials"]},
          {"settings", settings_json(core::training_option_values(settings))},
          {"seconds", report.seconds}};
}

void print_summary(const core::CategoryModel& model, const core::TrainingReport& report) {
  const auto percent = [](double fraction) { return std::round(1000 * fraction) / 10; };
  std::cerr << "canonical: " << model.training.canonical << " (" << report.canonical_choice << ")\n";
  for (const core::ShapeSpace& space : model.spaces) {
    std::cerr << "space " << space.name << ": " << space.point_count() << " points, " << space.dimensions()
              << " dimensions, explained variance";
    for (double fraction : space.explained_fraction()) std::cerr << ' ' << percent(fraction) << '%';
    std::cerr << '\n';
  }
  for (const auto& [instance, agreement] : report.label_agreement) {
    std::cerr << "label propagation onto " << instance << ":";
    for (const auto& [part, fraction] : agreement.by_surface)
      std::cerr << ' ' << part << ' ' << percent(fraction) << '%';
    std::cerr << " (" << percent(agreement.by_sampled_part.at("all"))
              << "% by the part each point was sampled from; " << percent(agreement.shared_surface)
              << "% of its points on two parts' surfaces)\n";
  }
  if (model.training.seam_weight)
    std::cerr << "coupled seam weight " << *model.training.seam_weight << " ("
              << model.training.seam_weight_choice << ")\n";
  std::cerr << "trained in " << report.seconds << " s\n";
}

// Leaves the instances named in `names` out of `dataset` (the others keep the samples they have with them).
void hold_out(io::Dataset& dataset, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    auto& instances = dataset.instances;
    const auto found =
        std::find_if(instances.begin(), instances.end(),
                     [&](const core::TrainingInstance& instance) { return instance.name == name; });
    if (found == instances.end())
      throw UsageError("--hold-out: no instance '" + name + "' in " + dataset.name);
    instances.erase(found);
  }
  if (dataset.instances.size() < 2)
    throw UsageError("--hold-out leaves " + std::to_string(dataset.instances.size()) +
                     " instance to train on; a category needs at least 2");
}

void run_train(TrainOptions& options) {
  const core::ThreadBudget budget(options.threads);
  if (!options.canonical.empty()) options.settings.canonical = options.canonical;
  io::check_output(options.out_path, io::OutputKind::model, "--out");
  io::check_output(options.json_path, io::OutputKind::json, "--json");
  io::check_distinct_outputs({{"--out", options.out_path}, {"--json", options.json_path}});
  io::Dataset dataset = io::read_dataset(options.dataset_path, options.dataset);
  hold_out(dataset, options.held_out);
  std::cerr << "dataset " << dataset.name << ": " << dataset.instances.size() << " instances"
            << (options.held_out.empty() ? "" : " (" + std::to_string(options.held_out.size()) + " held out)")
            << (dataset.part_names.empty() ? ", no parts" : "") << '\n';
  if (!options.labels_paths.empty())
    options.settings.canonical =
        apply_labels_files(dataset, options.labels_paths, options.canonical, options.dataset);
  for (const core::TrainingInstance& instance : dataset.instances)
    if (instance.points.rows() < options.settings.canonical_points &&
        options.settings.canonical == instance.name)
      std::cerr << "note: canonical '" << instance.name << "' has only " << instance.points.rows()
                << " points: the model uses all of them\n";

  core::TrainingReport report;
  // One line per CPD and per PCA-EM, with the count and the time left (above a bar on a terminal).
  ProgressDisplay progress({"training steps", /*lines_are_detail=*/false, /*log_every_percent=*/0});
  const core::CategoryModel model = core::train_category(dataset.name, dataset.instances, dataset.part_names,
                                                         options.settings, &report, progress.listener());
  progress.finish();
  io::write_model(options.out_path, model);
  print_summary(model, report);
  std::cerr << "wrote " << options.out_path << '\n';
  write_json_or_stdout(summary_json(model, report, options.settings), options.json_path);
}

}  // namespace

void add_train_command(CLI::App& app) {
  auto options = std::make_shared<TrainOptions>();
  CLI::App* command =
      app.add_subcommand("train", "Learn a category model (shape spaces) from a dataset folder");
  add_threads_flag(command, options->threads);
  command
      ->add_option("DATASET", options->dataset_path,
                   "folder: one file per instance, or one folder of part meshes per instance")
      ->required();
  command->add_option("--out", options->out_path, "model file to write (.prm)")->required();
  command->add_option("--canonical", options->canonical, "instance to use as canonical (default: automatic)");
  command->add_option("--labels", options->labels_paths, kLabelsHelp);
  command->add_option("--hold-out", options->held_out,
                      "instance to leave out of training, by name (repeatable): to register it as a new one");
  command->add_option("--samples", options->dataset.points_per_instance, "surface samples per mesh instance")
      ->capture_default_str()
      ->check(sample_count_range());
  command->add_option("--seed", options->dataset.seed, "sampling seed")
      ->capture_default_str()
      ->check(seed_check());
  add_training_flags(command, options->settings);
  command->add_option("--json", options->json_path, "write a training summary as JSON ('-' for stdout)");
  command->callback([options] { run_train(*options); });
}

}  // namespace partreg::app
