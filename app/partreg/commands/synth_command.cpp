// `partreg synth CATEGORY --out DIR`: a synthetic category with parts and ground-truth correspondences.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/commands/console.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/progress.hpp"
#include "partreg/core/synthetic/synthetic.hpp"
#include "partreg/io/cloud_io.hpp"
#include "partreg/io/mesh_io.hpp"

namespace partreg::app {
namespace fs = std::filesystem;
namespace {

struct SynthOptions {
  std::string category;
  std::string out_path;
  int instances = 8;
  std::uint64_t seed = 1;
  int correspondences = 2000;
};

void write_ground_truth(const fs::path& file, const core::SurfaceSamples& samples) {
  core::Cloud cloud{samples.points, {}};
  io::PointAttributes attributes;
  attributes.integers["part"] = samples.part;
  attributes.reals["u"] = samples.uv.col(0);
  attributes.reals["v"] = samples.uv.col(1);
  io::write_cloud_ply(file, cloud, attributes);
}

void run_synth(const SynthOptions& options) {
  const core::SyntheticCategory category = core::parse_enum<core::SyntheticCategory>(options.category);
  // Staged: a killed run leaves a hidden folder (removed by the next run), never one `train` would use.
  StagedFolder folder(options.out_path);
  const fs::path out = folder.staging();
  fs::create_directories(out / "ground_truth");
  nlohmann::json parameters = nlohmann::json::object();
  // Hundreds of instances take seconds: a bar, each instance's line a detail. One instance at a time (as
  // make_synthetic_category makes them), so memory stays that of one.
  ProgressDisplay display({"instances", /*lines_are_detail=*/true, /*log_every_percent=*/10});
  const core::ProgressListener listener = display.listener();
  core::ProgressCounter progress(static_cast<std::size_t>(options.instances), listener);
  for (int index = 0; index < options.instances; ++index) {
    const core::SyntheticInstance instance = core::make_synthetic_instance(category, options.seed, index);
    fs::create_directories(out / instance.name);
    for (const core::SyntheticPart& part : instance.parts)
      io::write_mesh(out / instance.name / (part.name + ".obj"), part.mesh);
    write_ground_truth(out / "ground_truth" / (instance.name + ".ply"),
                       core::sample_correspondences(category, instance.shape_parameters, options.correspondences,
                                                    options.seed));
    parameters[instance.name] = instance.shape_parameters;
    progress.step("made " + instance.name + " (" + std::to_string(instance.parts.size()) + " parts)");
  }
  display.finish();
  const nlohmann::json description = {{"category", core::enum_name(category)},
                                      {"seed", options.seed},
                                      {"parts", core::part_names(category)},
                                      {"shape_parameters", parameters}};
  write_json_or_stdout(description, (out / "ground_truth" / "parameters.json").string(), /*log=*/false);
  folder.commit();
  std::cerr << "wrote " << options.out_path << " (" << options.instances << " instances and their ground truth)\n";
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto options = std::make_shared<SynthOptions>();
  CLI::App* command = app.add_subcommand(
      "synth", "Generate a synthetic category with parts and ground-truth correspondences");
  command->add_option("CATEGORY", options->category, "mug | drill | spray_bottle")->required();
  command->add_option("--out", options->out_path, "new folder to write (part-folder layout)")->required();
  command->add_option("--instances", options->instances, "how many instances (2 to 1000)")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000));
  command->add_option("--seed", options->seed, "random seed of the shape parameters")
      ->capture_default_str()
      ->check(seed_check());
  command
      ->add_option("--correspondences", options->correspondences, "ground-truth surface points per instance")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  command->callback([options] { run_synth(*options); });
}

}  // namespace partreg::app
