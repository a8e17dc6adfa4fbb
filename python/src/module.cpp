// partreg's Python module (imported as `partreg`, see partreg/__init__.py): the library's two error kinds
// become Python exceptions, then the classes and functions are added.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/model_file.hpp"
#include "partreg/version.hpp"

PYBIND11_MODULE(_partreg, m) {
  namespace py = pybind11;
  m.doc() = "partreg: category-level, part-based, non-rigid 3D registration";
  // InputError: bad data or a failing resource (exit 1 on the command line); UsageError: a request that can
  // never succeed as stated (exit 2). Their messages are the library's own.
  py::register_exception<partreg::InputError>(m, "InputError", PyExc_RuntimeError);
  py::register_exception<partreg::UsageError>(m, "UsageError", PyExc_ValueError);
  m.attr("__version__") = partreg::kVersion;
  m.attr("model_format_version") = partreg::io::kModelFormatVersion;
  partreg::python::bind_types(m);
  partreg::python::bind_verdict(m);
  partreg::python::bind_functions(m);
  partreg::python::bind_grasps(m);
  partreg::python::bind_reprs(m);
  partreg::python::bind_scene_functions(m);
}
