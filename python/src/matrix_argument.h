// M, C or K from Python: a numpy array (or anything numpy.asarray takes) of
// real numbers, or a scipy.sparse matrix in any format. Checked before
// anything is copied: real dtype (complex, bool, strings and objects are
// refused, not cast), 2-D, within the size limits; scipy's arrays are
// validated and canonicalised by eqhb::sparseFromCompressed / Coordinates,
// never read through unchecked indices. Errors are InputError naming `field`.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "eqhb/sparse_matrix.h"

namespace eqhb::python {

SparseMatrix matrixArgument(const pybind11::handle& value, const std::string& field);

}  // namespace eqhb::python
