#pragma once
/// \file
/// Every registration setting as a named option, declared once. The command line turns each into `--NAME`,
/// the app's `register` verb into `NAME=VALUE`, the Python module into a keyword argument (with '-' as
/// '_'). Values travel as text so that every front end parses them alike; a bad value is a UsageError that
/// names the value (the front end adds where it came from, e.g. the flag).

#include <functional>
#include <string>
#include <vector>

#include "partreg/core/registration_settings.hpp"

namespace partreg::core {

/// One registration setting.
struct RegistrationOption {
  std::string name;        ///< "restarts": --restarts, restarts=N, restarts=
  std::string value_name;  ///< what the value looks like in help: "N", "X,Y,Z", "holistic|partwise|hol+part"
  std::string help;        ///< one line, with units
  bool is_flag = false;    ///< a switch: "true"/"false" (a command-line flag takes no value)
  std::function<void(RegistrationSettings&, const std::string&)> set;  ///< parses; UsageError on a bad value
  std::function<std::string(const RegistrationSettings&)> get;         ///< the value as `set` reads it
};

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
