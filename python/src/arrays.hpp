#pragma once
/// \file
/// numpy <-> Eigen for the module, with one rule for every function:
///  - In: point sets of shape (N, 3) as robotics code holds them: float64 or float32 numpy arrays of any
///    strides, Open3D's PointCloud and Vector3dVector (numpy borrows their buffer), lists of [x, y, z] (numpy
///    makes them an array). They are copied exactly once, straight into the library's Points (its functions
///    take `const Points&`, whose memory Eigen cannot borrow from numpy): one block for a C-contiguous
///    float64 array, element by element (converting) otherwise. Other dtypes and shapes: partreg.UsageError.
///  - Out: large arrays (points, parts, mesh vertices and faces) are numpy views of the C++ object that owns
///    them (no copy); the view keeps its owner alive. Views of results (the caller's own) are writeable, as
///    Open3D's vectors need; views into a model are read-only (every later registration reads them).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "partreg/core/types.hpp"

namespace partreg::python {

namespace py = pybind11;

/// `points` as Points (one copy, see above). UsageError naming `what` for a wrong form, dtype or shape.
core::Points to_points(const py::handle& array, const std::string& what);

/// `array` as a vector of int (int32 or int64, one dimension, C-contiguous; one copy). UsageError otherwise.
Eigen::VectorXi to_indices(const py::handle& array, const std::string& what);

/// Mesh faces: int32 or int64 (F, 3) vertex indices, C-contiguous (one copy). UsageError otherwise.
core::Faces to_faces(const py::handle& array, const std::string& what);

/// A vector of doubles (float64, one dimension; one copy). UsageError otherwise.
Eigen::VectorXd to_vector(const py::handle& array, const std::string& what);

/// Whether a view may be written through.
enum class Access { read_only, writeable };

/// A (rows, 3) view of `points`, whose memory `owner` keeps alive.
py::array points_view(const core::Points& points, py::handle owner, Access access = Access::read_only);

/// A (rows, 3) view of integer triples (mesh faces) owned by `owner`.
py::array faces_view(const core::Faces& faces, py::handle owner, Access access = Access::read_only);

/// A one-dimensional view of `values` owned by `owner`.
py::array indices_view(const Eigen::VectorXi& values, py::handle owner, Access access = Access::read_only);

/// A read-only view of a column-major matrix (a shape space's basis) or vector owned by `owner`.
py::array matrix_view(const Eigen::MatrixXd& matrix, py::handle owner);
py::array vector_view(const Eigen::VectorXd& values, py::handle owner);

/// A numpy array that takes over `points` (moved, not copied; freed with the array).
py::array owned_points(core::Points&& points);

/// Small results (latents, 4x4 poses): a copy is cheaper than the bookkeeping of a view.
py::array_t<double> copy_vector(const Eigen::VectorXd& values);
py::array_t<double> copy_matrix(const Eigen::MatrixXd& matrix);

/// A (3,) or (4, 4) or (3, 3) float64 array of the given shape, copied; UsageError otherwise.
Eigen::MatrixXd to_matrix(const py::handle& array, long rows, long cols, const std::string& what);

}  // namespace partreg::python
