// The eigenvalues of a Hill pencil nearest a shift σ, as ν = 1/(s − σ) of
// the operator E (A − σB)⁻¹ B̃ (hill_stability.h): dense by a real Schur form
// and inverse iteration for small pencils, sparse by Spectra's Arnoldi
// solver (shift-invert) for large ones. σ = 0 first; where A − σB is
// singular (a fold exactly at the point, or a degenerate law Jacobian) a
// small shift in units of ω is tried instead.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <complex>
#include <string>

#include "eqhb/stability/dense_eigenproblem.h"
#include "eqhb/stability/hill_pencil.h"

namespace eqhb {

struct HillSpectrum {
  Eigen::VectorXcd values;   // ν = 1/(s − σ)
  Eigen::MatrixXcd vectors;  // E u, or its displacement rows only
  double shift = 0.0;        // σ
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
  bool operator()(std::complex<double> nu) const {
    return std::abs(nu) > 1e-11 * largest && std::abs(shift + 1.0 / nu) <= limit;
  }
};

// The largest modulus of `values` (0 for none).
double largestModulus(const Eigen::VectorXcd& values);

// Every eigenvalue, with the vectors of the finite ones (exponent_limit on
// |s|, FiniteExponent). False, with *failure set, if A − σB is singular at
// every shift tried or the Schur iteration fails.
bool denseHillSpectrum(const HillPencil& pencil, double omega, double exponent_limit, DenseEigenproblem& solver,
                       HillSpectrum* out, std::string* failure);

// J's LU for the sparse path at σ = 0, whose symbolic analysis (J's pattern
// is the full system's, fixed) is made at the first use and kept.
struct JacobianLu {
  Eigen::SparseLU<SparseMatrix> lu;
  bool analysed = false;
};

// The `wanted` eigenvalues of largest |ν| (the exponents nearest σ), with
// the displacement rows of their vectors; `jacobian` is J, the top-left
// block of A. False, with *failure set, if every shift fails.
bool sparseHillSpectrum(const HillPencil& pencil, double omega, int wanted, const SparseMatrix& jacobian,
                        JacobianLu& jacobian_lu, HillSpectrum* out, std::string* failure);

}  // namespace eqhb
