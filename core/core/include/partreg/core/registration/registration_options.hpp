#pragma once
/// \file
/// Every registration setting as a named option (setting_option.hpp), declared once. The command line turns
/// each into `--NAME`, the app's `register` verb into `NAME=VALUE`, the Python module's register() into a
/// keyword argument (with '-' as '_').

#include <string>
#include <vector>

#include "partreg/core/options/setting_option.hpp"
#include "partreg/core/registration/registration_settings.hpp"

namespace partreg::core {

/// One registration setting (setting_option.hpp).
using RegistrationOption = SettingOption<RegistrationSettings>;

/// Every registration option, in the order help lists them.
const std::vector<RegistrationOption>& registration_options();

/// The option called `name`; UsageError listing the known names otherwise.
const RegistrationOption& registration_option(const std::string& name);

/// Sets option `name` of `settings` from `value`.
void set_registration_option(RegistrationSettings& settings, const std::string& name,
                             const std::string& value);

/// Every option's value as text, by name (what a result file records of its request).
std::vector<std::pair<std::string, std::string>> registration_option_values(
    const RegistrationSettings& settings);

/// Checks the whole request (ranges that one option alone cannot check); UsageError naming the value.
void validate(const RegistrationSettings& settings);

}  // namespace partreg::core
