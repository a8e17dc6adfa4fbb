// `partreg synth CATEGORY --out DIR`: a synthetic category with parts and ground-truth correspondences.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "partreg/commands/commands.hpp"
#include "partreg/commands/common.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/synthetic.hpp"
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

// The folder must be new or empty: synth never mixes its files with somebody else's.
void prepare_output(const fs::path& folder) {
  if (fs::exists(folder) && !(fs::is_directory(folder) && fs::is_empty(folder)))
    throw UsageError("output folder " + folder.string() + " exists and is not empty");
  fs::create_directories(folder / "ground_truth");
}

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
  if (options.instances < 2) throw UsageError("--instances must be at least 2");
  const fs::path out(options.out_path);
  prepare_output(out);
  nlohmann::json parameters = nlohmann::json::object();
  try {
    for (const core::SyntheticInstance& instance :
         core::make_synthetic_category(category, options.instances, options.seed)) {
      fs::create_directories(out / instance.name);
      for (const core::SyntheticPart& part : instance.parts)
        io::write_mesh(out / instance.name / (part.name + ".obj"), part.mesh);
      write_ground_truth(out / "ground_truth" / (instance.name + ".ply"),
                         core::sample_correspondences(category, instance.shape_parameters,
                                                      options.correspondences, options.seed));
      parameters[instance.name] = instance.shape_parameters;
      std::cerr << "wrote " << (out / instance.name).string() << " (" << instance.parts.size() << " parts)\n";
    }
  } catch (...) {
    fs::remove_all(out);  // nothing half-written is left behind
    throw;
  }
  const nlohmann::json description = {{"category", core::enum_name(category)},
                                      {"seed", options.seed},
                                      {"parts", core::part_names(category)},
                                      {"shape_parameters", parameters}};
  write_json_or_stdout(description, (out / "ground_truth" / "parameters.json").string());
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto options = std::make_shared<SynthOptions>();
  CLI::App* command = app.add_subcommand(
      "synth", "Generate a synthetic category with parts and ground-truth correspondences");
  command->add_option("CATEGORY", options->category, "mug | drill | spray_bottle")->required();
  command->add_option("--out", options->out_path, "new folder to write (part-folder layout)")->required();
  command->add_option("--instances", options->instances, "how many instances")->capture_default_str();
  command->add_option("--seed", options->seed, "random seed of the shape parameters")->capture_default_str();
  command
      ->add_option("--correspondences", options->correspondences, "ground-truth surface points per instance")
      ->capture_default_str();
  command->callback([options] { run_synth(*options); });
}

}  // namespace partreg::app
