#pragma once
/// \file
/// The evaluation and training tools the app offers beside its panels: a partial view and a perturbation
/// of the observation (as `partreg eval` makes them), and training a model on a dataset folder with the
/// labels being edited. Each returns the line for the status bar; failures throw and change nothing.

#include <cstdint>
#include <string>

#include "partreg/core/training/training.hpp"
#include "partreg/io/labels_file.hpp"
#include "partreg/ui/app_state.hpp"

namespace partreg::ui {

/// Replaces the observation by what a depth camera sees of it from direction `index` of `count` on a
/// tessellated sphere (docs/evaluation.md); the camera position becomes the registration's viewpoint.
std::string take_partial_view(AppState& state, int index, int count);

/// Perturbs the observation: `kind` noise | outliers | rotation | translation at `paper_level` in the
/// paper's units (noise and translation in metres for a 0.3 m object, scaled to this object's size;
/// outliers as a ratio; rotation in radians). A rigid perturbation moves the viewpoint with it.
std::string perturb_observation(AppState& state, const std::string& kind, double paper_level,
                                std::uint64_t seed);

/// Training a model on a dataset folder (as `partreg train`), made ready to run anywhere: it holds copies of
/// what it reads from the state, so the window can run it on a worker thread.
struct TrainingJob {
  std::string dataset_path;
  std::string model_path;         ///< where the model is written (atomically)
  std::string labelled_instance;  ///< stem of the mesh being labelled; empty when none is loaded
  io::PartLabels labels;          ///< its labels, one per face
  /// The training options (core/training/training_options.hpp); the canonical is set here.
  core::TrainingSettings settings;

  /// Reads the dataset and trains; when the labelled mesh is one of the dataset's instances it becomes the
  /// canonical with these labels (every face must have a part, else UsageError). Writes the model and
  /// returns the line for the status bar. Touches no app state; `progress` is called on this thread, first
  /// with 0 of 0 steps while the dataset is read.
  std::string run(const core::TrainingProgressCallback& progress = {}) const;
};

/// The job for training on `dataset_path` into `model_path` with the labelling document's mesh and labels.
/// Throws InputError when the dataset folder does not exist.
TrainingJob prepare_training_job(const AppState& state, const std::string& dataset_path,
                                 const std::string& model_path);

}  // namespace partreg::ui
