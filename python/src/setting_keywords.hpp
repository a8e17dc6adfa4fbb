#pragma once
/// \file
/// Keyword arguments from the option tables: register()'s are the registration options
/// (core/registration/registration_options.hpp), train()'s the training options
/// (core/training/training_options.hpp), each named as on the command line with '-' as '_' (and a trailing
/// '_' on a Python keyword: `lambda_`), with the same defaults.

#include <pybind11/pybind11.h>

#include <string>

#include "partreg/core/registration/registration.hpp"
#include "partreg/core/training/training.hpp"

namespace partreg::python {

/// Settings from keyword arguments; UsageError naming an unknown keyword or a bad value's keyword.
core::RegistrationSettings registration_settings(const pybind11::kwargs& keywords);
core::TrainingSettings training_settings(const pybind11::kwargs& keywords);

/// Every keyword with its default value (what register() or train() uses when it is not given).
pybind11::dict registration_defaults();
pybind11::dict training_defaults();

/// One line per keyword, "keyword=default  help", for the docstring.
std::string registration_keywords_doc();
std::string training_keywords_doc();

/// Every keyword as a dict: keyword, option (the command line's flag), value (its form), help, default.
pybind11::list registration_options();
pybind11::list training_options();

}  // namespace partreg::python
