#include "eqhb/structures/matrix_market.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
    while (readLine(line)) {
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '%') continue;
      return true;
    }
    return false;
  }

  bool firstLine(std::string& line) { return readLine(line); }

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
  long lineNumber() const { return line_number_; }

 private:
  // One line of at most kMaxMatrixMarketLine characters: a longer one is
  // refused after reading that many, not stored whole (std::getline would
  // grow the string to the file's size).
  bool readLine(std::string& line) {
    buffer_.resize(kMaxMatrixMarketLine + 2);
    in_.getline(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    const std::streamsize read = in_.gcount();
    if (read == 0 && in_.eof()) return false;
    ++line_number_;
    if (in_.bad()) fail("read error");
    // failbit without the end of the file: no newline within the buffer.
    if (in_.fail() && !in_.eof())
      fail("line longer than " + std::to_string(kMaxMatrixMarketLine) + " characters (not a Matrix Market file)");
    const size_t length = std::strlen(buffer_.data());
    // gcount counts the newline getline consumed; a shorter strlen means a NUL.
    if (static_cast<std::streamsize>(length) + (in_.eof() ? 0 : 1) != read)
      fail("a NUL byte in the line (not a text file)");
    if (length > static_cast<size_t>(kMaxMatrixMarketLine))
      fail("line longer than " + std::to_string(kMaxMatrixMarketLine) + " characters (not a Matrix Market file)");
    line.assign(buffer_.data(), length);
    return true;
  }

  std::string path_;
  std::ifstream in_;
  std::vector<char> buffer_;
  long line_number_ = 0;
};

// The banner's format and symmetry, in a MatrixMarketSize still without sizes.
MatrixMarketSize readHeader(MarketReader& reader) {
  std::string line;
  if (!reader.firstLine(line)) reader.fail("empty file (expected a %%MatrixMarket header)");
  std::istringstream words(line);
  std::string banner, object, format, field, symmetry;
  words >> banner >> object >> format >> field >> symmetry;
  // The line itself is not shown: a scene can name any readable file, whose
  // first line (a password hash, a key) has no business in an error message.
  if (banner != "%%MatrixMarket")
    reader.fail("expected a Matrix Market header \"%%MatrixMarket matrix coordinate|array real|integer "
                "general|symmetric\" on the first line; this file does not start with \"%%MatrixMarket\"");
  if (lower(object) != "matrix") reader.fail("object \"" + object + "\" is not supported (only \"matrix\")");
  MatrixMarketSize header;
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

// The header and the size line, checked for sign and shape (the memory they
// imply is judged in doubles by checkMatrixMarketMemory: a product of two
// declared longs may overflow).
MatrixMarketSize readSizes(MarketReader& reader) {
  MatrixMarketSize size = readHeader(reader);
  std::string line;
  if (!reader.nextDataLine(line)) reader.fail("no size line after the header");
  const char* p = line.c_str();
  size.rows = reader.integer(p, "(rows on the size line)");
  size.cols = reader.integer(p, "(columns on the size line)");
  if (size.coordinate) size.entries = reader.integer(p, "(entry count on the size line)");
  reader.expectEnd(p);
  if (size.rows < 1 || size.cols < 1 || size.entries < 0)
    reader.fail("sizes " + std::to_string(size.rows) + " x " + std::to_string(size.cols) +
                (size.coordinate ? " with " + std::to_string(size.entries) + " entries" : std::string()) +
                ": rows and columns must be >= 1, the entry count >= 0");
  if (size.symmetric && size.rows != size.cols)
    reader.fail("a symmetric matrix must be square, not " + std::to_string(size.rows) + " x " +
                std::to_string(size.cols));
  size.size_line = reader.lineNumber();
  return size;
}

}  // namespace

double MatrixMarketSize::storedEntries() const {
  const double r = static_cast<double>(rows), c = static_cast<double>(cols);
  if (!coordinate) return r * c;  // symmetric arrays expand to the full square
  return static_cast<double>(entries) * (symmetric ? 2.0 : 1.0);
}

double MatrixMarketSize::matrixBytes() const {
  return sparseBytes(static_cast<double>(cols), storedEntries());
}

double MatrixMarketSize::readBytes() const {
  // Per stored entry: a 16-byte triplet, the row-major copy setFromTriplets
  // sorts through (12 bytes) and the result (12 bytes). Per row: that copy's
  // offsets, its per-row counts and the counting vector (4 bytes each); per
  // column: the result's offsets twice (the assignment builds a new matrix
  // before freeing the old one) and its position vector.
  const double r = static_cast<double>(rows), c = static_cast<double>(cols);
  return 40.0 * storedEntries() + 12.0 * (r + 1.0) + 12.0 * (c + 1.0);
}

MatrixMarketSize readMatrixMarketSize(const std::string& path) {
  MarketReader reader(path);
  return readSizes(reader);
}

void checkMatrixMarketMemory(const std::string& path, const MatrixMarketSize& size, double extra_bytes) {
  const double bytes = size.readBytes() + extra_bytes;
  if (bytes <= kMaxModelBytes) return;
  char amount[64];
  std::snprintf(amount, sizeof amount, "%.3g GiB", bytes / (1024.0 * 1024 * 1024));
  throw InputError(path + ":" + std::to_string(size.size_line) + ": a " + std::to_string(size.rows) + " x " +
                   std::to_string(size.cols) + " matrix of " +
                   (size.coordinate ? std::to_string(size.entries) + " entries" : std::string("dense array storage")) +
                   " needs about " + amount + " to read, more than the " +
                   formatNumber(kMaxModelBytes / (1024.0 * 1024 * 1024)) + " GiB limit");
}
// Within the limit rows + cols < 4 GiB / 12 bytes: inside int, Eigen's index.
static_assert(kMaxModelBytes / 12.0 < 2147483647.0, "the memory limit keeps matrix sizes inside int");

Eigen::SparseMatrix<double> readMatrixMarket(const std::string& path) {
  MarketReader reader(path);
  const MatrixMarketSize size = readSizes(reader);
  checkMatrixMarketMemory(path, size);
  // Bounded now: rows * cols cannot overflow.
  const long rows = size.rows, cols = size.cols;
  const long expected = size.coordinate ? size.entries : size.symmetric ? rows * (rows + 1) / 2 : rows * cols;
  // Reserved once at the declared count (bounded by readSizes): no growth
  // that would hold two copies, and pages are touched only as entries are
  // read, so a file declaring more than it holds costs address space only.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(size.storedEntries()));
  long count = 0;
  long array_row = 0, array_col = 0;  // next position of an array-format file
  std::string line;
  while (reader.nextDataLine(line)) {
    if (count == expected)
      reader.fail("more entries than the " + std::to_string(expected) + " announced by the size line");
    const char* p = line.c_str();
    long i, j;
    double value;
    if (size.coordinate) {
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
      if (++array_row == rows) array_row = size.symmetric ? ++array_col : (++array_col, 0);
    }
    reader.expectEnd(p);
    if (size.symmetric && j > i)
      reader.fail("entry (" + std::to_string(i) + ", " + std::to_string(j) +
                  ") above the diagonal in a symmetric file (only the lower triangle is stored)");
    ++count;
    if (value == 0.0) continue;
    triplets.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), value);
    if (size.symmetric && i != j) triplets.emplace_back(static_cast<int>(j - 1), static_cast<int>(i - 1), value);
  }
  if (count != expected)
    throw InputError(path + ": the size line announces " + std::to_string(expected) + " entries, the file has " +
                     std::to_string(count));
  Eigen::SparseMatrix<double> matrix(rows, cols);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

Eigen::VectorXd readMatrixMarketVector(const std::string& path) {
  const MatrixMarketSize size = readMatrixMarketSize(path);
  if (size.cols != 1 && size.rows != 1)
    throw InputError(path + ": a load vector must be n x 1 or 1 x n, not " + std::to_string(size.rows) + " x " +
                     std::to_string(size.cols));
  // The vector beside the matrix it is read as (8 bytes an entry).
  const long length = std::max(size.rows, size.cols);
  checkMatrixMarketMemory(path, size, 8.0 * static_cast<double>(length));
  const Eigen::SparseMatrix<double> m = readMatrixMarket(path);
  Eigen::VectorXd vector = Eigen::VectorXd::Zero(length);
  for (int c = 0; c < m.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, c); it; ++it)
      vector[size.cols == 1 ? it.row() : it.col()] = it.value();
  return vector;
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
