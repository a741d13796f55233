#include "eqhb/stability/hill_stability.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>
#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/stability/dense_eigenproblem.h"

namespace eqhb {

namespace {

using Complex = std::complex<double>;
using Triplet = Eigen::Triplet<double>;

// The pencil A u = s B u on u = [p; q; w] (see the header), with B kept only
// on its nonzero columns: B = B̃ E, E picking `columns` of u.
struct HillPencil {
  SparseMatrix a, b_columns;   // A (size x size), B̃ (size x columns)
  std::vector<int> columns;    // p first, then w, then q where Ψ depends on λ̇
  int size = 0, displacement_unknowns = 0;
  int jacobian_size = 0;       // n0: A = diag(J, I) with J n0 x n0
};

// Work space of addLawRateBlocks, made once per model: samples per law.
struct LawRateWork {
  std::vector<LawSamples> samples;
  Eigen::VectorXd rate, reading;  // reading: u_a = W_a x, coefficients
  Eigen::MatrixXd block;
  explicit LawRateWork(const HbModel& model)
      : samples(model.laws.size()), rate(model.basis.size()), reading(model.basis.size()),
        block(model.basis.size(), model.basis.size()) {
    for (size_t l = 0; l < model.laws.size(); ++l) samples[l].resize(model.samples, model.laws[l].law->dimension(), model.laws[l].law->historyTermsOn(model.samples));
  }
};

// The law rows' s-terms: P diag(Ψ_v) P and P diag(Ψ_λ̇) P per (a, b).
void addLawRateBlocks(const HbModel& model, FourierTransform& transform, LawRateWork& work,
                      std::vector<Triplet>& b, const Eigen::VectorXd& full, bool* uses_force_rate) {
  const int n = model.structure.dofs(), nb = model.basis.size();
  Eigen::VectorXd& rate = work.rate;
  Eigen::MatrixXd& block = work.block;
  *uses_force_rate = false;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const AttachedLaw& attached = model.laws[l];
    const Law& law = *attached.law;
    const int d = law.dimension();
    LawSamples& samples = work.samples[l];
    for (int a = 0; a < d; ++a) {
      attached.attachment.gatherCoefficients(full.data(), nb, a, work.reading.data());
      const double* x = work.reading.data();
      const double* lambda = full.data() + (n + model.componentIndex(l, a)) * nb;
      transform.synthesize(x, samples.displacement.col(a).data());
      transform.differentiate(x, model.omega, rate.data());
      transform.synthesize(rate.data(), samples.velocity.col(a).data());
      transform.synthesize(lambda, samples.force.col(a).data());
      transform.differentiate(lambda, model.omega, rate.data());
      transform.synthesize(rate.data(), samples.force_rate.col(a).data());
    }
    law.evaluate(samples, true);
    for (int a = 0; a < d; ++a) {
      const int row = (n + model.componentIndex(l, a)) * nb;
      for (int bi = 0; bi < d; ++bi) {
        const int ab = a * d + bi;
        if (law.usesVelocity()) {
          transform.gram(samples.dpsi_dvelocity.col(ab).data(), block);
          for (int c = 0; c < nb; ++c)
            for (int r = 0; r < nb; ++r)
              if (block(r, c) != 0.0)
                for (const AttachmentTerm& term : attached.attachment.row(bi))
                  b.emplace_back(row + r, term.dof * nb + c, -(term.weight * block(r, c)));
        }
        if (law.usesForceRate()) {
          *uses_force_rate = true;
          transform.gram(samples.dpsi_dforce_rate.col(ab).data(), block);
          const int lambda_b = (n + model.componentIndex(l, bi)) * nb;
          for (int c = 0; c < nb; ++c)
            for (int r = 0; r < nb; ++r)
              if (block(r, c) != 0.0) b.emplace_back(row + r, lambda_b + c, -block(r, c));
        }
      }
    }
  }
}

}  // namespace

// What one model's analyses share from point to point: the full system (its
// ω set per point) and its Jacobian pattern, the Fourier transform of the law
// rows, the triplet lists and the dense solver's work space.
struct HillStability::Work {
  explicit Work(const HbModel& m)
      : system(m), jacobian(system.jacobianPattern()), g(system.size()), transform(m.basis, m.samples),
        law_rates(m) {}
  FullSystem system;  // its model's ω the current point's
  SparseMatrix jacobian;
  Eigen::VectorXd g;
  FourierTransform transform;
  LawRateWork law_rates;
  std::vector<Triplet> a, b, b_kept;
  HillPencil pencil;
  DenseEigenproblem dense;
  Eigen::SparseLU<SparseMatrix> jacobian_lu;  // sparse path, σ = 0
  bool jacobian_analysed = false;
};

namespace {

void buildPencil(HillStability::Work& work, const Eigen::VectorXd& full) {
  FullSystem& system = work.system;
  const HbModel& model = system.model();
  const int n = model.structure.dofs(), nb = model.basis.size();
  const int n0 = system.size(), nx = n * nb;
  if (full.size() != n0)
    throwInputError("solution", std::to_string(full.size()) + " coefficients",
                    "must have " + std::to_string(n0) + " ([x; lambda] of the full system)");
  SparseMatrix& jacobian = work.jacobian;
  system.residualAndSparseJacobian(full, work.g, jacobian);

  HillPencil& pencil = work.pencil;
  pencil.size = n0 + nx;
  pencil.displacement_unknowns = nx;
  pencil.jacobian_size = n0;
  pencil.columns.clear();
  std::vector<Triplet>& a = work.a;
  std::vector<Triplet>& b = work.b;
  a.clear();
  b.clear();
  a.reserve(jacobian.nonZeros() + nx);
  for (int j = 0; j < jacobian.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(jacobian, j); it; ++it) a.emplace_back(it.row(), j, it.value());
  for (int i = 0; i < nx; ++i) a.emplace_back(n0 + i, n0 + i, 1.0);

  // Dynamics rows: J p + s (C ⊗ I + 2 M ⊗ D) p + s (M ⊗ I) w = 0, so B
  // holds −(C ⊗ I + 2 M ⊗ D) on p and −M ⊗ I on w.
  const auto& ks = model.basis.harmonics();
  const LinearStructure& st = model.structure;
  for (int j = 0; j < st.damping.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(st.damping, j); it; ++it)
      for (int t = 0; t < nb; ++t) b.emplace_back(it.row() * nb + t, j * nb + t, -it.value());
  for (int j = 0; j < st.mass.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(st.mass, j); it; ++it) {
      const int row = static_cast<int>(it.row()) * nb, col = j * nb;
      for (int t = 0; t < nb; ++t) b.emplace_back(row + t, n0 + col + t, -it.value());
      // D on (a, b) of harmonic k: (kω b, −kω a).
      for (size_t h = 0; h < ks.size(); ++h) {
        if (ks[h] == 0) continue;
        const int o = model.basis.offset(static_cast<int>(h));
        const double kw = ks[h] * model.omega;
        b.emplace_back(row + o, col + o + 1, -2.0 * it.value() * kw);
        b.emplace_back(row + o + 1, col + o, 2.0 * it.value() * kw);
      }
    }
  bool force_rate = false;
  addLawRateBlocks(model, work.transform, work.law_rates, b, full, &force_rate);
  // Identity rows: w − s p = 0.
  for (int i = 0; i < nx; ++i) b.emplace_back(n0 + i, i, 1.0);

  for (int i = 0; i < nx; ++i) pencil.columns.push_back(i);
  for (int i = 0; i < nx; ++i) pencil.columns.push_back(n0 + i);
  if (force_rate)
    for (int i = nx; i < n0; ++i) pencil.columns.push_back(i);
  std::vector<int> position(pencil.size, -1);
  for (size_t c = 0; c < pencil.columns.size(); ++c) position[pencil.columns[c]] = static_cast<int>(c);
  std::vector<Triplet>& b_kept = work.b_kept;
  b_kept.clear();
  b_kept.reserve(b.size());
  for (const Triplet& e : b)
    if (position[e.col()] >= 0) b_kept.emplace_back(e.row(), position[e.col()], e.value());

  pencil.a.resize(pencil.size, pencil.size);
  pencil.a.setFromTriplets(a.begin(), a.end());
  pencil.b_columns.resize(pencil.size, static_cast<int>(pencil.columns.size()));
  pencil.b_columns.setFromTriplets(b_kept.begin(), b_kept.end());
}

// κ of an eigenvector's displacement part (header).
double centroid(const HarmonicSet& basis, int dofs, const Eigen::Ref<const Eigen::VectorXcd>& u) {
  const int nb = basis.size();
  const auto& ks = basis.harmonics();
  double weight = 0.0, moment = 0.0;
  for (int i = 0; i < dofs; ++i)
    for (size_t h = 0; h < ks.size(); ++h) {
      const int o = i * nb + basis.offset(static_cast<int>(h));
      if (ks[h] == 0) {
        weight += std::norm(u[o]);
        continue;
      }
      const Complex a = u[o], b = u[o + 1], i_unit(0.0, 1.0);
      const double plus = std::norm((a - i_unit * b) * 0.5), minus = std::norm((a + i_unit * b) * 0.5);
      weight += plus + minus;
      moment += ks[h] * (plus - minus);
    }
  return weight > 0.0 ? moment / weight : NAN;
}

// u ↦ E (A − σB)⁻¹ B̃ u through a sparse LU, for Spectra. With `solved` =
// n0 (σ = 0, A = diag(J, I)) the LU is J's: the top n0 rows of the solution
// are J⁻¹ times those of B̃ u, the rest B̃ u itself; with `solved` = the
// pencil's size it is the LU of A − σB.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const HillPencil& pencil, const Eigen::SparseLU<SparseMatrix>& lu, int solved)
      : pencil_(pencil), lu_(lu), solved_(solved), rhs_(pencil.size), solution_(pencil.size) {}
  Eigen::Index rows() const { return static_cast<Eigen::Index>(pencil_.columns.size()); }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* in, double* out) const {
    rhs_.noalias() = pencil_.b_columns * Eigen::Map<const Eigen::VectorXd>(in, rows());
    solution_.head(solved_) = lu_.solve(rhs_.head(solved_));
    for (Eigen::Index c = 0; c < rows(); ++c) {
      const int r = pencil_.columns[c];
      out[c] = r < solved_ ? solution_[r] : rhs_[r];
    }
  }

 private:
  const HillPencil& pencil_;
  const Eigen::SparseLU<SparseMatrix>& lu_;
  const int solved_;
  mutable Eigen::VectorXd rhs_, solution_;
};

// Spectra's solver, whose eigenvectors are asked for their leading rows only
// (the displacement part that the centroid reads) and formed by two real
// products V·Re + i V·Im instead of one mixed real-complex product.
class HillArnoldi : public Spectra::GenEigsSolver<ShiftInvertOperator> {
 public:
  using Spectra::GenEigsSolver<ShiftInvertOperator>::GenEigsSolver;
  // Rows [0, rows) of the Ritz vectors; valid after a successful compute()
  // (all nev converged, in eigenvalues()' order).
  Eigen::MatrixXcd leadingRows(Eigen::Index rows) const {
    const auto v = m_fac.matrix_V().topRows(rows);
    const Eigen::MatrixXd re = v * m_ritz_vec.real(), im = v * m_ritz_vec.imag();
    Eigen::MatrixXcd out(rows, m_nev);
    out.real() = re;
    out.imag() = im;
    return out;
  }
};

// ν = 1/(s − σ) = 0 is an infinite exponent (a constraint), not a Floquet
// one. In rounding it is not exactly 0: where sticking or a closed contact
// constrains displacements, the infinite eigenvalues are defective (index 2
// or 3) and come out at |ν| of about ε^{1/k} of the largest, that is at |s|
// of 7e6–1e10 ω on the damper and planar-friction scenes, while the finite
// exponents of the truncated problem lie within a few hundred ω (harmonics
// up to k_max, the structure's own frequencies). So an eigenvalue is taken as
// infinite when |ν| is below 1e-11 of the largest |ν| of the spectrum or
// |s| exceeds kLargestExponent · max(k_max, 1) · ω.
constexpr double kLargestExponent = 1e5;
struct FiniteExponent {
  double largest = 0.0;  // the largest |ν|
  double shift = 0.0;    // σ
  double limit = 0.0;    // on |s|
  bool operator()(Complex nu) const {
    return std::abs(nu) > 1e-11 * largest && std::abs(shift + 1.0 / nu) <= limit;
  }
};

double largestModulus(const Eigen::VectorXcd& values) {
  double largest = 0.0;
  for (Eigen::Index j = 0; j < values.size(); ++j) largest = std::max(largest, std::abs(values[j]));
  return largest;
}

struct Spectrum {
  Eigen::VectorXcd values;   // ν = 1/(s − σ)
  Eigen::MatrixXcd vectors;  // E u, or its displacement rows only
  double shift = 0.0;
};

// Shifts tried in turn where A − σB is singular (a fold exactly at the
// point, or a degenerate law Jacobian): σ in units of ω.
constexpr double kShifts[] = {0.0, -0.0137, 0.0291};

bool denseSpectrum(const HillPencil& pencil, double omega, double exponent_limit, DenseEigenproblem& solver,
                   Spectrum* out, std::string* failure) {
  const Eigen::MatrixXd b_columns = Eigen::MatrixXd(pencil.b_columns);
  const int n0 = pencil.jacobian_size, m = static_cast<int>(pencil.columns.size());
  Eigen::MatrixXd reduced(m, m);
  for (double shift : kShifts) {
    const double sigma = shift * omega;
    if (sigma == 0.0) {
      // A = diag(J, I): J [p; q] = (B̃ x) on the top n0 rows and w = (B̃ x)
      // on the rest, so only J is factorised (n0 of the pencil's unknowns).
      // Singular as diag(J, I) would be judged: rcond(A) from J's with
      // ‖A‖₁ = max(‖J‖₁, 1) and ‖A⁻¹‖₁ = max(‖J⁻¹‖₁, 1).
      const Eigen::MatrixXd j = Eigen::MatrixXd(pencil.a.topLeftCorner(n0, n0));
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(j);
      const double norm = j.cwiseAbs().colwise().sum().maxCoeff();
      const double inverse_norm = 1.0 / (lu.rcond() * norm);
      if (!(1.0 / (std::max(norm, 1.0) * std::max(inverse_norm, 1.0)) > 1e-14)) continue;
      const Eigen::MatrixXd solved = lu.solve(b_columns.topRows(n0));
      for (int c = 0; c < m; ++c) {
        const int r = pencil.columns[c];
        reduced.row(c) = r < n0 ? solved.row(r) : b_columns.row(r);
      }
    } else {
      // Only here (J singular) are the whole A and B needed dense.
      Eigen::MatrixXd a_shifted = Eigen::MatrixXd(pencil.a);
      for (size_t c = 0; c < pencil.columns.size(); ++c) a_shifted.col(pencil.columns[c]) -= sigma * b_columns.col(c);
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a_shifted);
      if (!(lu.rcond() > 1e-14)) continue;
      const Eigen::MatrixXd solved = lu.solve(b_columns);
      for (int c = 0; c < m; ++c) reduced.row(c) = solved.row(pencil.columns[c]);
    }
    if (!solver.compute(reduced)) continue;
    out->values = solver.eigenvalues();
    // Vectors of the finite eigenvalues only, the candidates.
    std::vector<int> finite;
    const FiniteExponent isFinite{largestModulus(out->values), sigma, exponent_limit};
    for (Eigen::Index j = 0; j < out->values.size(); ++j)
      if (isFinite(out->values[j])) finite.push_back(static_cast<int>(j));
    Eigen::MatrixXcd vectors;
    solver.eigenvectors(finite, &vectors);
    out->vectors.setZero(reduced.rows(), reduced.cols());
    for (size_t c = 0; c < finite.size(); ++c) out->vectors.col(finite[c]) = vectors.col(c);
    out->shift = sigma;
    return true;
  }
  *failure = "the Hill pencil is singular at every shift tried";
  return false;
}

// `jacobian` is J (the top-left block of A), `jacobian_lu` its LU, whose
// symbolic analysis (J's pattern is the full system's, fixed) is made at the
// first call (*analysed false) and kept.
bool sparseSpectrum(const HillPencil& pencil, double omega, int wanted, const SparseMatrix& jacobian,
                    Eigen::SparseLU<SparseMatrix>& jacobian_lu, bool* analysed, Spectrum* out,
                    std::string* failure) {
  SparseMatrix b(pencil.size, pencil.size);
  {
    std::vector<Triplet> entries;
    for (int c = 0; c < pencil.b_columns.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(pencil.b_columns, c); it; ++it)
        entries.emplace_back(it.row(), pencil.columns[c], it.value());
    b.setFromTriplets(entries.begin(), entries.end());
  }
  const int m = static_cast<int>(pencil.columns.size());
  const int nev = std::clamp(wanted, 1, m - 2);
  const int ncv = std::min(m, std::max(2 * nev + 1, nev + 20));
  for (double shift : kShifts) {
    const double sigma = shift * omega;
    Eigen::SparseLU<SparseMatrix> shifted_lu;
    const Eigen::SparseLU<SparseMatrix>* lu = &jacobian_lu;
    int solved = pencil.jacobian_size;
    if (sigma == 0.0) {
      if (!*analysed) jacobian_lu.analyzePattern(jacobian);
      *analysed = true;
      jacobian_lu.factorize(jacobian);
      if (jacobian_lu.info() != Eigen::Success) continue;
    } else {
      SparseMatrix shifted = pencil.a - sigma * b;
      shifted.makeCompressed();
      shifted_lu.compute(shifted);
      if (shifted_lu.info() != Eigen::Success) continue;
      lu = &shifted_lu;
      solved = pencil.size;
    }
    ShiftInvertOperator op(pencil, *lu, solved);
    HillArnoldi solver(op, nev, ncv);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
    if (solver.info() != Spectra::CompInfo::Successful) {
      *failure = "the Arnoldi solver did not converge";
      continue;
    }
    out->values = solver.eigenvalues();
    out->vectors = solver.leadingRows(pencil.displacement_unknowns);
    out->shift = sigma;
    return true;
  }
  if (failure->empty()) *failure = "the Hill pencil is singular at every shift tried";
  return false;
}

}  // namespace

void HillOptions::validate() const {
  if (dense_limit < 0) throwInputError("dense_limit", std::to_string(dense_limit), "must be >= 0");
  if (sparse_eigenvalues < 0)
    throwInputError("sparse_eigenvalues", std::to_string(sparse_eigenvalues), "must be >= 0");
  if (!(unit_tolerance >= 0.0) || !std::isfinite(unit_tolerance))
    throwInputError("unit_tolerance", formatNumber(unit_tolerance), "must be finite and >= 0");
  if (method != "hill" && method != "monodromy" && method != "auto")
    throwInputError("stability_method", "\"" + method + "\"", "must be hill, monodromy or auto");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throwInputError("stability_time_limit", formatNumber(time_limit), "must be finite and >= 0 (0: none)");
}

HillStability::HillStability(const HbModel& model, const HillOptions& options) : options_(options) {
  options_.validate();
  model.validate();
  work_ = std::make_unique<Work>(model);
}

HillStability::~HillStability() = default;

HillResult hillStability(const HbModel& model, const Eigen::VectorXd& full, const HillOptions& options) {
  return HillStability(model, options).analyse(model.omega, full);
}

HillResult HillStability::analyse(double omega, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  const HillOptions& options = options_;
  work_->system.setOmega(omega);  // throws InputError naming omega unless finite and > 0
  const HbModel& model = work_->system.model();
  HillResult result;
  const int n = model.structure.dofs();
  result.state_dimension = 2 * n;
  buildPencil(*work_, full);
  const HillPencil& pencil = work_->pencil;
  result.pencil_size = pencil.size;
  result.sparse = pencil.size > options.dense_limit;

  Spectrum spectrum;
  const int wanted = options.sparse_eigenvalues > 0 ? options.sparse_eigenvalues : 40;
  const double exponent_limit = kLargestExponent * std::max(model.basis.highest(), 1) * model.omega;
  const bool ok = result.sparse ? sparseSpectrum(pencil, model.omega, wanted, work_->jacobian, work_->jacobian_lu,
                                                 &work_->jacobian_analysed, &spectrum, &result.failure)
                                : denseSpectrum(pencil, model.omega, exponent_limit, work_->dense, &spectrum,
                                                &result.failure);
  if (ok) {
    result.failure.clear();
    const bool odd = model.basis.kind() == HarmonicKind::kOdd;
    const double quantum = odd ? 2.0 * model.omega : model.omega;  // Ω
    const double reference = odd ? 1.0 : 0.0;                       // r
    const double period = 2.0 * M_PI / model.omega;
    const FiniteExponent isFinite{largestModulus(spectrum.values), spectrum.shift, exponent_limit};
    std::vector<FloquetExponent> candidates;
    for (Eigen::Index j = 0; j < spectrum.values.size(); ++j) {
      const Complex nu = spectrum.values[j];
      if (!isFinite(nu)) continue;
      ++result.candidates;
      FloquetExponent e;
      e.exponent = spectrum.shift + 1.0 / nu;
      e.centroid = centroid(model.basis, n, spectrum.vectors.col(j).head(pencil.displacement_unknowns));
      if (!std::isfinite(e.centroid)) continue;
      e.multiplier = std::exp(e.exponent * period);
      candidates.push_back(e);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [&](const auto& x, const auto& y) {
      return std::abs(x.centroid - reference) < std::abs(y.centroid - reference);
    });
    // Most central first; copies s and s + i m Ω (m ≠ 0) of one exponent
    // are one family, represented by its most central copy. (A real σ < 0
    // of an odd basis has its two most central copies at κ = 0 and 2, the
    // same distance from r = 1: no window around r, the family rule decides.)
    auto sameFamily = [&](Complex x, Complex y) {
      const Complex d = x - y;
      const double m = std::round(d.imag() / quantum);
      const double tolerance = 1e-3 * (quantum + std::abs(x.real()));
      return m != 0.0 && std::abs(d.real()) <= tolerance && std::abs(d.imag() - m * quantum) <= tolerance;
    };
    for (const FloquetExponent& e : candidates) {
      if (static_cast<int>(result.exponents.size()) >= result.state_dimension) break;
      bool duplicate = false;
      for (const FloquetExponent& kept : result.exponents) duplicate = duplicate || sameFamily(e.exponent, kept.exponent);
      if (!duplicate) result.exponents.push_back(e);
    }
    std::stable_sort(result.exponents.begin(), result.exponents.end(), [](const auto& x, const auto& y) {
      return std::abs(x.multiplier) > std::abs(y.multiplier);
    });
    if (result.exponents.empty()) {
      result.failure = "no eigenvector centred on the reference harmonic";
    } else {
      result.spectral_radius = std::abs(result.exponents.front().multiplier);
      result.stable = result.spectral_radius < 1.0 + options.unit_tolerance;
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

namespace {
constexpr double kRealAngle = 1e-4;  // rad
}  // namespace

int unstableMultipliers(const HillResult& result, double unit_tolerance) {
  int count = 0;
  for (const FloquetExponent& e : result.exponents) count += std::abs(e.multiplier) >= 1.0 + unit_tolerance;
  return count;
}

std::string bifurcationKind(const HillResult& before, const HillResult& after, double unit_tolerance) {
  if (before.exponents.empty() || after.exponents.empty()) return "";
  // Multipliers outside the unit circle, by kind: real > 0, real < 0, complex.
  auto census = [&](const HillResult& r) {
    std::array<int, 3> count{0, 0, 0};
    for (const FloquetExponent& e : r.exponents) {
      if (std::abs(e.multiplier) < 1.0 + unit_tolerance) continue;
      // A real multiplier comes from an exponent whose imaginary part is a
      // multiple of ω/2, up to the eigensolver's accuracy (~1e-6 rad); a
      // complex pair leaving the circle has a visibly nonzero argument.
      const double angle = std::abs(std::arg(e.multiplier));
      ++count[angle <= kRealAngle ? 0 : angle >= M_PI - kRealAngle ? 1 : 2];
    }
    return count;
  };
  const auto b = census(before), a = census(after);
  if (b[0] + b[1] + b[2] == a[0] + a[1] + a[2]) return "";
  if (a[0] != b[0]) return "fold";
  if (a[1] != b[1]) return "period-doubling";
  return "neimark-sacker";
}

}  // namespace eqhb
