#pragma once
/// \file
/// The module's parts: its classes (types.cpp), its functions (functions.cpp).

#include <pybind11/pybind11.h>

namespace partreg::python {

/// Mesh, Frame, Model, ShapeSpace, the registration result and its parts, CPD results, View.
void bind_types(pybind11::module_& module);

/// The verdict: TrustFigures, and the result's figures, verdict and reasons (verdict_types.cpp).
void bind_verdict(pybind11::module_& module);

/// read/write, train, register, deform, transfer, cpd, views, errors.
void bind_functions(pybind11::module_& module);

/// Gripper, Grasp, read/write_grasps, sample_grasps, check_grasps, transfer_grasps (grasps.cpp).
void bind_grasps(pybind11::module_& module);
/// A readable __repr__ for the result and frame types bound by bind_types (after it).
void bind_reprs(pybind11::module_& module);
/// segment_depth, register_depth: depth images in the camera frame (scene_functions.cpp).
void bind_scene_functions(pybind11::module_& module);

}  // namespace partreg::python
