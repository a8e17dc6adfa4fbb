#pragma once
/// \file
/// register()'s keyword arguments: the registration settings by name, with the command line's names ('-'
/// as '_') and defaults.

#include <pybind11/pybind11.h>

#include "partreg/core/registration.hpp"

namespace partreg::python {

/// Settings from keyword arguments; UsageError naming an unknown keyword or a bad value.
core::RegistrationSettings registration_settings(const pybind11::kwargs& keywords);

/// Every keyword with its default value (what register() uses when it is not given).
pybind11::dict registration_defaults();

}  // namespace partreg::python
