#pragma once
/// \file
/// The evaluation and training tools the app offers beside its panels: a partial view and a perturbation
/// of the observation (as `partreg eval` makes them), and training a model on a dataset folder with the
/// labels being edited. Each returns the line for the status bar; failures throw and change nothing.

#include <cstdint>
#include <string>

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

/// Trains a model on the dataset folder (as `partreg train`) and writes it to `model_path`; the mesh being
/// labelled, when it is one of the dataset's instances, becomes the canonical with the current labels (every
/// face must have a part). The caller loads the model.
std::string train_model(const AppState& state, const std::string& dataset_path,
                        const std::string& model_path);

}  // namespace partreg::ui
