// The two square systems of the weighted-residual formulation (spec §3).
//
// FullSystem: z = [x_1 .. x_n, λ_1 .. λ_L] (Fourier coefficients, one channel
// after another, layout of HarmonicSet), equations = the exactly projected
// dynamics A x − f − W λ = 0 (n channels) followed by the projected laws.
//
// CondensedSystem: z = [λ_1 .. λ_L]; the dynamics are solved exactly per
// harmonic, x = B λ + c, and only the projected laws remain. Far smaller;
// requires every A_k to be regular at the current ω.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/harmonic_balance/law_assembly.h"
#include "eqhb/solvers/square_system.h"

namespace eqhb {

// Right-hand side f (n * nb): the harmonic loads in coefficient layout.
Eigen::VectorXd forcingCoefficients(const HbModel& model);

// Common to both systems: the model, ω, and the mapping of a solution vector
// back to full coefficients.
class HbSystem : public SquareSystem {
 public:
  explicit HbSystem(HbModel model);
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

 protected:
  HbModel model_;
  LawAssembly laws_;
  int nb_;
};

class FullSystem : public HbSystem {
 public:
  // Throws InputError if the model is invalid.
  explicit FullSystem(HbModel model);
  int size() const override { return size_; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  void setOmega(double omega) override;
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override { return z; }
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override {
    return full;
  }
  bool condensed() const override { return false; }

 private:
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                Eigen::Ref<Eigen::MatrixXd>* jacobian);
  int size_;
  int dynamic_rows_;
  Eigen::MatrixXd linear_operator_;  // A, (n nb) x (n nb), block per DOF pair
  Eigen::VectorXd forcing_;
};

class CondensedSystem : public HbSystem {
 public:
  // Throws InputError if the model is invalid, std::runtime_error if some
  // A_k is singular at the model's ω.
  explicit CondensedSystem(HbModel model);
  int size() const override { return size_; }
  bool residual(const Eigen::Ref<const Eigen::VectorXd>& z,
                Eigen::Ref<Eigen::VectorXd> g) override;
  bool residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                           Eigen::Ref<Eigen::VectorXd> g,
                           Eigen::Ref<Eigen::MatrixXd> jacobian) override;
  void setOmega(double omega) override;
  Eigen::VectorXd fullCoefficients(const Eigen::VectorXd& z) const override;
  Eigen::VectorXd fromFullCoefficients(const Eigen::VectorXd& full) const override;
  bool condensed() const override { return true; }

 private:
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g,
                Eigen::Ref<Eigen::MatrixXd>* jacobian);
  int size_;
  int components_;
  std::vector<int> component_dof_;  // DOF of each law component
  // Per harmonic: A_k^{-1} [f_k | W_k], rows (cos rows, sin rows) x DOF.
  std::vector<Eigen::MatrixXd> harmonic_maps_;
  // coupling_[q][c]: nb x 2, rows of harmonic h hold the w x w block mapping
  // λ_c's coefficients of h to those of x at component q's DOF.
  std::vector<std::vector<Eigen::MatrixXd>> coupling_;
  std::vector<Eigen::VectorXd> offset_;  // c per component's DOF (nb)
};

// The condensed or the full system of a model (throws as their constructors).
std::unique_ptr<HbSystem> makeHbSystem(const HbModel& model, bool condensed);

}  // namespace eqhb
