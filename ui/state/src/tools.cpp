#include "partreg/ui/tools.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/normalization.hpp"
#include "partreg/core/training/training.hpp"
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
  const eval::Perturbation kind = core::parse_enum<eval::Perturbation>(kind_name);
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

TrainingJob prepare_training_job(const AppState& state, const std::string& dataset_path,
                                 const std::string& model_path) {
  if (!std::filesystem::is_directory(dataset_path))
    throw InputError("no dataset folder " + dataset_path + " to train on");
  if (model_path.empty()) throw UsageError("train needs a model file to write (out=MODEL.prm)");
  TrainingJob job{dataset_path, model_path, "", {}};
  if (state.labelling.loaded()) {
    job.labelled_instance = std::filesystem::path(state.labelling.mesh_path).stem().string();
    job.labels = state.labelling.labels;
  }
  return job;
}

std::string TrainingJob::run(const core::TrainingProgressCallback& progress) const {
  if (progress) progress(core::TrainingProgress{0, 0, "reading " + dataset_path});
  io::Dataset dataset = io::read_dataset(dataset_path);
  core::TrainingSettings settings = this->settings;
  std::string canonical_note = "no labels used";
  const bool in_dataset =
      !labelled_instance.empty() && !dataset.part_folders &&
      std::any_of(dataset.instances.begin(), dataset.instances.end(),
                  [&](const core::TrainingInstance& i) { return i.name == labelled_instance; });
  if (in_dataset) {
    if ((labels.labels.array() < 0).any())
      throw UsageError("every face of " + labelled_instance +
                       " needs a part before training (fill the rest)");
    io::apply_face_labels(dataset, labelled_instance, labels.names, labels.labels);
    settings.canonical = labelled_instance;
    canonical_note = "canonical " + labelled_instance + " with its labels";
  }
  const core::CategoryModel model =
      core::train_category(dataset.name, dataset.instances, dataset.part_names, settings, nullptr, progress);
  io::write_model(model_path, model);
  return "trained " + model_path + " on " + std::to_string(dataset.instances.size()) + " instances (" +
         canonical_note + ")";
}

}  // namespace partreg::ui
