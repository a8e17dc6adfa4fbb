#include "partreg/ui/tools.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/normalization.hpp"
#include "partreg/core/training.hpp"
#include "partreg/eval/perturbation.hpp"
#include "partreg/eval/views.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/model_file.hpp"

namespace partreg::ui {

std::string take_partial_view(AppState& state, int index, int count) {
  RegistrationDocument& registration = state.registration;
  if (registration.observed.rows() == 0) throw UsageError("no observation to view (load CLOUD first)");
  const std::vector<Eigen::Vector3d> directions = eval::sphere_directions(count);
  if (index < 0 || index >= count)
    throw UsageError("view index " + std::to_string(index) + " is not in 0.." + std::to_string(count - 1));
  eval::View view = eval::ViewCaster(registration.observed).cast(directions[static_cast<std::size_t>(index)]);
  if (view.points.rows() < 10) throw InputError("view " + std::to_string(index) + " sees almost nothing");
  const Eigen::Index before = registration.observed.rows();
  registration.observed = std::move(view.points);
  registration.viewpoint = view.viewpoint;
  registration.result.reset();
  registration.step = -1;
  return "partial view " + std::to_string(index) + " of " + std::to_string(count) + ": " +
         std::to_string(registration.observed.rows()) + " of " + std::to_string(before) + " points seen";
}

std::string perturb_observation(AppState& state, const std::string& kind_name, double paper_level,
                                std::uint64_t seed) {
  RegistrationDocument& registration = state.registration;
  if (registration.observed.rows() == 0) throw UsageError("no observation to perturb (load CLOUD first)");
  const eval::Perturbation kind = eval::parse_perturbation(kind_name);
  const double diagonal = core::bounding_box_diagonal(registration.observed);
  const eval::Perturbed perturbed =
      eval::perturb(registration.observed, kind, eval::relative_level(kind, paper_level), diagonal, seed);
  registration.observed = perturbed.points;
  if (registration.viewpoint)
    registration.viewpoint = perturbed.T_perturbed_original * *registration.viewpoint;
  registration.result.reset();
  registration.step = -1;
  std::ostringstream text;
  text << kind_name << " at " << paper_level << " (paper's units): " << registration.observed.rows()
       << " points";
  return text.str();
}

std::string train_model(const AppState& state, const std::string& dataset_path,
                        const std::string& model_path) {
  io::Dataset dataset = io::read_dataset(dataset_path);
  core::TrainingSettings settings;
  const LabelDocument& labelling = state.labelling;
  std::string canonical_note = "no labels used";
  if (labelling.loaded() && !dataset.part_folders) {
    const std::string instance = std::filesystem::path(labelling.mesh_path).stem().string();
    const bool in_dataset = std::any_of(dataset.instances.begin(), dataset.instances.end(),
                                        [&](const core::TrainingInstance& i) { return i.name == instance; });
    if (in_dataset) {
      const Eigen::VectorXi& labels = labelling.labels.labels;
      if ((labels.array() < 0).any())
        throw UsageError("every face of " + instance + " needs a part before training (fill the rest)");
      io::apply_face_labels(dataset, instance, labelling.labels.names, labels);
      settings.canonical = instance;
      canonical_note = "canonical " + instance + " with its labels";
    }
  }
  const core::CategoryModel model =
      core::train_category(dataset.name, dataset.instances, dataset.part_names, settings);
  io::write_model(model_path, model);
  return "trained " + model_path + " on " + std::to_string(dataset.instances.size()) + " instances (" +
         canonical_note + ")";
}

}  // namespace partreg::ui
