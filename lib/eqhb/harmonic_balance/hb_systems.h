// The two square systems of the weighted-residual formulation (spec §3).
//
// FullSystem: z = [x_1 .. x_n, λ_1 .. λ_L] (Fourier coefficients, one channel
// after another, layout of HarmonicSet), equations = the exactly projected
// dynamics A x − f − W λ = 0 (n channels) followed by the projected laws.
//
// CondensedSystem: z = [λ_1 .. λ_L]; the dynamics are solved exactly per
// harmonic, x = B λ + c, and only the projected laws remain. Far smaller;
// requires every A_k to be regular at the current ω. Only the receptance
// at the law DOFs (the rows of B and c there) is kept; the other DOFs are
// recovered from the factors of A_k when asked for.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <vector>

#include "eqhb/harmonic_balance/dynamic_stiffness_factors.h"
#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/harmonic_balance/law_assembly.h"
#include "eqhb/solvers/deadline.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb {

// Right-hand side f (n * nb): the harmonic loads in coefficient layout.
Eigen::VectorXd forcingCoefficients(const HbModel& model);

// Common to both systems: the model, ω, and the mapping of a solution vector
// back to full coefficients.
class HbSystem : public SquareSystem {
 public:
  // Validates the model and checks with `fits` (which throws InputError)
  // that the system fits in memory, before anything of it is allocated.
  HbSystem(HbModel model, const std::function<void(const HbModel&)>& fits);
  int size() const override { return size_; }
  const HbModel& model() const { return model_; }
  double omega() const { return model_.omega; }
  // Changes ω; throws (std::runtime_error) where the condensed system's
  // dynamic stiffness is singular.
  virtual void setOmega(double omega) = 0;
  // Full coefficient vector [x; λ] for a solution vector of this system.
  virtual Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const = 0;
  // The solution vector of this system for a full coefficient vector.
  virtual Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const = 0;
  virtual bool condensed() const = 0;
  // While held, setOmega keeps every law's ρ as it is instead of setting a
  // scale-free ρ for the new ω: a system whose ω is an unknown (nonlinear
  // modes) needs one residual function of ω within a solve.
  void holdRho(bool held) { rho_held_ = held; }
  // From now on every scale-free ρ comes from the static compliance
  // (withStaticScaleFreeRhos), set at once: for a system whose ω is a
  // resonance of its own (nonlinear modes).
  void scaleRhoByStaticCompliance();
  // Dynamics rows (full system): the force scale F; law rows: each law's
  // residual scale, in the model's physical scales at the current ω
  // (problem_scales.h).
  void residualScales(Eigen::Ref<Eigen::VectorXd> scales) const override;
  // The size of a solution vector in the problem's own scales
  // (problem_scales.h): F for the condensed system's law forces, √(X² + F²)
  // for the full [x; λ]. A measure of z where z itself is nil, as on a
  // curve whose laws are idle (a contact not yet reached).
  double unknownScale() const;
  // A friction law that dissipates half the energy its limit demands, or
  // less, at z (dissipation_deficit >= kGrossDissipationDeficit, measured on
  // the model's samples): "law[l] (type): dissipation_deficit = value".
  std::string violatedPhysics(const Eigen::Ref<const Eigen::VectorXd>& z) override;

 protected:
  // The largest amplitude of the linear response at the laws' DOFs.
  virtual double responseAtLaws() const = 0;
  // After ω changed: every scale-free ρ set again for the new ω, so that a
  // point of a sweep gets the ρ a solve at its ω would (withScaleFreeRhos).
  void setScaleFreeRhos();
  HbModel model_;
  LawAssembly laws_;
  int nb_;
  int size_ = 0;  // unknowns, set by each system's constructor
  bool rho_held_ = false;
  bool rho_static_ = false;
};

class FullSystem : public HbSystem {
 public:
  // Throws InputError if the model is invalid, TimeLimitReached once
  // `deadline` has passed during the set-up.
  explicit FullSystem(HbModel model, const Deadline& deadline = Deadline());
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  // The Jacobian assembled sparse (pattern fixed here, at construction):
  // per harmonic the blocks of A_k on the pattern of M, C and K, −W on the
  // law DOFs, and the nb x nb law blocks on the law rows only.
  bool nativeSparseJacobian() const override { return true; }
  const SparseMatrix& jacobianPattern() override { return pattern_; }
  bool residualAndSparseJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                 Eigen::Ref<Eigen::VectorXd> g, SparseMatrix& jacobian) override;
  void setOmega(double omega) override;
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override { return z; }
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override {
    return full;
  }
  bool condensed() const override { return false; }
  // After residualAndJacobian or residualAndSparseJacobian at z: the law
  // rows of ∂g/∂ω at z (LawAssembly::omegaDerivative) into `column`; its
  // dynamics rows are left as they are.
  void lawOmegaDerivative(Eigen::Ref<Eigen::VectorXd> column);

 protected:
  double responseAtLaws() const override;

 private:
  // Residual into g; with `values`, the Jacobian's values in the order of
  // pattern_'s storage.
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                double* values);
  // The set-up (at construction), step by step, `deadline` checked in each.
  using Entry = Eigen::Triplet<double>;
  void buildPattern(const Deadline& deadline);
  std::vector<Entry> dynamicsEntries(const SparseMatrix& union_pattern, const Deadline& deadline) const;
  void buildJacobianPattern(const std::vector<Entry>& dynamics, const Deadline& deadline);
  void locateDynamicsEntries(const std::vector<Entry>& dynamics, const Deadline& deadline);
  void locateLawEntries(const Deadline& deadline);
  int dynamic_rows_;
  SparseMatrix linear_operator_;  // A, (n nb) x (n nb): blocks of A_k per DOF pair
  Eigen::VectorXd forcing_;
  SparseMatrix pattern_;          // the Jacobian's structure
  // Values of M, C, K on the union pattern P, in P's storage order.
  Eigen::VectorXd pattern_mass_, pattern_damping_, pattern_stiffness_;
  // Per entry of A (loop order of setOmega): its index in linear_operator_
  // and in pattern_'s values.
  std::vector<int> operator_slot_, jacobian_slot_;
  Eigen::VectorXd constant_values_;  // the Jacobian without the law blocks
  Eigen::VectorXd values_;           // scratch for the dense Jacobian
  // Per law l, per (a, b): the nb x nb slots (column-major) of ∂Ψ_a/∂λ_b in
  // pattern_'s values, and of ∂Ψ_a/∂u_b · W_bj for each DOF j of W's row b
  // (one nb x nb block after another, in the row's order).
  std::vector<std::vector<std::vector<int>>> displacement_slots_, force_slots_;
  // responseAtLaws() at response_omega_ (one solve per ω, made when asked).
  mutable double response_ = 0.0, response_omega_ = 0.0;
};

class CondensedSystem : public HbSystem {
 public:
  // Throws InputError if the model is invalid, std::runtime_error if some
  // A_k is singular at the model's ω.
  // algebra: how A_k is factored (kAuto: sparse from
  // kSparseCondensationFromDofs DOFs up).
  // TimeLimitReached once `deadline` has passed during the set-up.
  explicit CondensedSystem(HbModel model, LinearAlgebra algebra = LinearAlgebra::kAuto,
                           const Deadline& deadline = Deadline());
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  void setOmega(double omega) override;
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override;
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override;
  bool condensed() const override { return true; }
  // The factorisations of A_k: dense or sparse, set-up time, memory.
  const DynamicStiffnessFactors& factors() const { return factors_; }

 protected:
  double responseAtLaws() const override;  // from the offsets: no new solve

 private:
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                Eigen::Ref<Eigen::MatrixXd>* jacobian);
  // setOmega, with the set-up's deadline checked between harmonics.
  void condenseAt(double omega, const Deadline& deadline);
  int components_;
  // Row of W (law_attachment.h) of each law component, and its force sign.
  std::vector<std::vector<AttachmentTerm>> component_row_;
  std::vector<double> component_sign_;
  DynamicStiffnessFactors factors_;
  bool factored_ = false;
  // coupling_[q][c]: nb x 2, rows of harmonic h hold the w x w block mapping
  // λ_c's coefficients of h to those of u_q = W_q x (component q's reading).
  std::vector<std::vector<Eigen::MatrixXd>> coupling_;
  std::vector<Eigen::VectorXd> offset_;  // c per component's DOF (nb)
};

// The condensed or the full system of a model (throws as their constructors).
// algebra: the condensed system's factorisation (the full system always
// offers both Jacobians).
// deadline: checked during the set-up (assembly, factorisations), which
// then throws TimeLimitReached saying where it was.
std::unique_ptr<HbSystem> makeHbSystem(const HbModel& model, bool condensed,
                                       LinearAlgebra algebra = LinearAlgebra::kAuto,
                                       const Deadline& deadline = Deadline());

}  // namespace eqhb
