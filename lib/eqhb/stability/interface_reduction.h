// A structure reduced to its law DOFs and the fixed-interface modes that
// the monodromy needs (Craig–Bampton): x = T q, q = [x_b; η], with x_b the
// law (boundary) DOFs kept as they are, the interior following them
// statically (Ψ = −K_ii⁻¹ K_ib) plus the retained modes Φ of the interior
// with the boundary held (K_ii φ = ω² M_ii φ, Φᵀ M_ii Φ = I).
//
// A mode is dropped only when it is both fast (ω_k above `fast_rate`, the
// orbit's highest harmonic times a margin) and so damped that its free
// multiplier over the period, e^{−σ_k T} with σ_k = φᵀ C_ii φ / 2, is below
// e^{−decay} (decay = 13.8: 1e-6): such a mode neither resonates with the
// orbit nor carries a multiplier near the unit circle; its static part stays
// in Ψ. With proportional damping (C = αM + βK, β > 0) σ_k grows with ω_k,
// so the kept modes are the lowest ones and only they are computed. Stuck
// or closed law DOFs are boundary DOFs, so holding them is exact in q. An undamped or slightly damped structure keeps every mode (T = I in
// effect, at the full cost).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <optional>
#include <vector>

namespace eqhb {

// A mode faster than this many times the orbit's highest harmonic frequency
// neither resonates with the orbit nor is resolved by its harmonics: both
// the monodromy's and Hill's reductions may drop it (fast_rate below).
constexpr double kResolvedBandMargin = 3.0;

struct InterfaceReduction {
  Eigen::MatrixXd basis;       // T: n x m
  Eigen::MatrixXd projection;  // P: m x n, q = P x (P T = I)
  Eigen::MatrixXd mass, damping, stiffness;  // Tᵀ M T, Tᵀ C T, Tᵀ K T
  std::vector<int> boundary;   // the law DOFs, sorted: q's first entries
  int modes_kept = 0, modes_dropped = 0;
};

// Throws InputError if M or K_ii is not positive definite. On the sparse
// matrices (a structure's own), factorised sparse; the dense form is read as
// sparse.
InterfaceReduction reduceToInterface(const Eigen::SparseMatrix<double>& mass, const Eigen::SparseMatrix<double>& damping,
                                     const Eigen::SparseMatrix<double>& stiffness, std::vector<int> boundary,
                                     double fast_rate, double period, double decay = 13.8);
InterfaceReduction reduceToInterface(const Eigen::MatrixXd& mass, const Eigen::MatrixXd& damping,
                                     const Eigen::MatrixXd& stiffness, std::vector<int> boundary, double fast_rate,
                                     double period, double decay = 13.8);

// The same reduction on the coordinates the laws read rather than on the
// DOFs they touch (law_coordinate_reduction.cpp): a law between two nodes
// reads their relative motion u = wᵀx, one coordinate where the DOFs are
// two. The structure is written in y = E x, with y_p = w_pᵀ x on one pivot
// DOF per direction and every other DOF as it is, and reduced there with
// the y_p as the boundary: q = [u; η], each law's u kept exactly, the rest
// (the pairs' common motion with the interior) following statically plus
// the fixed-interface modes the monodromy needs. On the lap joint the
// boundary is 42 relative coordinates instead of 84 DOFs. `directions`
// (n x b) holds one column per distinct law direction.
struct LawCoordinateReduction {
  InterfaceReduction reduction;  // basis = E⁻¹ T_y and projection = P_y E, in x
  std::vector<int> coordinate;   // per column of `directions`: its place in q
};
// Empty when the directions are linearly dependent; throws InputError when
// the structure with every law coordinate held is not positive definite
// (a body held by its joints alone: the DOF boundary may still hold it).
std::optional<LawCoordinateReduction> reduceToLawCoordinates(const Eigen::MatrixXd& mass,
                                                             const Eigen::MatrixXd& damping,
                                                             const Eigen::MatrixXd& stiffness,
                                                             const Eigen::MatrixXd& directions, double fast_rate,
                                                             double period, double decay = 13.8);

}  // namespace eqhb
