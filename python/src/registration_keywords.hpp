#pragma once
/// \file
/// register()'s keyword arguments: the registration options of core/registration_options.hpp, named as on
/// the command line with '-' as '_', with the same defaults.

#include <pybind11/pybind11.h>

#include <string>

#include "partreg/core/registration.hpp"

namespace partreg::python {

/// Settings from keyword arguments; UsageError naming an unknown keyword or a bad value.
core::RegistrationSettings registration_settings(const pybind11::kwargs& keywords);

/// Every keyword with its default value (what register() uses when it is not given).
pybind11::dict registration_defaults();

/// One line per keyword, "keyword=default  help", for register()'s docstring.
std::string registration_keywords_doc();

/// Every keyword as a dict: keyword, option (the command line's flag), value (its form), help, default.
pybind11::list registration_options();

}  // namespace partreg::python
