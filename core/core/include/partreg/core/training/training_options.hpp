#pragma once
/// \file
/// Every training setting as a named option (setting_option.hpp), declared once: `partreg train` and
/// `partreg eval` (which trains a model per fold) turn each into `--NAME`, the Python module's train() into
/// a keyword argument (with '-' as '_'; `lambda_` for `lambda`), and train_category checks its settings
/// against the same ranges.

#include <string>
#include <vector>

#include "partreg/core/options/setting_option.hpp"
#include "partreg/core/training/training.hpp"

namespace partreg::core {

/// One training setting.
using TrainingOption = SettingOption<TrainingSettings>;

/// Every training option, in the order help lists them.
const std::vector<TrainingOption>& training_options();

/// The option called `name`; UsageError listing the known names otherwise.
const TrainingOption& training_option(const std::string& name);

/// Every option's value as text, by name (what an evaluation records of the models it trained).
std::vector<std::pair<std::string, std::string>> training_option_values(const TrainingSettings& settings);

/// Checks settings built in code against the options' ranges; UsageError naming the value.
void validate(const TrainingSettings& settings);

}  // namespace partreg::core
