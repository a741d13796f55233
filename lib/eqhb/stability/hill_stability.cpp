#include "eqhb/stability/hill_stability.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>

#include "eqhb/error.h"
#include "eqhb/stability/dense_eigenproblem.h"
#include "eqhb/stability/hill_reduction.h"
#include "eqhb/stability/hill_pencil.h"
#include "eqhb/stability/hill_spectrum.h"

namespace eqhb {

namespace {

using Complex = std::complex<double>;

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

// The exponents s = σ + 1/ν of the finite eigenvalues, with their
// multipliers exp(s T) and centroids; *examined counts every finite one,
// those whose eigenvector has no displacement part (no centroid) are left out.
std::vector<FloquetExponent> finiteExponents(const HbModel& model, const HillSpectrum& spectrum,
                                             int displacement_unknowns, double exponent_limit, int* examined) {
  const double period = 2.0 * M_PI / model.omega;
  const FiniteExponent isFinite{largestModulus(spectrum.values), spectrum.shift, exponent_limit};
  std::vector<FloquetExponent> candidates;
  for (Eigen::Index j = 0; j < spectrum.values.size(); ++j) {
    const Complex nu = spectrum.values[j];
    if (!isFinite(nu)) continue;
    ++*examined;
    FloquetExponent e;
    e.exponent = spectrum.shift + 1.0 / nu;
    e.centroid = centroid(model.basis, model.structure.dofs(), spectrum.vectors.col(j).head(displacement_unknowns));
    if (!std::isfinite(e.centroid)) continue;
    e.multiplier = std::exp(e.exponent * period);
    candidates.push_back(e);
  }
  return candidates;
}

// The selection criterion (header): most central first, one per family, at
// most `count`; returned largest |multiplier| first.
std::vector<FloquetExponent> onePerFamily(const HbModel& model, std::vector<FloquetExponent> candidates, int count) {
  const bool odd = model.basis.kind() == HarmonicKind::kOdd;
  const double quantum = odd ? 2.0 * model.omega : model.omega;  // Ω
  const double reference = odd ? 1.0 : 0.0;                       // r
  std::stable_sort(candidates.begin(), candidates.end(), [&](const auto& x, const auto& y) {
    return std::abs(x.centroid - reference) < std::abs(y.centroid - reference);
  });
  // Copies s and s + i m Ω (m ≠ 0) of one exponent are one family,
  // represented by its most central copy. (A real σ < 0 of an odd basis has
  // its two most central copies at κ = 0 and 2, the same distance from r = 1:
  // no window around r, the family rule decides.)
  auto sameFamily = [&](Complex x, Complex y) {
    const Complex d = x - y;
    const double m = std::round(d.imag() / quantum);
    const double tolerance = 1e-3 * (quantum + std::abs(x.real()));
    return m != 0.0 && std::abs(d.real()) <= tolerance && std::abs(d.imag() - m * quantum) <= tolerance;
  };
  std::vector<FloquetExponent> kept;
  for (const FloquetExponent& e : candidates) {
    if (static_cast<int>(kept.size()) >= count) break;
    bool duplicate = false;
    for (const FloquetExponent& k : kept) duplicate = duplicate || sameFamily(e.exponent, k.exponent);
    if (!duplicate) kept.push_back(e);
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const auto& x, const auto& y) { return std::abs(x.multiplier) > std::abs(y.multiplier); });
  return kept;
}

// The spectral radius and the verdict, or why there is none.
void judge(double unit_tolerance, HillResult* result) {
  if (result->exponents.empty()) {
    result->failure = "no eigenvector centred on the reference harmonic";
    return;
  }
  result->spectral_radius = std::abs(result->exponents.front().multiplier);
  result->stable = result->spectral_radius < 1.0 + unit_tolerance;
}

}  // namespace

// What one model's analyses share from point to point: the pencil's builder
// (its full system's ω set per point), the dense solver's work space and J's
// sparse LU.
struct HillStability::Work {
  Work(const HbModel& m, std::optional<HillReduction> r)
      : reduction(std::move(r)), pencil(reduction ? reduction->model : m) {}
  std::optional<HillReduction> reduction;  // the model the pencil is built on, if reduced
  HillPencilBuilder pencil;
  DenseEigenproblem dense;
  JacobianLu jacobian_lu;  // sparse path, σ = 0
};

namespace {

// The pencil's eigenvalues, dense or sparse by its size (HillOptions).
bool solveSpectrum(HillStability::Work& work, const HillOptions& options, const HillPencil& pencil, double omega,
                   double exponent_limit, HillSpectrum* spectrum, std::string* failure) {
  if (pencil.size > options.dense_limit) {
    const int wanted = options.sparse_eigenvalues > 0 ? options.sparse_eigenvalues : 40;
    return sparseHillSpectrum(pencil, omega, wanted, work.pencil.jacobian(), work.jacobian_lu, spectrum, failure);
  }
  return denseHillSpectrum(pencil, omega, exponent_limit, work.dense, spectrum, failure);
}

}  // namespace

void HillOptions::validate() const {
  if (dense_limit < 0) throwInputError("dense_limit", std::to_string(dense_limit), "must be >= 0");
  if (reduce_above < 0) throwInputError("reduce_above", std::to_string(reduce_above), "must be >= 0 (0: never)");
  if (sparse_eigenvalues < 0)
    throwInputError("sparse_eigenvalues", std::to_string(sparse_eigenvalues), "must be >= 0");
  if (!(unit_tolerance >= 0.0) || !std::isfinite(unit_tolerance))
    throwInputError("unit_tolerance", formatNumber(unit_tolerance), "must be finite and >= 0");
  if (method != "hill" && method != "monodromy" && method != "shooting" && method != "auto")
    throwInputError("stability_method", "\"" + method + "\"", "must be hill, monodromy, shooting or auto");
  if (!(time_limit >= 0.0) || !std::isfinite(time_limit))
    throwInputError("stability_time_limit", formatNumber(time_limit), "must be finite and >= 0 (0: none)");
}

HillStability::HillStability(const HbModel& model, const HillOptions& options) : options_(options) {
  options_.validate();
  model.validate();
  work_ = std::make_unique<Work>(model, reduceForHill(model, options_.reduce_above));
}

HillStability::~HillStability() = default;

HillResult hillStability(const HbModel& model, const Eigen::VectorXd& full, const HillOptions& options) {
  return HillStability(model, options).analyse(model.omega, full);
}

HillResult HillStability::analyse(double omega, const Eigen::VectorXd& full) {
  const auto start = std::chrono::steady_clock::now();
  HillPencilBuilder& builder = work_->pencil;
  builder.setOmega(omega);  // throws InputError naming omega unless finite and > 0
  const HbModel& model = builder.model();
  HillResult result;
  result.state_dimension = 2 * model.structure.dofs();
  const HillPencil& pencil = builder.build(work_->reduction ? work_->reduction->reduce(full) : full);
  result.pencil_size = pencil.size;
  result.sparse = pencil.size > options_.dense_limit;

  HillSpectrum spectrum;
  const double exponent_limit = kLargestExponent * std::max(model.basis.highest(), 1) * model.omega;
  if (solveSpectrum(*work_, options_, pencil, model.omega, exponent_limit, &spectrum, &result.failure)) {
    result.failure.clear();
    std::vector<FloquetExponent> candidates =
        finiteExponents(model, spectrum, pencil.displacement_unknowns, exponent_limit, &result.candidates);
    result.exponents = onePerFamily(model, std::move(candidates), result.state_dimension);
    judge(options_.unit_tolerance, &result);
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
