// Until the one table of registration options (issue 13) lands, the keywords are the fields of
// core::RegistrationSettings, bound here and only here.
#include "registration_keywords.hpp"

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "partreg/core/errors.hpp"

namespace partreg::python {

namespace py = pybind11;

core::RegistrationSettings registration_settings(const py::kwargs& keywords) {
  core::RegistrationSettings settings;
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    try {
      if (name == "variant") settings.variant = core::parse_variant(value.cast<std::string>());
      else if (name == "direction") settings.direction = core::parse_direction(value.cast<std::string>());
      else if (name == "loss") settings.loss = core::parse_loss(value.cast<std::string>());
      else if (name == "loss_scale") settings.loss_scale = value.cast<double>();
      else if (name == "trim_fraction") settings.trim_fraction = value.cast<double>();
      else if (name == "prior_weight") settings.prior_weight = value.cast<double>();
      else if (name == "scale") settings.estimate_scale = value.cast<bool>();
      else if (name == "viewpoint") {
        if (!value.is_none()) settings.viewpoint = to_matrix(value, 3, 1, "viewpoint").col(0);
      } else if (name == "align_axes") settings.align_principal_axes = value.cast<bool>();
      else if (name == "restarts") settings.restarts = value.cast<int>();
      else if (name == "up") settings.up = to_matrix(value, 3, 1, "up").col(0);
      else if (name == "outer_iterations") settings.outer_iterations = value.cast<int>();
      else if (name == "inner_iterations") settings.inner_iterations = value.cast<int>();
      else if (name == "tolerance") settings.tolerance = value.cast<double>();
      else if (name == "observed_points") settings.observed_points = value.cast<int>();
      else {
        std::string known;
        for (const auto& [known_name, unused] : registration_defaults()) known += " " + std::string(py::str(known_name));
        throw UsageError("unknown registration setting '" + name + "'; known:" + known);
      }
    } catch (const py::cast_error&) {
      throw UsageError("registration setting " + name + " cannot be " + std::string(py::repr(value)));
    }
  }
  if (settings.restarts < 1) throw UsageError("restarts must be at least 1");
  return settings;
}

py::dict registration_defaults() {
  const core::RegistrationSettings settings;
  py::dict defaults;
  defaults["variant"] = core::to_string(settings.variant);
  defaults["direction"] = core::to_string(settings.direction);
  defaults["loss"] = core::to_string(settings.loss);
  defaults["loss_scale"] = settings.loss_scale;
  defaults["trim_fraction"] = settings.trim_fraction;
  defaults["prior_weight"] = settings.prior_weight;
  defaults["scale"] = settings.estimate_scale;
  defaults["viewpoint"] = py::none();
  defaults["align_axes"] = settings.align_principal_axes;
  defaults["restarts"] = settings.restarts;
  defaults["up"] = copy_vector(settings.up);
  defaults["outer_iterations"] = settings.outer_iterations;
  defaults["inner_iterations"] = settings.inner_iterations;
  defaults["tolerance"] = settings.tolerance;
  defaults["observed_points"] = settings.observed_points;
  return defaults;
}

}  // namespace partreg::python
