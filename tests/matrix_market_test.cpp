#include "eqhb/structures/matrix_market.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/scenes/scene.h"
#include "eqhb/structures/structure_matrices.h"
#include "eqhb/backends/registry.h"

namespace eqhb {
namespace {

namespace fs = std::filesystem;

class MatrixMarketFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("eqhb_mm_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // Expects an InputError containing every needle.
  template <typename F>
  void expectError(F&& f, std::initializer_list<std::string> needles) {
    try {
      f();
      FAIL() << "accepted";
    } catch (const InputError& e) {
      for (const auto& needle : needles) EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

const char* kStiffness =
    "%%MatrixMarket matrix coordinate real symmetric\n% 3-DOF chain\n3 3 5\n1 1 2\n2 1 -1\n2 2 2\n3 2 -1\n3 3 1\n";

TEST_F(MatrixMarketFiles, SymmetricStorageIsExpandedAndGeneralIsKept) {
  const auto k = readMatrixMarket(write("k.mtx", kStiffness));
  ASSERT_EQ(k.rows(), 3);
  EXPECT_DOUBLE_EQ(k.coeff(0, 1), -1.0);
  EXPECT_DOUBLE_EQ(k.coeff(1, 0), -1.0);
  EXPECT_DOUBLE_EQ(k.coeff(2, 2), 1.0);
  EXPECT_EQ(k.nonZeros(), 7);
  const auto g = readMatrixMarket(write("g.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 2 5\n1 2 1\n2 1 6\n"));
  EXPECT_DOUBLE_EQ(g.coeff(0, 1), 6.0);  // duplicates summed
  EXPECT_DOUBLE_EQ(g.coeff(1, 0), 6.0);
  EXPECT_DOUBLE_EQ(g.coeff(0, 0), 0.0);
}

TEST_F(MatrixMarketFiles, ArrayLayoutIsColumnMajorAndSymmetricArrayIsTheLowerTriangle) {
  const auto a = readMatrixMarket(write("a.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n"));
  EXPECT_DOUBLE_EQ(a.coeff(1, 0), 2.0);
  EXPECT_DOUBLE_EQ(a.coeff(0, 1), 3.0);
  const auto s = readMatrixMarket(write("s.mtx", "%%MatrixMarket matrix array real symmetric\n3 3\n1\n2\n3\n4\n5\n6\n"));
  EXPECT_DOUBLE_EQ(s.coeff(2, 0), 3.0);
  EXPECT_DOUBLE_EQ(s.coeff(0, 2), 3.0);
  EXPECT_DOUBLE_EQ(s.coeff(1, 1), 4.0);
  EXPECT_DOUBLE_EQ(s.coeff(2, 1), 5.0);
  EXPECT_DOUBLE_EQ(s.coeff(2, 2), 6.0);
}

TEST_F(MatrixMarketFiles, WriteThenReadRestoresTheMatrixExactly) {
  Eigen::MatrixXd d(3, 3);
  d << 4, 1.0 / 3.0, 0, 1.0 / 3.0, 5, -2e-17, 0, -2e-17, 6;
  const Eigen::SparseMatrix<double> m = d.sparseView();
  for (bool symmetric : {false, true}) {
    const std::string path = (dir_ / "w.mtx").string();
    writeMatrixMarket(path, m, symmetric);
    EXPECT_EQ(Eigen::MatrixXd(readMatrixMarket(path)), d);
  }
}

TEST_F(MatrixMarketFiles, BadFilesNameTheFileAndTheLine) {
  const std::string missing = (dir_ / "none.mtx").string();
  expectError([&] { readMatrixMarket(missing); }, {missing, "cannot open"});
  const auto header = write("h.mtx", "3 3 1\n1 1 1\n");
  expectError([&] { readMatrixMarket(header); }, {header + ":1:", "expected a Matrix Market header"});
  // A file that is no matrix: its first line is not repeated in the message.
  const auto secret = write("s.txt", "root:$6$secret-hash:19000:0:99999:7:::\n");
  try {
    readMatrixMarket(secret);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("secret-hash"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("%%MatrixMarket matrix coordinate"), std::string::npos) << e.what();
  }
  const auto complex = write("c.mtx", "%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n");
  expectError([&] { readMatrixMarket(complex); }, {":1:", "complex"});
  const auto nan = write("n.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 nan\n");
  expectError([&] { readMatrixMarket(nan); }, {nan + ":4:", "NaN"});
  const auto outside = write("o.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n");
  expectError([&] { readMatrixMarket(outside); }, {":3:", "outside the 2 x 2"});
  const auto few = write("f.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 1\n");
  expectError([&] { readMatrixMarket(few); }, {few, "announces 3 entries, the file has 1"});
  const auto many = write("m.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n2 2 1\n");
  expectError([&] { readMatrixMarket(many); }, {":4:", "more entries"});
  const auto garbled = write("g.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 x 1\n");
  expectError([&] { readMatrixMarket(garbled); }, {":3:", "column index"});
  const auto upper = write("u.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n");
  expectError([&] { readMatrixMarket(upper); }, {":3:", "above the diagonal"});
}

// A 3-DOF chain from files: M, K (and C or a damping model), friction on DOF 3.
std::string scene(const std::string& structure_keys, const std::string& law_dof = "3") {
  return "name = \"mm\"\n[structure]\ntype = \"matrix-market\"\n" + structure_keys +
         "\n[[forcing]]\ndof = 1\ncos = 2.0\n[[law]]\ntype = \"coulomb-1d\"\ndofs = [" + law_dof +
         "]\nmuN = 0.5\n[harmonic_balance]\nharmonics = 3\nsamples = 64\nomega = 0.5\n";
}

TEST_F(MatrixMarketFiles, DeclaredSizesAreBoundedBeforeAnythingIsAllocated) {
  // 2^30 columns: 4 GiB of column offsets would be allocated for one entry.
  expectError([&] {
    readMatrixMarket(write("wide.mtx", "%%MatrixMarket matrix coordinate real general\n1073741824 1073741824 1\n1 1 1\n"));
  }, {"wide.mtx:2: a 1073741824 x 1073741824 matrix of 1 entries needs about", "GiB limit"});
  expectError([&] {
    readMatrixMarket(write("many.mtx", "%%MatrixMarket matrix coordinate real symmetric\n1000 1000 400000000\n1 1 1\n"));
  }, {"many.mtx:2: a 1000 x 1000 matrix of 400000000 entries needs about"});
  expectError([&] {
    readMatrixMarket(write("array.mtx", "%%MatrixMarket matrix array real general\n100000 100000\n1\n"));
  }, {"array.mtx:2: a 100000 x 100000 matrix of dense array storage needs about"});
}

TEST_F(MatrixMarketFiles, DeclaredSizesAreJudgedWithoutOverflowAndWithTheReadersTemporaries) {
  // 3037000500^2 overflows a long: judged by memory, not "must be positive".
  expectError([&] {
    readMatrixMarket(write("big.mtx", "%%MatrixMarket matrix array real general\n3037000500 3037000500\n1\n"));
  }, {"big.mtx:2: a 3037000500 x 3037000500 matrix of dense array storage needs about", "to read"});
  // No entries, but the transposed copy and index vectors setFromTriplets
  // builds per row and column (12 bytes each way) exceed the limit.
  expectError([&] {
    readMatrixMarket(write("wide.mtx", "%%MatrixMarket matrix coordinate real general\n200000000 200000000 0\n"));
  }, {"wide.mtx:2: a 200000000 x 200000000 matrix of 0 entries needs about 4.47 GiB to read"});
  // A load vector also counts the dense vector it becomes (8 bytes an entry).
  expectError([&] {
    readMatrixMarketVector(write("v.mtx", "%%MatrixMarket matrix coordinate real general\n300000000 1 0\n"));
  }, {"v.mtx:2: a 300000000 x 1 matrix of 0 entries needs about 5.59 GiB to read"});
  expectError([&] {
    readMatrixMarketVector(write("m.mtx", "%%MatrixMarket matrix coordinate real general\n1000000 2 0\n"));
  }, {"a load vector must be n x 1 or 1 x n, not 1000000 x 2"});
  const MatrixMarketSize size = readMatrixMarketSize(write("s.mtx", kStiffness));
  EXPECT_EQ(size.rows, 3);
  EXPECT_EQ(size.entries, 5);
  EXPECT_EQ(size.size_line, 3);
  EXPECT_DOUBLE_EQ(size.storedEntries(), 10.0);  // symmetric: up to both triangles
}

TEST_F(MatrixMarketFiles, LinesAreBoundedAndTextOnly) {
  // One line a character longer than the bound is refused as it is read; a
  // line of exactly the bound is read.
  const std::string zeros(kMaxMatrixMarketLine - 5, '0');  // "1 1 " + zeros + "1": the bound
  const auto at_bound = write("b.mtx", "%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 " + zeros + "1\n");
  EXPECT_DOUBLE_EQ(readMatrixMarket(at_bound).coeff(0, 0), 1.0);
  const auto long_value = write("l.mtx", "%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 0" + zeros + "1\n");
  expectError([&] { readMatrixMarket(long_value); }, {"l.mtx:3: line longer than 4096 characters"});
  const auto long_comment =
      write("c.mtx", "%%MatrixMarket matrix coordinate real general\n%" + std::string(5000, 'x') + "\n1 1 0\n");
  expectError([&] { readMatrixMarket(long_comment); }, {"c.mtx:2: line longer than 4096 characters"});
  const auto long_last = write("e.mtx", "%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 0" + zeros + "1");
  expectError([&] { readMatrixMarket(long_last); }, {"e.mtx:3: line longer than 4096 characters"});
  // Text after a NUL byte would be ignored silently.
  const auto nul = write("n.mtx", std::string("%%MatrixMarket matrix coordinate real general\n1 1 1\n1 1 1") + '\0' + " junk\n");
  expectError([&] { readMatrixMarket(nul); }, {"n.mtx:3: a NUL byte"});
}

TEST_F(MatrixMarketFiles, OnlyRegularFilesAreRead) {
  // A directory, or a device that would be read without end.
  expectError([&] { readMatrixMarket(dir_.string()); }, {dir_.string() + ": not a regular file"});
  expectError([&] { readMatrixMarket("/dev/zero"); }, {"/dev/zero: not a regular file"});
  expectError([&] { readMatrixMarket((dir_ / "missing.mtx").string()); }, {"cannot open the Matrix Market file"});
}

TEST_F(MatrixMarketFiles, SceneReadsPathsRelativeToTheSceneFileAndBuildsRayleighDamping) {
  write("k.mtx", kStiffness);
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 2\n3 3 3\n");
  const auto path = write("s.toml", scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"\nrayleigh = [0.1, 0.02]"));
  const Scene s = loadScene(path);
  ASSERT_EQ(s.model.structure.dofs(), 3);
  EXPECT_DOUBLE_EQ(s.model.structure.mass.coeff(2, 2), 3.0);
  EXPECT_DOUBLE_EQ(s.model.structure.damping.coeff(1, 1), 0.1 * 2 + 0.02 * 2);
  EXPECT_DOUBLE_EQ(s.model.structure.damping.coeff(0, 1), 0.02 * -1);
}

TEST_F(MatrixMarketFiles, SceneComparesTheSizeLinesBeforeReadingAnyEntry) {
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 2\n3 3 3\n");
  write("k.mtx", kStiffness);
  // 2^28 DOFs beside a 3 x 3 mass: refused by the size line, not built.
  write("big.mtx", "%%MatrixMarket matrix coordinate real symmetric\n268435456 268435456 1\n1 1 1\n");
  expectError([&] { loadScene(write("a.toml", scene("mass = \"m.mtx\"\nstiffness = \"big.mtx\""))); },
              {"a.toml: structure.stiffness = \"", "big.mtx\": is 268435456 x 268435456, the mass matrix is 3 x 3",
               "by the size lines"});
  write("rect.mtx", "%%MatrixMarket matrix coordinate real general\n3 4 0\n");
  expectError([&] { loadScene(write("b.toml", scene("mass = \"rect.mtx\"\nstiffness = \"k.mtx\""))); },
              {"structure.mass = \"", "must be square, its size line says 3 x 4"});
  // Of one size but too large to read: named by the field and the file.
  write("wide-m.mtx", "%%MatrixMarket matrix coordinate real general\n536870912 536870912 0\n");
  write("wide-k.mtx", "%%MatrixMarket matrix coordinate real general\n536870912 536870912 0\n");
  expectError([&] { loadScene(write("c.toml", scene("mass = \"wide-m.mtx\"\nstiffness = \"wide-k.mtx\""))); },
              {"c.toml: structure.mass: ", "wide-m.mtx:2: a 536870912 x 536870912 matrix of 0 entries needs about"});
  // A load vector of 2^30 - 1 entries for 3 DOFs: refused by its size line.
  std::string text = scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"");
  text.replace(text.find("dof = 1\ncos = 2.0"), 17, "file = \"f.mtx\"\ncos = 3.0");
  write("f.mtx", "%%MatrixMarket matrix coordinate real general\n1073741823 1 0\n");
  expectError([&] { loadScene(write("d.toml", text)); },
              {"forcing[0].file = \"", "has 1073741823 entries, the structure has 3 DOFs"});
  write("f.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 0\n");
  expectError([&] { loadScene(write("e.toml", text)); }, {"forcing[0].file", "its size line says 3 x 3"});
  // Modal damping on more DOFs than it allows: before the files are read.
  write("m5.mtx", "%%MatrixMarket matrix coordinate real general\n5000 5000 1\n1 1 1\n");
  write("k5.mtx", "%%MatrixMarket matrix coordinate real general\n5000 5000 1\n1 1 1\n");
  expectError([&] { loadScene(write("f.toml", scene("mass = \"m5.mtx\"\nstiffness = \"k5.mtx\"\nmodal_damping = 0.01"))); },
              {"structure.modal_damping = 0.01: modal damping forms a dense C; with 5000 DOFs"});
}

TEST_F(MatrixMarketFiles, ModalDampingGivesEveryModeTheRatio) {
  write("k.mtx", kStiffness);
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 2\n3 3 3\n");
  const Scene s = loadScene(write("s.toml", scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"\nmodal_damping = 0.03")));
  const auto& st = s.model.structure;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(st.stiffness, st.mass);
  const Eigen::MatrixXd modal = modes.eigenvectors().transpose() * st.damping * modes.eigenvectors();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(modal(i, i), 2 * 0.03 * std::sqrt(modes.eigenvalues()[i]), 1e-12);
    for (int j = 0; j < 3; ++j)
      if (j != i) {
        EXPECT_NEAR(modal(i, j), 0.0, 1e-12);
      }
  }
}

TEST_F(MatrixMarketFiles, ForcingFromAVectorFileScalesItsEntries) {
  write("k.mtx", kStiffness);
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 2\n3 3 3\n");
  write("f.mtx", "%%MatrixMarket matrix array real general\n3 1\n0\n2\n-1\n");
  std::string text = scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"");
  text.replace(text.find("dof = 1\ncos = 2.0"), 17, "file = \"f.mtx\"\ncos = 3.0\nsin = 1.0");
  const Scene s = loadScene(write("s.toml", text));
  const auto& loads = s.model.structure.loads;
  ASSERT_EQ(loads.size(), 2u);
  EXPECT_EQ(loads[0].dof, 1);
  EXPECT_DOUBLE_EQ(loads[0].cos_amplitude, 6.0);
  EXPECT_DOUBLE_EQ(loads[1].sin_amplitude, -1.0);
  write("f4.mtx", "%%MatrixMarket matrix array real general\n4 1\n0\n2\n-1\n1\n");
  text.replace(text.find("f.mtx"), 5, "f4.mtx");
  expectError([&] { loadScene(write("s4.toml", text)); }, {"forcing[0].file", "4 entries, the structure has 3"});
}

TEST_F(MatrixMarketFiles, SceneErrorsNameTheFileOrTheField) {
  write("k.mtx", kStiffness);
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 2\n3 3 3\n");
  write("m2.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 2\n");
  const std::string k_asym =
      write("ka.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 5\n1 1 2\n2 1 -1\n1 2 -1.001\n2 2 1\n3 3 1\n");
  expectError([&] { loadScene(write("a.toml", scene("mass = \"m.mtx\"\nstiffness = \"nope.mtx\""))); },
              {"nope.mtx", "cannot open"});
  expectError([&] { loadScene(write("b.toml", scene("mass = \"m2.mtx\"\nstiffness = \"k.mtx\""))); },
              {"k.mtx", "is 3 x 3, the mass matrix is 2 x 2"});
  expectError([&] { loadScene(write("c.toml", scene("mass = \"m.mtx\"\nstiffness = \"ka.mtx\""))); },
              {k_asym, "not symmetric", "= 0.0005", "relative tolerance 1e-08"});
  // The same file passes with a looser tolerance.
  EXPECT_NO_THROW(loadScene(write("c2.toml", scene("mass = \"m.mtx\"\nstiffness = \"ka.mtx\"\nsymmetry_tolerance = 1e-3"))));
  expectError([&] { loadScene(write("d.toml", scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"", "4"))); },
              {"law[0].dofs = 4", "no such DOF (the structure has 3"});
  expectError([&] {
    loadScene(write("e.toml", scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"\ndamping = \"k.mtx\"\nrayleigh = [0, 1]")));
  }, {"structure.damping", "one damping model"});
}

TEST_F(MatrixMarketFiles, MasslessContactDofHeldByAStiffnessSolvesInBothSystems) {
  write("k.mtx", kStiffness);
  // DOF 3 carries no mass (a contact node on a spring): allowed.
  write("m.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 2\n1 1 1\n2 2 1\n");
  const Scene s = loadScene(write("s.toml", scene("mass = \"m.mtx\"\nstiffness = \"k.mtx\"\nrayleigh = [0.02, 0.0]")));
  // Condensed and full systems converge to the same solution.
  CondensedSystem condensed(s.model);
  FullSystem full(s.model);
  EXPECT_EQ(condensed.size(), 6);
  EXPECT_EQ(full.size(), 24);
  const auto rc = makeSolver("dogleg")->solve(condensed, Eigen::VectorXd::Zero(6), SolverOptions());
  const auto rf = makeSolver("dogleg")->solve(full, Eigen::VectorXd::Zero(24), SolverOptions());
  ASSERT_TRUE(rc.converged()) << rc.summary();
  ASSERT_TRUE(rf.converged()) << rf.summary();
  const Eigen::VectorXd zc = condensed.fullCoefficients(rc.solution);
  EXPECT_LT((zc - rf.solution).norm(), 1e-8 * zc.norm());
  // Friction sticks part of the period: the force is not zero and |λ| <= μN.
  EXPECT_GT(rc.solution.norm(), 0.1);
  // A massless DOF not held by the stiffness makes the system singular: refused.
  write("k0.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 2\n2 1 -1\n2 2 1\n");
  expectError([&] { loadScene(write("t.toml", scene("mass = \"m.mtx\"\nstiffness = \"k0.mtx\""))); },
              {"k0.mtx", "massless DOF", "first DOF 3", "not regular"});
  write("mn.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 -1\n3 3 1\n");
  expectError([&] { loadScene(write("u.toml", scene("mass = \"mn.mtx\"\nstiffness = \"k.mtx\""))); },
              {"mn.mtx", "negative mass direction"});
}

}  // namespace
}  // namespace eqhb
