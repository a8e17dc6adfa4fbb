// Keywords come from the option tables (core/options/setting_option.hpp): a keyword is an option's name with
// '-' as '_', its value travels as the text the command line would read, and its default is the table's.
// Nothing about a setting is declared here.
#include "setting_keywords.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

#include "arrays.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/geometry/part_selection.hpp"
#include "partreg/core/registration/registration_options.hpp"
#include "partreg/core/training/training_options.hpp"

namespace partreg::python {
namespace {

namespace py = pybind11;

std::string keyword_of(std::string option_name) {
  std::replace(option_name.begin(), option_name.end(), '-', '_');
  // Python's own words cannot be keyword arguments: train(lambda_=3) for --lambda.
  static const std::set<std::string> reserved = {"lambda", "from", "global", "pass", "class", "import", "in", "is"};
  if (reserved.count(option_name)) option_name += '_';
  return option_name;
}

template <class Settings>
const core::SettingOption<Settings>& option_of(const std::vector<core::SettingOption<Settings>>& options,
                                               const std::string& keyword, const std::string& kind) {
  std::string known;
  for (const core::SettingOption<Settings>& option : options) {
    if (keyword_of(option.name) == keyword) return option;
    known += (known.empty() ? "" : ", ") + keyword_of(option.name);
  }
  throw UsageError("unknown " + kind + " setting '" + keyword + "' (known: " + known + ")");
}

// A Python value as the option's text: floats by their shortest round-trip repr, so no digit is lost.
std::string text_of(const py::handle& value, const std::string& keyword) {
  if (value.is_none()) return "none";
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return py::repr(value);
  if (py::isinstance<py::array>(value) || py::isinstance<py::sequence>(value)) {
    std::string text;
    for (const py::handle item : py::iter(value))
      text += (text.empty() ? "" : ",") +
              std::string(py::repr(py::float_(py::reinterpret_borrow<py::object>(item))));
    return text;
  }
  throw UsageError(keyword + " cannot be " + std::string(py::repr(value)));
}

// The option's text as a Python value of the kind its value name announces.
template <class Settings>
py::object value_of(const core::SettingOption<Settings>& option, const std::string& text) {
  if (option.is_flag) return py::bool_(text == "true");
  if (text == "none") return py::none();
  if (option.value_name == "N") return py::int_(std::stoi(text));
  if (option.value_name == "X") return py::float_(std::stod(text));
  // A number or a vector, unless a word stands in for one (up = "model": the model's own axis).
  const bool word = std::isalpha(static_cast<unsigned char>(text.front()));
  if (option.value_name.rfind("X,Y,Z", 0) == 0 && !word)
    return copy_vector(core::parse_vector3(text, option.name));
  if (option.value_name.rfind("X|", 0) == 0 && !word) return py::float_(std::stod(text));
  if (option.value_name == "W[,W...]") {  // a list of numbers
    py::list values;
    std::stringstream items(text);
    for (std::string item; std::getline(items, item, ',');) values.append(py::float_(std::stod(item)));
    return std::move(values);
  }
  return py::str(text);
}

// Settings from keywords: a bad value's UsageError starts with its keyword, as the command line's with its
// flag; then the whole request is checked.
template <class Settings>
Settings settings_of(const std::vector<core::SettingOption<Settings>>& options, const py::kwargs& keywords,
                     const std::string& kind) {
  Settings settings;
  for (const auto& [key, value] : keywords) {
    const std::string keyword = py::str(key);
    const core::SettingOption<Settings>& option = option_of(options, keyword, kind);
    try {
      option.set(settings, text_of(value, keyword));
    } catch (const UsageError& error) {
      throw UsageError(keyword + ": " + error.what());
    }
  }
  return settings;
}

template <class Settings>
py::dict defaults_of(const std::vector<core::SettingOption<Settings>>& options) {
  const Settings defaults;
  py::dict values;
  for (const core::SettingOption<Settings>& option : options)
    values[py::str(keyword_of(option.name))] = value_of(option, option.get(defaults));
  return values;
}

template <class Settings>
std::string doc_of(const std::vector<core::SettingOption<Settings>>& options) {
  const Settings defaults;
  std::string doc;
  for (const core::SettingOption<Settings>& option : options)
    doc += "\n  " + keyword_of(option.name) + "=" + option.get(defaults) + "  " + option.help;
  return doc;
}

template <class Settings>
py::list list_of(const std::vector<core::SettingOption<Settings>>& options) {
  const Settings defaults;
  py::list list;
  for (const core::SettingOption<Settings>& option : options) {
    py::dict entry;
    entry["keyword"] = keyword_of(option.name);
    entry["option"] = "--" + option.name;
    entry["value"] = option.value_name;
    entry["help"] = option.help;
    entry["default"] = value_of(option, option.get(defaults));
    list.append(entry);
  }
  return list;
}

}  // namespace

core::RegistrationSettings registration_settings(const py::kwargs& keywords) {
  core::RegistrationSettings settings = settings_of(core::registration_options(), keywords, "registration");
  core::validate(settings);
  return settings;
}

core::TrainingSettings training_settings(const py::kwargs& keywords) {
  core::TrainingSettings settings = settings_of(core::training_options(), keywords, "training");
  core::validate(settings);
  return settings;
}

py::dict registration_defaults() { return defaults_of(core::registration_options()); }
py::dict training_defaults() { return defaults_of(core::training_options()); }
std::string registration_keywords_doc() { return doc_of(core::registration_options()); }
std::string training_keywords_doc() { return doc_of(core::training_options()); }
py::list registration_options() { return list_of(core::registration_options()); }
py::list training_options() { return list_of(core::training_options()); }

}  // namespace partreg::python
