#include "matrix_argument.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"
#include "eqhb/structures/sparse_arrays.h"

namespace eqhb::python {

namespace py = pybind11;

namespace {

using Indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string typeName(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

std::string shapeText(std::int64_t rows, std::int64_t cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

// numpy.asarray: no copy of an array, a view or a broadcast.
py::array asArray(const py::handle& value, const std::string& field, const std::string& what) {
  try {
    return py::module_::import("numpy").attr("asarray")(value).cast<py::array>();
  } catch (const py::error_already_set&) {
    throw InputError(field + ": " + what + " is not an array of numbers (got " + typeName(value) + ")");
  }
}

// Real numbers only: a cast would drop an imaginary part, turn booleans into
// 0/1 or parse strings.
void requireKind(const py::array& a, const std::string& field, const std::string& what, const std::string& kinds,
                 const char* expected) {
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string::npos)
    throw InputError(field + ": " + what + " must be " + expected + ", not dtype " + std::string(py::str(a.dtype())));
}

// A 1-D array of a scipy matrix, at most its first `count` entries (count < 0:
// all), as T: only what the matrix uses is ever copied.
template <typename Array>
Array oneDimensional(const py::handle& value, const std::string& field, const std::string& name, std::int64_t count,
                     const std::string& kinds, const char* expected) {
  py::array a = asArray(value, field, name);
  requireKind(a, field, name, kinds, expected);
  if (a.ndim() != 1) throw InputError(field + ": " + name + " must be 1-D (is " + std::to_string(a.ndim()) + "-D)");
  if (count >= 0 && count < a.shape(0)) a = a[py::slice(0, static_cast<py::ssize_t>(count), 1)].cast<py::array>();
  Array out = Array::ensure(a);
  if (!out) throw InputError(field + ": " + name + " cannot be read as " + expected);
  return out;
}

Indices indexArray(const py::handle& value, const std::string& field, const std::string& name, std::int64_t count) {
  return oneDimensional<Indices>(value, field, name, count, "iu", "integers");
}

Values valueArray(const py::handle& value, const std::string& field, std::int64_t count) {
  return oneDimensional<Values>(value, field, "its values", count, "fiu", "real numbers");
}

IndexView view(const Indices& a) { return {a.data(), static_cast<std::size_t>(a.size())}; }
ValueView view(const Values& a) { return {a.data(), static_cast<std::size_t>(a.size())}; }

SparseMatrix fromScipy(const py::handle& value, const std::string& field) {
  std::int64_t rows = 0, cols = 0;
  std::string format;
  try {
    const py::tuple shape = value.attr("shape");
    rows = shape[0].cast<std::int64_t>();
    cols = shape[1].cast<std::int64_t>();
    format = py::str(value.attr("format"));
  } catch (const std::exception&) {
    throw InputError(field + ": a scipy.sparse matrix without a 2-D shape or a format");
  }
  checkSparseSize(field, rows, cols, 0);
  if (format == "csc" || format == "csr") {
    const Compressed layout = format == "csr" ? Compressed::kRows : Compressed::kColumns;
    const std::int64_t majors = layout == Compressed::kRows ? rows : cols;
    // One entry more than needed is enough for the wrong length to be reported.
    const Indices indptr = indexArray(value.attr("indptr"), field, "indptr", majors + 2);
    const std::int64_t used =
        indptr.size() == majors + 1 ? std::max<std::int64_t>(0, indptr.at(static_cast<py::ssize_t>(majors))) : 0;
    checkSparseSize(field, rows, cols, used);
    const Values values = valueArray(value.attr("data"), field, used);
    const Indices indices = indexArray(value.attr("indices"), field, "indices", used);
    return sparseFromCompressed(field, layout, rows, cols, view(indptr), view(indices), view(values));
  }
  if (format == "coo") {
    checkSparseSize(field, rows, cols, py::len(value.attr("data")));
    const Values values = valueArray(value.attr("data"), field, -1);
    const Indices row = indexArray(value.attr("row"), field, "row", -1);
    const Indices col = indexArray(value.attr("col"), field, "col", -1);
    return sparseFromCoordinates(field, rows, cols, view(row), view(col), view(values));
  }
  // BSR, DIA, LIL, DOK: scipy converts them with numpy operations, which
  // raise on bad indices instead of reading out of bounds.
  py::object coo;
  try {
    coo = value.attr("tocoo")();
  } catch (const py::error_already_set& e) {
    throw InputError(field + ": this scipy.sparse " + format + " matrix cannot be read (" + e.what() + ")");
  }
  return fromScipy(coo, field);
}

// A dense array, read a block of rows at a time as float64 (a view when it
// already is): a first pass counts the nonzeros per column and checks the
// size, the second fills the sparse matrix, so nothing of the array's full
// size is ever copied.
SparseMatrix fromDense(const py::handle& value, const std::string& field) {
  const py::array a = asArray(value, field, "it");
  requireKind(a, field, "its entries", "fiu", "real numbers");
  if (a.ndim() != 2)
    throw InputError(field + ": must be a real 2-D numpy array or a scipy.sparse matrix (got " + typeName(value) +
                     ", " + std::to_string(a.ndim()) + "-D)");
  const std::int64_t rows = a.shape(0), cols = a.shape(1);
  checkSparseSize(field, rows, cols, 0);
  checkBytes(field, shapeText(rows, cols), "a dense array (give large structures as scipy.sparse matrices)",
             8.0 * static_cast<double>(rows) * static_cast<double>(cols));
  const std::int64_t block = std::max<std::int64_t>(1, (std::int64_t{1} << 20) / std::max<std::int64_t>(cols, 1));
  const auto forEachBlock = [&](const auto& visit) {
    for (std::int64_t first = 0; first < rows; first += block) {
      const std::int64_t last = std::min(rows, first + block);
      const Values part = Values::ensure(a[py::slice(first, last, 1)]);
      if (!part) throw InputError(field + ": rows " + std::to_string(first) + " .. " + std::to_string(last - 1) +
                                  " cannot be read as float64");
      const auto v = part.unchecked<2>();
      for (py::ssize_t i = 0; i < v.shape(0); ++i)
        for (py::ssize_t j = 0; j < v.shape(1); ++j)
          if (v(i, j) != 0.0) visit(first + i, j, v(i, j));
    }
  };
  Eigen::VectorXi per_column = Eigen::VectorXi::Zero(cols);
  std::int64_t entries = 0;
  forEachBlock([&](std::int64_t, py::ssize_t j, double) {
    ++per_column[j];
    if (++entries % (std::int64_t{1} << 20) == 0) checkSparseSize(field, rows, cols, entries);
  });
  checkSparseSize(field, rows, cols, entries);
  SparseMatrix m(static_cast<int>(rows), static_cast<int>(cols));
  m.reserve(per_column);
  // Row by row: each column's rows arrive in increasing order.
  forEachBlock([&](std::int64_t i, py::ssize_t j, double x) {
    m.insert(static_cast<int>(i), static_cast<int>(j)) = x;
  });
  m.makeCompressed();
  return m;
}

}  // namespace

SparseMatrix matrixArgument(const py::handle& value, const std::string& field) {
  try {
    const py::module_ sparse = py::module_::import("scipy.sparse");
    if (sparse.attr("issparse")(value).cast<bool>()) return fromScipy(value, field);
    return fromDense(value, field);
  } catch (const py::error_already_set& e) {
    // What numpy or scipy raised on an object that only looks like a matrix.
    throw InputError(field + ": cannot be read as a matrix (" + e.what() + ")");
  }
}

}  // namespace eqhb::python
