// libFuzzer target: the raw arrays of a sparse matrix as the Python module
// receives them from scipy, through eqhb::sparseFromCompressed and
// sparseFromCoordinates. The input is text, four lines:
//   csc|csr|coo ROWS COLS
//   indptr (csc, csr) or row indices (coo)
//   indices (csc, csr) or column indices (coo)
//   values
// Bad arrays must end in InputError; an accepted matrix must be canonical
// (compressed, rows strictly increasing in each column, finite) and equal
// the sum of the entries given. Anything else, a crash, a leak or undefined
// behaviour is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"
#include "eqhb/structures/sparse_arrays.h"

namespace {

// Matrices of more rows or columns are legitimate but only slow and large to
// build (their per-column arrays); their size checks run without building.
constexpr std::int64_t kBuildDimension = std::int64_t{1} << 22;

struct Arrays {
  std::string layout;
  std::int64_t rows = 0, cols = 0;
  std::vector<std::int64_t> first, second;  // indptr and indices, or row and col
  std::vector<double> values;
};

template <typename T>
std::vector<T> numbers(const std::string& line) {
  std::vector<T> out;
  const char* p = line.c_str();
  while (*p) {
    char* end = nullptr;
    if constexpr (std::is_same_v<T, double>) {
      out.push_back(std::strtod(p, &end));
    } else {
      out.push_back(std::strtoll(p, &end, 10));
    }
    if (end == p) {
      out.pop_back();
      ++p;  // not a number: skip a character
    } else {
      p = end;
    }
  }
  return out;
}

Arrays parse(const std::string& text) {
  std::istringstream in(text);
  std::string header, first, second, values;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, values);
  Arrays a;
  a.layout = header.substr(0, 3);
  const auto shape = numbers<std::int64_t>(header.size() > 3 ? header.substr(3) : "");
  a.rows = shape.size() > 0 ? shape[0] : 0;
  a.cols = shape.size() > 1 ? shape[1] : 0;
  a.first = numbers<std::int64_t>(first);
  a.second = numbers<std::int64_t>(second);
  a.values = numbers<double>(values);
  return a;
}

void require(bool ok, const char* what) {
  if (!ok) throw std::logic_error(what);  // uncaught: a finding
}

// (row, col) -> sum of the values given there, in the order given.
std::map<std::pair<std::int64_t, std::int64_t>, double> entrySums(const Arrays& a) {
  std::map<std::pair<std::int64_t, std::int64_t>, double> sums;
  if (a.layout == "coo") {
    for (std::size_t k = 0; k < a.values.size(); ++k) sums[{a.first[k], a.second[k]}] += a.values[k];
    return sums;
  }
  const bool by_rows = a.layout == "csr";
  for (std::size_t major = 0; major + 1 < a.first.size(); ++major)
    for (std::int64_t k = a.first[major]; k < a.first[major + 1]; ++k) {
      const std::int64_t minor = a.second[k];
      sums[by_rows ? std::make_pair(std::int64_t(major), minor) : std::make_pair(minor, std::int64_t(major))] +=
          a.values[k];
    }
  return sums;
}

void checkCanonical(const Arrays& a, const eqhb::SparseMatrix& m) {
  require(m.isCompressed(), "not compressed");
  require(m.rows() == a.rows && m.cols() == a.cols, "wrong shape");
  std::map<std::pair<std::int64_t, std::int64_t>, double> stored;
  for (int j = 0; j < m.outerSize(); ++j) {
    int previous = -1;
    for (eqhb::SparseMatrix::InnerIterator it(m, j); it; ++it) {
      require(it.row() > previous && it.row() < m.rows(), "rows not strictly increasing within range");
      require(std::isfinite(it.value()), "a stored value is not finite");
      previous = it.row();
      stored[{it.row(), j}] = it.value();
    }
  }
  require(stored == entrySums(a), "the stored entries are not the sums of the entries given");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Arrays a = parse(std::string(reinterpret_cast<const char*>(data), size));
  if (a.layout != "csc" && a.layout != "csr" && a.layout != "coo") return 0;
  const eqhb::IndexView first{a.first.data(), a.first.size()}, second{a.second.data(), a.second.size()};
  const eqhb::ValueView values{a.values.data(), a.values.size()};
  try {
    if (a.rows > kBuildDimension || a.cols > kBuildDimension) {
      eqhb::checkSparseSize("fuzz", a.rows, a.cols, static_cast<std::int64_t>(a.values.size()));
      return 0;
    }
    const eqhb::SparseMatrix m =
        a.layout == "coo" ? eqhb::sparseFromCoordinates("fuzz", a.rows, a.cols, first, second, values)
                          : eqhb::sparseFromCompressed(
                                "fuzz", a.layout == "csr" ? eqhb::Compressed::kRows : eqhb::Compressed::kColumns,
                                a.rows, a.cols, first, second, values);
    checkCanonical(a, m);
  } catch (const eqhb::InputError&) {
  }
  return 0;
}
