#pragma once
/// \file
/// numpy <-> Eigen for the module, with one rule for every function:
///  - In: point sets are float64 arrays of shape (N, 3), C-contiguous (a row per point, as core::Points).
///    Anything else (float32, a transposed or sliced view, a list) is refused with partreg.UsageError
///    naming the fix, never converted silently: a hidden conversion would be a hidden copy. Such an array
///    is copied exactly once, straight into the library's Points (its functions take `const Points&`,
///    whose memory Eigen cannot borrow from numpy).
///  - Out: large arrays (points, parts, mesh vertices and faces) are numpy views of the C++ object that owns
///    them (no copy); the view keeps its owner alive. Views of results (the caller's own) are writeable, as
///    Open3D's vectors need; views into a model are read-only (every later registration reads them).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "partreg/core/types.hpp"

namespace partreg::python {

namespace py = pybind11;

/// `array` as Points (one copy). UsageError naming `what` for a wrong dtype, shape or memory layout.
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
