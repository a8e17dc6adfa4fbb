// register()'s keywords come from the one table of registration options (core/registration_options.hpp): a
// keyword is an option's name with '-' as '_', its value travels as the text the command line would read,
// and its default is the table's. Nothing about a setting is declared here.
#include "registration_keywords.hpp"

#include <algorithm>
#include <cctype>

#include "arrays.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/core/part_selection.hpp"
#include "partreg/core/registration_options.hpp"

namespace partreg::python {
namespace {

namespace py = pybind11;

std::string keyword_of(std::string option_name) {
  std::replace(option_name.begin(), option_name.end(), '-', '_');
  return option_name;
}

const core::RegistrationOption& option_of(const std::string& keyword) {
  for (const core::RegistrationOption& option : core::registration_options())
    if (keyword_of(option.name) == keyword) return option;
  std::string known;
  for (const core::RegistrationOption& option : core::registration_options())
    known += (known.empty() ? "" : ", ") + keyword_of(option.name);
  throw UsageError("unknown registration setting '" + keyword + "' (known: " + known + ")");
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
py::object value_of(const core::RegistrationOption& option, const std::string& text) {
  if (option.is_flag) return py::bool_(text == "true");
  if (text == "none") return py::none();
  if (option.value_name == "N") return py::int_(std::stoi(text));
  if (option.value_name == "X") return py::float_(std::stod(text));
  // A vector, unless a word stands in for one (up = "model": the model's own axis).
  if (option.value_name.rfind("X,Y,Z", 0) == 0 && !std::isalpha(static_cast<unsigned char>(text.front())))
    return copy_vector(core::parse_vector3(text, option.name));
  return py::str(text);
}

}  // namespace

core::RegistrationSettings registration_settings(const py::kwargs& keywords) {
  core::RegistrationSettings settings;
  for (const auto& [key, value] : keywords) {
    const std::string keyword = py::str(key);
    option_of(keyword).set(settings, text_of(value, keyword));
  }
  core::validate(settings);
  return settings;
}

py::dict registration_defaults() {
  const core::RegistrationSettings defaults;
  py::dict values;
  for (const core::RegistrationOption& option : core::registration_options())
    values[py::str(keyword_of(option.name))] = value_of(option, option.get(defaults));
  return values;
}

std::string registration_keywords_doc() {
  const core::RegistrationSettings defaults;
  std::string doc;
  for (const core::RegistrationOption& option : core::registration_options())
    doc += "\n  " + keyword_of(option.name) + "=" + option.get(defaults) + "  " + option.help;
  return doc;
}

py::list registration_options() {
  const core::RegistrationSettings defaults;
  py::list options;
  for (const core::RegistrationOption& option : core::registration_options()) {
    py::dict entry;
    entry["keyword"] = keyword_of(option.name);
    entry["option"] = "--" + option.name;
    entry["value"] = option.value_name;
    entry["help"] = option.help;
    entry["default"] = value_of(option, option.get(defaults));
    options.append(entry);
  }
  return options;
}

}  // namespace partreg::python
