// Sparse matrices from another program's raw arrays: legal layouts
// (duplicates, unsorted rows, CSR, COO) give the matrix they mean; corrupt
// ones are refused naming the field before any index is followed.
#include "eqhb/structures/sparse_arrays.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "eqhb/error.h"
#include "test_support.h"

namespace eqhb {
namespace {

IndexView indexView(const std::vector<std::int64_t>& v) { return {v.data(), v.size()}; }
ValueView valueView(const std::vector<double>& v) { return {v.data(), v.size()}; }

SparseMatrix csc(std::int64_t rows, std::int64_t cols, const std::vector<std::int64_t>& indptr,
                 const std::vector<std::int64_t>& indices, const std::vector<double>& values,
                 Compressed layout = Compressed::kColumns) {
  return sparseFromCompressed("stiffness", layout, rows, cols, indexView(indptr), indexView(indices),
                              valueView(values));
}

using test::messageOf;

bool sortedWithoutDuplicates(const SparseMatrix& m) {
  for (int j = 0; j < m.outerSize(); ++j)
    for (int k = m.outerIndexPtr()[j] + 1; k < m.outerIndexPtr()[j + 1]; ++k)
      if (m.innerIndexPtr()[k] <= m.innerIndexPtr()[k - 1]) return false;
  return true;
}

const Eigen::Matrix2d kStiffness = (Eigen::Matrix2d() << 2, -1, -1, 1).finished();

TEST(SparseArrays, DuplicatesAreSummedAndRowsSorted) {
  // K(0,0) stored as 1 + 1, column 0's rows given as 0, 0, 1 and column 1's as 0, 1.
  const SparseMatrix m = csc(2, 2, {0, 3, 5}, {0, 0, 1, 0, 1}, {1, 1, -1, -1, 1});
  EXPECT_EQ(Eigen::MatrixXd(m), kStiffness);
  EXPECT_TRUE(m.isCompressed());
  EXPECT_EQ(m.nonZeros(), 4);
  const SparseMatrix unsorted = csc(2, 2, {0, 2, 4}, {1, 0, 1, 0}, {-1, 2, 1, -1});
  EXPECT_EQ(Eigen::MatrixXd(unsorted), kStiffness);
  EXPECT_TRUE(sortedWithoutDuplicates(unsorted));
}

TEST(SparseArrays, UnusedTrailingStorageIsIgnored) {
  // scipy may keep more indices and data than indptr[cols] uses.
  const SparseMatrix m = csc(2, 2, {0, 2, 4}, {0, 1, 0, 1, 99}, {2, -1, -1, 1, NAN});
  EXPECT_EQ(Eigen::MatrixXd(m), kStiffness);
}

TEST(SparseArrays, CompressedRowsAreTheTranspose) {
  // A 2 x 3 matrix by rows: [[4, 0, 2], [0, 1, 0]] with (0, 2) given as 1 + 1.
  const SparseMatrix m = csc(2, 3, {0, 3, 4}, {2, 0, 2, 1}, {1, 4, 1, 1}, Compressed::kRows);
  Eigen::MatrixXd expected(2, 3);
  expected << 4, 0, 2, 0, 1, 0;
  EXPECT_EQ(Eigen::MatrixXd(m), expected);
  EXPECT_TRUE(sortedWithoutDuplicates(m));
  EXPECT_NE(messageOf([] { csc(2, 3, {0, 1, 2}, {0, 3}, {1, 1}, Compressed::kRows); })
                .find("stiffness: stored entry 1 has column index 3, outside 0 .. 2"),
            std::string::npos);
}

TEST(SparseArrays, CoordinatesSumDuplicates) {
  const std::vector<std::int64_t> row{0, 0, 0, 1, 1}, col{0, 1, 0, 0, 1};
  const std::vector<double> values{1.5, -1, 0.5, -1, 1};
  const SparseMatrix m = sparseFromCoordinates("stiffness", 2, 2, indexView(row), indexView(col), valueView(values));
  EXPECT_EQ(Eigen::MatrixXd(m), kStiffness);
  EXPECT_TRUE(sortedWithoutDuplicates(m));
  const std::vector<std::int64_t> far{0, 0, 0, 1000000, 1};
  EXPECT_NE(messageOf([&] {
              sparseFromCoordinates("stiffness", 2, 2, indexView(row), indexView(far), valueView(values));
            }).find("stiffness: stored entry 3 has column index 1000000, outside 0 .. 1"),
            std::string::npos);
  EXPECT_NE(messageOf([&] {
              sparseFromCoordinates("stiffness", 2, 2, indexView(row), indexView({0, 1}), valueView(values));
            }).find("stiffness: 5 row indices, 2 column indices and 5 values"),
            std::string::npos);
}

TEST(SparseArrays, CorruptArraysAreRefusedNamingTheField) {
  const std::vector<std::pair<std::function<void()>, std::string>> cases = {
      {[] { csc(2, 2, {0, 2, 4}, {0, 1000000, 0, 1}, {2, -1, -1, 1}); },
       "stiffness: stored entry 1 has row index 1000000, outside 0 .. 1 (index out of range)"},
      {[] { csc(2, 2, {0, 2, 4}, {0, -3, 0, 1}, {2, -1, -1, 1}); }, "stored entry 1 has row index -3"},
      {[] { csc(2, 2, {0, 3, 1}, {0, 1, 0, 1}, {2, -1, -1, 1}); },
       "stiffness: indptr decreases from 3 to 1 at column 1"},
      {[] { csc(2, 2, {0, 2, 40}, {0, 1, 0, 1}, {2, -1, -1, 1}); },
       "stiffness: indptr ends at 40 but there are only 4 indices and 4 values"},
      {[] { csc(2, 2, {1, 2, 4}, {0, 1, 0, 1}, {2, -1, -1, 1}); }, "stiffness: indptr must start at 0"},
      {[] { csc(2, 2, {0, 4}, {0, 1, 0, 1}, {2, -1, -1, 1}); },
       "stiffness: indptr has 2 entries, a matrix of 2 columns needs 3"},
      {[] { csc(2, 2, {0, 2, 4}, {0, 1, 0, 1}, {2, NAN, -1, 1}); }, "stiffness: stored entry 1 is NaN or Inf"},
      {[] { csc(1, 1, {0, 2}, {0, 0}, {1e308, 1e308}); },
       "stiffness: the duplicate entries at (1, 1) sum to Inf"},
      {[] { csc(-1, 2, {0, 0, 0}, {}, {}); }, "stiffness: shape -1 x 2 is outside 0 .. 2147483647"},
      {[] { csc(std::int64_t{1} << 31, 1, {0, 0}, {}, {}); }, "stiffness: shape 2147483648 x 1 is outside"},
  };
  for (const auto& [call, expected] : cases) EXPECT_NE(messageOf(call).find(expected), std::string::npos) << expected;
}

TEST(SparseArrays, SizeLimitIsCheckedBeforeAnyAllocation) {
  // 2e9 columns need 8 GB of column offsets alone.
  EXPECT_NE(messageOf([] { checkSparseSize("mass", 2000000000, 2000000000, 0); })
                .find("mass = 2000000000 x 2000000000 with 0 stored entries: the sparse matrix needs about"),
            std::string::npos);
  EXPECT_NE(messageOf([] { checkSparseSize("mass", 10, 10, 1000000000); }).find("GiB limit"), std::string::npos);
  EXPECT_EQ(messageOf([] { checkSparseSize("mass", 30000, 30000, 30000); }), "(no error)");
}

}  // namespace
}  // namespace eqhb
