#pragma once
/// \file
/// A setting as a named option, declared once in its settings type's table (registration_options.hpp,
/// training_options.hpp). The command line turns each into `--NAME`, the Python module into a keyword
/// argument (with '-' as '_'), the app's script into `NAME=VALUE`. Values travel as text so that every
/// front end parses them alike; a bad value is a UsageError that names the value (the front end adds where
/// it came from, e.g. the flag).

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "partreg/core/errors.hpp"

namespace partreg::core {

/// One setting of a `Settings` struct.
template <class Settings>
struct SettingOption {
  std::string name;        ///< "restarts": --restarts, restarts=N, restarts=
  std::string value_name;  ///< what the value looks like in help: "N", "X", "X,Y,Z", "holistic|partwise"
  std::string help;        ///< one line, with units
  bool is_flag = false;    ///< a switch: "true"/"false" (a command-line flag takes no value)
  std::function<void(Settings&, const std::string&)> set;  ///< parses; UsageError on a bad value
  std::function<std::string(const Settings&)> get;         ///< the value as `set` reads it
};

/// The option called `name` in `options`; UsageError naming the `kind` of setting and the known names.
template <class Settings>
const SettingOption<Settings>& find_option(const std::vector<SettingOption<Settings>>& options,
                                           const std::string& name, const std::string& kind) {
  std::string known;
  for (const SettingOption<Settings>& option : options) {
    if (option.name == name) return option;
    known += (known.empty() ? "" : ", ") + option.name;
  }
  throw UsageError("unknown " + kind + " setting '" + name + "' (known: " + known + ")");
}

/// Every option's value in `settings` as text, by name (what a result file records of its request).
template <class Settings>
std::vector<std::pair<std::string, std::string>> option_values(const std::vector<SettingOption<Settings>>& options,
                                                               const Settings& settings) {
  std::vector<std::pair<std::string, std::string>> values;
  for (const SettingOption<Settings>& option : options) values.emplace_back(option.name, option.get(settings));
  return values;
}

/// Checks settings built in code as the options check text on the way in: each value is written out and
/// read back through its option, so a value out of range is the same UsageError either way.
template <class Settings>
void check_options(const std::vector<SettingOption<Settings>>& options, const Settings& settings) {
  for (const SettingOption<Settings>& option : options) {
    Settings copy = settings;
    option.set(copy, option.get(settings));
  }
}

}  // namespace partreg::core
