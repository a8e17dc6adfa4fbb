#include "arrays.hpp"

#include <cstring>
#include <sstream>

#include "partreg/core/errors.hpp"

namespace partreg::python {
namespace {

std::string shape_text(const py::array& array) {
  std::ostringstream text;
  text << '(';
  for (py::ssize_t i = 0; i < array.ndim(); ++i) text << (i ? ", " : "") << array.shape(i);
  text << (array.ndim() == 1 ? ",)" : ")");
  return text.str();
}

// True for an array whose elements are T in this machine's byte order (numpy's own equivalence test: a dtype
// object may be any instance, an unpickled array's for example).
template <typename T>
bool holds(const py::handle& object) {
  return py::isinstance<py::array_t<T>>(object);
}

// The checks every input array gets, in the order a user would fix them.
template <typename T>
py::array checked_array(const py::handle& object, const std::string& what, const std::string& dtype_name, int ndim,
                        long columns) {
  if (!py::isinstance<py::array>(object))
    throw UsageError(what + " must be a numpy array, not " + std::string(py::str(object.get_type().attr("__name__"))));
  const py::array array = py::reinterpret_borrow<py::array>(object);
  if (!holds<T>(array))
    throw UsageError(what + " must be " + dtype_name + ", not " + std::string(py::str(array.dtype())) +
                     ": convert it with numpy.asarray(x, dtype=numpy." + dtype_name + ")");
  const bool shape_ok = array.ndim() == ndim && (ndim == 1 || array.shape(1) == columns);
  if (!shape_ok)
    throw UsageError(what + " must have shape " +
                     (ndim == 1 ? std::string("(N,)") : "(N, " + std::to_string(columns) + ")") + ", not " +
                     shape_text(array));
  if (!(array.flags() & py::array::c_style))
    throw UsageError(what + " is not C-contiguous (a transposed or strided view): pass "
                     "numpy.ascontiguousarray(x)");
  return array;
}

// pybind11 marks views of const memory read-only; a result's own views are made writeable here.
py::array with_access(py::array array, Access access) {
  auto& flags = py::detail::array_proxy(array.ptr())->flags;
  if (access == Access::read_only)
    flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  else
    flags |= py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

py::array read_only(py::array array) { return with_access(std::move(array), Access::read_only); }

}  // namespace

namespace {

// What Python code holds as a point set, as an array: a numpy array as it is; an object with a `points`
// attribute (Open3D's PointCloud, partreg.View) by that attribute; anything else (Open3D's Vector3dVector, a
// list of lists) through numpy.asarray, which borrows a buffer without a copy and builds one from a list.
py::array as_array(const py::handle& object, const std::string& what) {
  if (py::isinstance<py::array>(object)) return py::reinterpret_borrow<py::array>(object);
  if (py::hasattr(object, "points") && !py::isinstance<py::str>(object))
    return as_array(object.attr("points"), what);
  try {
    return py::module_::import("numpy").attr("asarray")(object, "float64");
  } catch (const py::error_already_set&) {
    throw UsageError(what +
                     " must be points (N, 3): a numpy array, an Open3D PointCloud or Vector3dVector, or "
                     "a list of [x, y, z]; not " +
                     std::string(py::str(object.get_type().attr("__name__"))));
  }
}

// Element by element, any strides: the one copy for float32 and for views that are not C-contiguous.
template <typename T>
void copy_strided(const py::array& array, core::Points& points) {
  const auto* base = static_cast<const char*>(array.data());
  const py::ssize_t row_stride = array.strides(0), column_stride = array.strides(1);
  for (Eigen::Index r = 0; r < points.rows(); ++r)
    for (Eigen::Index c = 0; c < 3; ++c)
      points(r, c) =
          static_cast<double>(*reinterpret_cast<const T*>(base + r * row_stride + c * column_stride));
}

}  // namespace

core::Points to_points(const py::handle& object, const std::string& what) {
  const py::array array = as_array(object, what);
  const bool is_double = holds<double>(array), is_float = holds<float>(array);
  if (!is_double && !is_float)
    throw UsageError(what + " must be float64 or float32, not " + std::string(py::str(array.dtype())) +
                     ": convert it with numpy.asarray(x, dtype=numpy.float64)");
  if (array.ndim() != 2 || array.shape(1) != 3)
    throw UsageError(what + " must have shape (N, 3), not " + shape_text(array));
  core::Points points(array.shape(0), 3);
  if (points.size() == 0) return points;
  if (is_double && (array.flags() & py::array::c_style))
    std::memcpy(points.data(), array.data(), sizeof(double) * points.size());  // row-major both: one block
  else if (is_double)
    copy_strided<double>(array, points);
  else
    copy_strided<float>(array, points);
  return points;
}

Eigen::VectorXi to_indices(const py::handle& object, const std::string& what) {
  if (holds<std::int64_t>(object)) {
    const py::array array = checked_array<std::int64_t>(object, what, "int64", 1, 1);
    const auto* data = static_cast<const std::int64_t*>(array.data());
    Eigen::VectorXi values(array.shape(0));
    for (Eigen::Index i = 0; i < values.size(); ++i) values[i] = static_cast<int>(data[i]);
    return values;
  }
  const py::array array = checked_array<std::int32_t>(object, what, "int32", 1, 1);
  return Eigen::Map<const Eigen::VectorXi>(static_cast<const int*>(array.data()), array.shape(0));
}

core::Faces to_faces(const py::handle& object, const std::string& what) {
  if (holds<std::int64_t>(object)) {
    const py::array array = checked_array<std::int64_t>(object, what, "int64", 2, 3);
    using Wide = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>;
    return Eigen::Map<const Wide>(static_cast<const std::int64_t*>(array.data()), array.shape(0), 3).cast<int>();
  }
  const py::array array = checked_array<std::int32_t>(object, what, "int32", 2, 3);
  return Eigen::Map<const core::Faces>(static_cast<const int*>(array.data()), array.shape(0), 3);
}

Eigen::VectorXd to_vector(const py::handle& object, const std::string& what) {
  const py::array array = checked_array<double>(object, what, "float64", 1, 1);
  return Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(array.data()), array.shape(0));
}

Eigen::MatrixXd to_matrix(const py::handle& object, long rows, long cols, const std::string& what) {
  const std::string shape = "(" + std::to_string(rows) + (cols == 1 ? ",)" : ", " + std::to_string(cols) + ")");
  // Small and read once: any real numbers (a list, float32, a numpy view) are taken as float64.
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(object, "float64");
  } catch (const py::error_already_set&) {
    throw UsageError(what + " must be real numbers of shape " + shape + ", not " +
                     std::string(py::str(object.get_type().attr("__name__"))));
  }
  const bool is_vector = cols == 1 && array.ndim() == 1 && array.shape(0) == rows;
  const bool is_matrix = array.ndim() == 2 && array.shape(0) == rows && array.shape(1) == cols;
  if (!is_vector && !is_matrix)
    throw UsageError(what + " must have shape " + shape + ", not " + shape_text(array));
  // Small: element access handles any strides.
  const auto typed = py::array_t<double>::ensure(array);
  Eigen::MatrixXd matrix(rows, cols);
  auto values = typed.unchecked();
  for (long r = 0; r < rows; ++r)
    for (long c = 0; c < cols; ++c) matrix(r, c) = is_vector ? values.data(r)[0] : *values.data(r, c);
  return matrix;
}

py::array points_view(const core::Points& points, py::handle owner, Access access) {
  return with_access(py::array_t<double>({static_cast<py::ssize_t>(points.rows()), py::ssize_t{3}},
                                       {py::ssize_t{3 * sizeof(double)}, py::ssize_t{sizeof(double)}},
                                       points.data(), owner),
                     access);
}

py::array faces_view(const core::Faces& faces, py::handle owner, Access access) {
  return with_access(py::array_t<int>({static_cast<py::ssize_t>(faces.rows()), py::ssize_t{3}},
                                    {py::ssize_t{3 * sizeof(int)}, py::ssize_t{sizeof(int)}}, faces.data(),
                                    owner),
                     access);
}

py::array indices_view(const Eigen::VectorXi& values, py::handle owner, Access access) {
  return with_access(py::array_t<int>({static_cast<py::ssize_t>(values.size())}, {py::ssize_t{sizeof(int)}},
                                      values.data(), owner),
                     access);
}

py::array matrix_view(const Eigen::MatrixXd& matrix, py::handle owner) {
  return read_only(py::array_t<double>({static_cast<py::ssize_t>(matrix.rows()), static_cast<py::ssize_t>(matrix.cols())},
                                       {py::ssize_t{sizeof(double)}, static_cast<py::ssize_t>(sizeof(double) * matrix.rows())},
                                       matrix.data(), owner));
}

py::array vector_view(const Eigen::VectorXd& values, py::handle owner) {
  return read_only(py::array_t<double>({static_cast<py::ssize_t>(values.size())}, {py::ssize_t{sizeof(double)}},
                                       values.data(), owner));
}

py::array owned_points(core::Points&& points) {
  auto* owned = new core::Points(std::move(points));
  py::capsule owner(owned, [](void* pointer) { delete static_cast<core::Points*>(pointer); });
  return points_view(*owned, owner, Access::writeable);  // the caller's own
}

py::array_t<double> copy_vector(const Eigen::VectorXd& values) {
  py::array_t<double> array(values.size());
  std::copy(values.data(), values.data() + values.size(), array.mutable_data());
  return array;
}

py::array_t<double> copy_matrix(const Eigen::MatrixXd& matrix) {
  py::array_t<double> array({matrix.rows(), matrix.cols()});
  auto out = array.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < matrix.rows(); ++r)
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) out(r, c) = matrix(r, c);
  return array;
}

}  // namespace partreg::python
