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

core::Points to_points(const py::handle& object, const std::string& what) {
  const py::array array = checked_array<double>(object, what, "float64", 2, 3);
  core::Points points(array.shape(0), 3);
  if (points.size() > 0) std::memcpy(points.data(), array.data(), sizeof(double) * points.size());
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
  if (!py::isinstance<py::array>(object))
    throw UsageError(what + " must be a numpy array of shape (" + std::to_string(rows) + ", " +
                     std::to_string(cols) + ")");
  const py::array array = py::reinterpret_borrow<py::array>(object);
  if (!holds<double>(array))
    throw UsageError(what + " must be float64, not " + std::string(py::str(array.dtype())));
  const bool is_vector = cols == 1 && array.ndim() == 1 && array.shape(0) == rows;
  const bool is_matrix = array.ndim() == 2 && array.shape(0) == rows && array.shape(1) == cols;
  if (!is_vector && !is_matrix)
    throw UsageError(what + " must have shape (" + std::to_string(rows) +
                     (cols == 1 ? ",)" : ", " + std::to_string(cols) + ")") + ", not " + shape_text(array));
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
