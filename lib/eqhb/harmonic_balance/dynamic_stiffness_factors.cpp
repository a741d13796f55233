#include "eqhb/harmonic_balance/dynamic_stiffness_factors.h"

#include <Eigen/UmfPackSupport>
#include <chrono>
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
class UmfPackLU : public Eigen::UmfPackLU<SparseMatrix> {
 public:
  UmfPackLU() { umfpackControl()(UMFPACK_IRSTEP) = 0; }
  double statistic(int field) const { return m_umfpackInfo[field]; }
};

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

struct DynamicStiffnessFactors::Sparse {
  std::vector<SparseMatrix> operators;  // A_k, pattern fixed; the LU refers to them
  std::vector<std::unique_ptr<UmfPackLU>> lu;
};

DynamicStiffnessFactors::DynamicStiffnessFactors(const LinearStructure& structure,
                                                 const HarmonicSet& basis, bool sparse,
                                                 const Deadline& deadline)
    : harmonics_(basis.harmonics()), sparse_(sparse) {
  if (!sparse_) return;
  const auto start = Clock::now();
  sparse_factors_ = std::make_unique<Sparse>();
  for (int k : harmonics_) {
    deadline.check("set-up: symbolic factorisation of A_k, harmonic " + std::to_string(k) + " (" +
                   std::to_string(sparse_factors_->lu.size()) + " of " + std::to_string(harmonics_.size()) +
                   " done)");
    // Any ω gives the pattern; the values are replaced by factorize().
    sparse_factors_->operators.push_back(structure.harmonicOperatorSparse(k, 1.0));
    sparse_factors_->operators.back().makeCompressed();
    sparse_factors_->lu.push_back(std::make_unique<UmfPackLU>());
    sparse_factors_->lu.back()->analyzePattern(sparse_factors_->operators.back());
    if (sparse_factors_->lu.back()->info() != Eigen::Success)
      throw std::runtime_error("UMFPACK symbolic analysis failed for harmonic " + std::to_string(k));
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
      const SparseMatrix values = structure.harmonicOperatorSparse(harmonics_[h], omega);
      SparseMatrix& a = s.operators[h];
      std::copy(values.valuePtr(), values.valuePtr() + values.nonZeros(), a.valuePtr());
      s.lu[h]->factorize(a);
      const double rcond = s.lu[h]->statistic(UMFPACK_RCOND);
      if (s.lu[h]->info() != Eigen::Success || !(rcond > kSingularRcond))
        throw singular(harmonics_[h], omega, s.lu[h]->info() == Eigen::Success ? rcond : 0.0);
      bytes += s.lu[h]->statistic(UMFPACK_NUMERIC_SIZE) * s.lu[h]->statistic(UMFPACK_SIZE_OF_UNIT);
    }
  }
  factor_bytes_ = bytes;
  factor_seconds_ = since(start);
}

Eigen::MatrixXd DynamicStiffnessFactors::solve(int h, const Eigen::MatrixXd& rhs) const {
  if (!sparse_) return dense_[h].solve(rhs);
  Eigen::MatrixXd x = sparse_factors_->lu[h]->solve(rhs);
  return x;
}

}  // namespace eqhb
