#include "eqhb/harmonic_balance/dynamic_stiffness_factors.h"

#include <Eigen/UmfPackSupport>
#include <chrono>
#include <complex>
#include <stdexcept>

#include "eqhb/error.h"

namespace eqhb {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Eigen's wrapper keeps UMFPACK's Info array to itself; the condition
// estimate and the size of the factors live there.
// UMFPACK refines each solve iteratively by default (up to two more
// residuals and solves per right-hand side): on the condensation's many
// right-hand sides (one per law component and harmonic, at every ω of a
// sweep) that was a quarter of beam-joint-large's sweep in a profile (its
// 21 points from ω = 3 to 3.2: 15.1 -> 13.1 s without it), for digits the
// LU with its own pivoting already gives (rcond checked below).
template <typename Matrix>
class UmfPackLU : public Eigen::UmfPackLU<Matrix> {
 public:
  UmfPackLU() { this->umfpackControl()(UMFPACK_IRSTEP) = 0; }
  double statistic(int field) const { return this->m_umfpackInfo[field]; }
};

using Complex = std::complex<double>;
using ComplexSparseMatrix = Eigen::SparseMatrix<Complex>;

// `m`'s values on the pattern `p` (a superset of m's entries, both compressed
// and sorted): one value per entry of p, zero where m has none.
Eigen::VectorXd valuesOnPattern(const SparseMatrix& p, const SparseMatrix& m) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(p.nonZeros() + m.nonZeros());
  for (const SparseMatrix* source : {&p, &m}) {
    const double scale = source == &p ? 0.0 : 1.0;
    for (int j = 0; j < source->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*source, j); it; ++it) entries.emplace_back(it.row(), j, scale * it.value());
  }
  SparseMatrix on(p.rows(), p.cols());
  on.setFromTriplets(entries.begin(), entries.end());
  on.makeCompressed();
  if (on.nonZeros() != p.nonZeros()) throw std::logic_error("a structure matrix has entries outside its pattern");
  return Eigen::Map<const Eigen::VectorXd>(on.valuePtr(), on.nonZeros());
}

// Below this reciprocal condition estimate A_k counts as singular.
constexpr double kSingularRcond = 1e-13;

std::runtime_error singular(int k, double omega, double rcond) {
  return std::runtime_error("condensation impossible: the dynamic stiffness of harmonic " +
                            std::to_string(k) + " is singular at omega = " + formatNumber(omega) +
                            " (rcond " + formatNumber(rcond) + "); use the full system");
}

// Where a factorisation is, for a time limit's message.
std::string factorisationStep(const std::vector<int>& harmonics, int h) {
  return "numeric factorisation of A_k, harmonic " + std::to_string(harmonics[h]) + " (" + std::to_string(h) +
         " of " + std::to_string(harmonics.size()) + " done)";
}
}  // namespace

// A harmonic k > 0 acts on the pair (a, b) of x = a cos kωt + b sin kωt
// through the real 2n x 2n block [[D, kωC], [-kωC, D]], D = K - (kω)² M.
// That block is the complex n x n A = D + i kωC acting on a - i b: the load
// (f_c, f_s) becomes f_c - i f_s and the response a = Re X, b = -Im X. The
// complex LU of A has half the order of the real block's and factors and
// solves faster (measured figures in the commit that made it). The static
// harmonic (k = 0) is K, real.
struct DynamicStiffnessFactors::Sparse {
  SparseMatrix pattern;                          // the union of K, M and C, compressed
  Eigen::VectorXd k_values, m_values, c_values;  // K, M, C on that pattern
  // Per harmonic of the basis: the static one in `real_*`, the others in `complex_*`.
  std::vector<SparseMatrix> real_operators;
  std::vector<ComplexSparseMatrix> complex_operators;  // pattern fixed; the LU refers to them
  std::vector<std::unique_ptr<UmfPackLU<SparseMatrix>>> real_lu;
  std::vector<std::unique_ptr<UmfPackLU<ComplexSparseMatrix>>> complex_lu;

  // The values of A_k at ω into its operator (k = 0: K, whatever ω).
  void setValues(int h, int k, double omega, const LinearStructure& structure) {
    if (k == 0) {
      real_operators[h] = structure.stiffness;
      real_operators[h].makeCompressed();
      return;
    }
    const double kw = k * omega;
    Complex* a = complex_operators[h].valuePtr();
    for (Eigen::Index e = 0; e < pattern.nonZeros(); ++e)
      a[e] = Complex(k_values[e] - kw * kw * m_values[e], kw * c_values[e]);
  }
};

DynamicStiffnessFactors::DynamicStiffnessFactors(const LinearStructure& structure,
                                                 const HarmonicSet& basis, bool sparse,
                                                 const Deadline& deadline)
    : harmonics_(basis.harmonics()), sparse_(sparse) {
  if (!sparse_) return;
  const auto start = Clock::now();
  sparse_factors_ = std::make_unique<Sparse>();
  Sparse& s = *sparse_factors_;
  s.pattern = structure.pattern();
  s.pattern.makeCompressed();
  s.k_values = valuesOnPattern(s.pattern, structure.stiffness);
  s.m_values = valuesOnPattern(s.pattern, structure.mass);
  s.c_values = valuesOnPattern(s.pattern, structure.damping);
  const int harmonics = static_cast<int>(harmonics_.size());
  s.real_operators.resize(harmonics);
  s.complex_operators.resize(harmonics);
  s.real_lu.resize(harmonics);
  s.complex_lu.resize(harmonics);
  for (int h = 0; h < harmonics; ++h) {
    const int k = harmonics_[h];
    deadline.check("set-up: symbolic factorisation of A_k, harmonic " + std::to_string(k) + " (" +
                   std::to_string(h) + " of " + std::to_string(harmonics) + " done)");
    // Any ω gives the pattern; the values are replaced by factorize().
    bool analysed = false;
    if (k == 0) {
      s.setValues(h, k, 1.0, structure);
      s.real_lu[h] = std::make_unique<UmfPackLU<SparseMatrix>>();
      s.real_lu[h]->analyzePattern(s.real_operators[h]);
      analysed = s.real_lu[h]->info() == Eigen::Success;
    } else {
      s.complex_operators[h] = s.pattern.cast<Complex>();
      s.setValues(h, k, 1.0, structure);
      s.complex_lu[h] = std::make_unique<UmfPackLU<ComplexSparseMatrix>>();
      s.complex_lu[h]->analyzePattern(s.complex_operators[h]);
      analysed = s.complex_lu[h]->info() == Eigen::Success;
    }
    if (!analysed) throw std::runtime_error("UMFPACK symbolic analysis failed for harmonic " + std::to_string(k));
  }
  analysis_seconds_ = since(start);
}

DynamicStiffnessFactors::~DynamicStiffnessFactors() = default;
DynamicStiffnessFactors::DynamicStiffnessFactors(DynamicStiffnessFactors&&) noexcept = default;
DynamicStiffnessFactors& DynamicStiffnessFactors::operator=(DynamicStiffnessFactors&&) noexcept =
    default;

void DynamicStiffnessFactors::factorize(const LinearStructure& structure, double omega, const Deadline& deadline) {
  const auto start = Clock::now();
  const int harmonics = static_cast<int>(harmonics_.size());
  double bytes = 0.0;
  if (!sparse_) {
    std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> factors;
    for (int h = 0; h < harmonics; ++h) {
      deadline.check(factorisationStep(harmonics_, h));
      factors.emplace_back(structure.harmonicOperator(harmonics_[h], omega));
      if (!(factors.back().rcond() > kSingularRcond))
        throw singular(harmonics_[h], omega, factors.back().rcond());
      bytes += 8.0 * factors.back().matrixLU().size();
    }
    dense_ = std::move(factors);
  } else {
    Sparse& s = *sparse_factors_;
    for (int h = 0; h < harmonics; ++h) {
      deadline.check(factorisationStep(harmonics_, h));
      // New values on the fixed pattern; the symbolic analysis stays.
      s.setValues(h, harmonics_[h], omega, structure);
      bool factored = false;
      double rcond = 0.0, numeric = 0.0, unit = 0.0;
      auto factor = [&](auto& lu, auto& a) {
        lu.factorize(a);
        factored = lu.info() == Eigen::Success;
        rcond = lu.statistic(UMFPACK_RCOND);
        numeric = lu.statistic(UMFPACK_NUMERIC_SIZE);
        unit = lu.statistic(UMFPACK_SIZE_OF_UNIT);
      };
      if (harmonics_[h] == 0) factor(*s.real_lu[h], s.real_operators[h]);
      else factor(*s.complex_lu[h], s.complex_operators[h]);
      if (!factored || !(rcond > kSingularRcond)) throw singular(harmonics_[h], omega, factored ? rcond : 0.0);
      bytes += numeric * unit;
    }
  }
  factor_bytes_ = bytes;
  factor_seconds_ = since(start);
}

Eigen::MatrixXd DynamicStiffnessFactors::solve(int h, const Eigen::MatrixXd& rhs) const {
  if (!sparse_) return dense_[h].solve(rhs);
  const Sparse& s = *sparse_factors_;
  if (harmonics_[h] == 0) return s.real_lu[h]->solve(rhs);
  // (f_c; f_s) -> f_c - i f_s, and back: a = Re X, b = -Im X.
  const Eigen::Index n = rhs.rows() / 2;
  Eigen::MatrixXcd load(n, rhs.cols());
  load.real() = rhs.topRows(n);
  load.imag() = -rhs.bottomRows(n);
  const Eigen::MatrixXcd x = s.complex_lu[h]->solve(load);
  Eigen::MatrixXd out(rhs.rows(), rhs.cols());
  out.topRows(n) = x.real();
  out.bottomRows(n) = -x.imag();
  return out;
}

}  // namespace eqhb
