#pragma once
/// \file
/// The real mug model with parts, trained as the README trains it: the ShapeNet mugs of ../shared/data with
/// the committed labels of the canonical mug (assets/labels). About 25 s on this machine.

#include <algorithm>
#include <string>

#include "partreg/core/training/training.hpp"
#include "partreg/io/dataset.hpp"
#include "partreg/io/labels_file.hpp"
#include "support/shared_data.hpp"

namespace partreg::testing {

inline constexpr const char* kLabelledMugCanonical = "1a97f3c83016abca21d0de04f408950f";

/// Trains on every mug but `held_out` (none when empty). Check PARTREG_REQUIRE_SHARED_DATA first.
inline core::CategoryModel train_labelled_mugs(const std::string& held_out = "") {
  io::Dataset dataset = io::read_dataset(shared_data("mugs"));
  const io::PartLabels labels = io::read_labels_file(std::string(PARTREG_SOURCE_DIR) + "/assets/labels/" +
                                                     kLabelledMugCanonical + ".labels.json");
  io::apply_face_labels(dataset, kLabelledMugCanonical, labels.names, labels.labels);
  dataset.instances.erase(
      std::remove_if(dataset.instances.begin(), dataset.instances.end(),
                     [&](const core::TrainingInstance& instance) { return instance.name == held_out; }),
      dataset.instances.end());
  core::TrainingSettings settings;
  settings.canonical = kLabelledMugCanonical;
  return core::train_category(dataset.name, dataset.instances, dataset.part_names, settings);
}

}  // namespace partreg::testing
