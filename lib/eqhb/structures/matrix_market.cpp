#include "eqhb/structures/matrix_market.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "eqhb/error.h"
#include "eqhb/size_limits.h"

namespace eqhb {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Reads the file line by line with line numbers for the messages.
class MarketReader {
 public:
  explicit MarketReader(const std::string& path) : path_(path) {
    // A device or a pipe named as a matrix could be read without end.
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
      throw InputError(path + ": not a regular file (a Matrix Market file is expected)");
    in_.open(path);
    if (!in_) throw InputError(path + ": cannot open the Matrix Market file");
  }

  [[noreturn]] void fail(const std::string& rule) const {
    throw InputError(path_ + ":" + std::to_string(line_number_) + ": " + rule);
  }

  // Next line that is neither a comment nor blank; false at the end of the file.
  bool nextDataLine(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_number_;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '%') continue;
      return true;
    }
    return false;
  }

  bool firstLine(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_number_;
    return true;
  }

  // Parses one integer / one real token, failing with the line number.
  long integer(const char*& p, const char* what) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(p, &end, 10);
    if (end == p || errno == ERANGE || !(*end == '\0' || std::isspace(static_cast<unsigned char>(*end))))
      fail(std::string("expected an integer ") + what);
    p = end;
    return v;
  }
  double real(const char*& p, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !(*end == '\0' || std::isspace(static_cast<unsigned char>(*end))))
      fail(std::string("expected a number ") + what);
    if (!std::isfinite(v)) fail(std::string("the ") + what + " is NaN or Inf");
    p = end;
    return v;
  }
  void expectEnd(const char* p) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (*p) fail("unexpected text after the entry: \"" + std::string(p) + "\"");
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  long line_number_ = 0;
};

struct Header {
  bool coordinate = true;
  bool symmetric = false;
};

Header readHeader(MarketReader& reader) {
  std::string line;
  if (!reader.firstLine(line)) reader.fail("empty file (expected a %%MatrixMarket header)");
  std::istringstream words(line);
  std::string banner, object, format, field, symmetry;
  words >> banner >> object >> format >> field >> symmetry;
  if (banner != "%%MatrixMarket")
    reader.fail("the first line must be the header \"%%MatrixMarket matrix coordinate real "
                "general|symmetric\", found \"" + line + "\"");
  if (lower(object) != "matrix") reader.fail("object \"" + object + "\" is not supported (only \"matrix\")");
  Header header;
  format = lower(format);
  if (format == "array") header.coordinate = false;
  else if (format != "coordinate")
    reader.fail("format \"" + format + "\" must be \"coordinate\" or \"array\"");
  field = lower(field);
  if (field != "real" && field != "integer" && field != "double")
    reader.fail("field \"" + field + "\" is not supported (real or integer; no complex or pattern)");
  symmetry = lower(symmetry);
  if (symmetry == "symmetric") header.symmetric = true;
  else if (symmetry != "general")
    reader.fail("symmetry \"" + symmetry + "\" is not supported (general or symmetric)");
  return header;
}

}  // namespace

Eigen::SparseMatrix<double> readMatrixMarket(const std::string& path) {
  MarketReader reader(path);
  const Header header = readHeader(reader);
  std::string line;
  if (!reader.nextDataLine(line)) reader.fail("no size line after the header");
  const char* p = line.c_str();
  const long rows = reader.integer(p, "(rows on the size line)");
  const long cols = reader.integer(p, "(columns on the size line)");
  const long entries = header.coordinate ? reader.integer(p, "(entry count on the size line)") : rows * cols;
  reader.expectEnd(p);
  if (rows < 1 || cols < 1 || entries < 0)
    reader.fail("sizes " + std::to_string(rows) + " x " + std::to_string(cols) + " must be positive");
  if (header.symmetric && rows != cols)
    reader.fail("a symmetric matrix must be square, not " + std::to_string(rows) + " x " + std::to_string(cols));
  if (rows > (1L << 30) || cols > (1L << 30)) reader.fail("sizes too large");
  // Bounded by the memory the declared sizes imply (the triplets read and the
  // compressed matrix), before anything of that size is allocated.
  const double stored = (header.coordinate ? static_cast<double>(entries) : static_cast<double>(rows) * cols) *
                        (header.symmetric ? 2.0 : 1.0);
  const double bytes = 16.0 * stored + sparseBytes(static_cast<double>(cols), stored);
  if (bytes > kMaxModelBytes) {
    char size[64];
    std::snprintf(size, sizeof size, "%.3g GiB", bytes / (1024.0 * 1024 * 1024));
    reader.fail("a " + std::to_string(rows) + " x " + std::to_string(cols) + " matrix of " +
                (header.coordinate ? std::to_string(entries) + " entries" : std::string("dense array storage")) +
                " needs about " + size + ", more than the " +
                formatNumber(kMaxModelBytes / (1024.0 * 1024 * 1024)) + " GiB limit");
  }

  const long expected = !header.coordinate && header.symmetric ? rows * (rows + 1) / 2 : entries;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(std::min<long>(expected, 1L << 24)) * (header.symmetric ? 2 : 1));
  long count = 0;
  long array_row = 0, array_col = 0;  // next position of an array-format file
  while (reader.nextDataLine(line)) {
    if (count == expected)
      reader.fail("more entries than the " + std::to_string(expected) + " announced by the size line");
    p = line.c_str();
    long i, j;
    double value;
    if (header.coordinate) {
      i = reader.integer(p, "(row index)");
      j = reader.integer(p, "(column index)");
      value = reader.real(p, "value");
      if (i < 1 || i > rows || j < 1 || j > cols)
        reader.fail("entry (" + std::to_string(i) + ", " + std::to_string(j) + ") outside the " +
                    std::to_string(rows) + " x " + std::to_string(cols) + " matrix (indices from 1)");
    } else {
      // Column-major; symmetric array storage lists the lower triangle only.
      value = reader.real(p, "value");
      i = array_row + 1;
      j = array_col + 1;
      if (++array_row == rows) array_row = header.symmetric ? ++array_col : (++array_col, 0);
    }
    reader.expectEnd(p);
    if (header.symmetric && j > i)
      reader.fail("entry (" + std::to_string(i) + ", " + std::to_string(j) +
                  ") above the diagonal in a symmetric file (only the lower triangle is stored)");
    ++count;
    if (value == 0.0) continue;
    triplets.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), value);
    if (header.symmetric && i != j) triplets.emplace_back(static_cast<int>(j - 1), static_cast<int>(i - 1), value);
  }
  if (count != expected)
    throw InputError(path + ": the size line announces " + std::to_string(expected) + " entries, the file has " +
                     std::to_string(count));
  Eigen::SparseMatrix<double> matrix(rows, cols);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

Eigen::VectorXd readMatrixMarketVector(const std::string& path) {
  const Eigen::SparseMatrix<double> m = readMatrixMarket(path);
  if (m.cols() != 1 && m.rows() != 1)
    throw InputError(path + ": a load vector must be n x 1 or 1 x n, not " + std::to_string(m.rows()) + " x " +
                     std::to_string(m.cols()));
  Eigen::MatrixXd dense(m);
  return m.cols() == 1 ? Eigen::VectorXd(dense.col(0)) : Eigen::VectorXd(dense.row(0).transpose());
}

void writeMatrixMarket(const std::string& path, const Eigen::SparseMatrix<double>& matrix, bool symmetric) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the Matrix Market file");
  long entries = 0;
  for (int c = 0; c < matrix.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it)
      if (!symmetric || it.row() >= it.col()) ++entries;
  out << "%%MatrixMarket matrix coordinate real " << (symmetric ? "symmetric" : "general") << "\n"
      << matrix.rows() << " " << matrix.cols() << " " << entries << "\n"
      << std::setprecision(17);
  for (int c = 0; c < matrix.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it)
      if (!symmetric || it.row() >= it.col()) out << it.row() + 1 << " " << it.col() + 1 << " " << it.value() << "\n";
  if (!out) throw InputError(path + ": write failed");
}

double relativeAsymmetry(const Eigen::SparseMatrix<double>& matrix) {
  if (matrix.rows() != matrix.cols()) return INFINITY;
  const Eigen::SparseMatrix<double> transposed = matrix.transpose();
  const Eigen::SparseMatrix<double> difference = matrix - transposed;
  double largest = 0.0, worst = 0.0;
  for (int c = 0; c < matrix.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it)
      largest = std::max(largest, std::abs(it.value()));
  for (int c = 0; c < difference.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(difference, c); it; ++it)
      worst = std::max(worst, std::abs(it.value()));
  return largest > 0.0 ? worst / largest : 0.0;
}

}  // namespace eqhb
