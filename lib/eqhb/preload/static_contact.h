// The static contact problem under constant loads (a bolt's preload), solved
// before the dynamic one (spec §1 at rest, ẍ = ẋ = 0):
//
//   K x − Σ_l W_lᵀ (s_l λ_l) = F₀,    Ψ_l(W_l x, v_l, λ_l, λ̇_l) = 0,
//
// F₀ the model's constant loads (harmonic 0). Each law is seen in one
// implicit step of unit length from the unloaded rest (x = 0, λ = 0): a
// rate-independent friction (Law::rateIndependent) reads the increments
// v = W x and λ̇ = λ, so it sticks where it was at rest unless the load makes
// it slip; other laws read v = λ̇ = 0 (a damper adds no static force). A
// history law (Law::anchoredAt) is its copy anchored at rest.
//
// The answer (StaticContactState) gives the gaps, normal forces and friction
// states per element, the operating point of the dynamic solve
// (operating_point.h).
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/solvers/solver.h"

namespace eqhb {

struct StaticContactState {
  SolverResult result;
  std::string solver;            // the backend that converged
  std::vector<std::string> failed;  // "NAME: termination" of those tried before it
  Eigen::VectorXd displacement;  // x (n)
  Eigen::VectorXd forces;        // λ of every law, in HbModel::componentIndex order
  // Per law: its state at rest (Law::staticStatus; nullopt for a law that
  // is not a contact or a friction).
  std::vector<std::optional<StaticStatus>> status;
  // Law l's inputs at rest on one sample (what staticStatus and anchoredAt read).
  std::vector<LawSamples> rest;
};

class StaticContactSystem : public SquareSystem {
 public:
  // `model`'s structure, laws and constant loads; throws InputError naming
  // "preload" when there is nothing to hold (no constant load).
  explicit StaticContactSystem(const HbModel& model);
  int size() const override { return size_; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  // Structure rows in the force scale, law rows in each law's own.
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;
  const Eigen::VectorXd& load() const { return load_; }  // F₀
  // The laws' inputs at z on one sample each, as the static step reads them.
  std::vector<LawSamples> restSamples(const Eigen::Ref<const Eigen::VectorXd>& z);

 private:
  void fill(const Eigen::Ref<const Eigen::VectorXd>& z, bool with_derivatives);
  // g from the filled samples.
  bool writeResidual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g);
  HbModel model_;                               // with ρ scale-free from K
  std::vector<std::shared_ptr<Law>> step_laws_;  // each law's static step
  Eigen::VectorXd load_;                        // F₀
  std::vector<LawSamples> samples_;             // one sample per law
  PhysicalScales scales_;
  int dofs_, size_;
};

// A static state the solvers could not find although one exists (the
// structure's own stiffness holds the load): not bad input but a solve that
// did not converge (the command exits 1).
class StaticSolveFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Solves the static problem from rest with each of `solvers` in turn until
// one converges (the stick–slip kinks at rest stall some methods, as a
// dynamic solve's fallback chain allows for). When none converges: throws
// InputError naming "preload" if K alone cannot hold the load (a free
// structure: no contact held it either), else StaticSolveFailed with each
// solver's termination.
StaticContactState solveStaticContact(const HbModel& model, const std::vector<Solver*>& solvers,
                                      const SolverOptions& options);
// With one solver.
StaticContactState solveStaticContact(const HbModel& model, Solver& solver, const SolverOptions& options);

}  // namespace eqhb
