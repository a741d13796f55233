#include "eqhb/preload/static_contact.h"

#include <Eigen/SparseCholesky>

#include "eqhb/error.h"
#include "eqhb/harmonic_balance/problem_scales.h"

namespace eqhb {

StaticContactSystem::StaticContactSystem(const HbModel& model)
    // ρ from the static compliance: ω means nothing at rest.
    : model_(withStaticScaleFreeRhos(model)),
      dofs_(model.structure.dofs()),
      size_(model.structure.dofs() + model.lawComponents()) {
  load_ = Eigen::VectorXd::Zero(dofs_);
  for (const HarmonicLoad& f : model_.structure.loads)
    if (f.harmonic == 0) load_[f.dof] += f.cos_amplitude;
  if (load_.isZero(0.0)) throwInputError("preload", "(no constant load)", "a static solve needs a constant load to hold");
  for (const AttachedLaw& attached : model_.laws) {
    const Law& law = *attached.law;
    // At rest a history law is its copy anchored at the unloaded state.
    LawSamples unloaded;
    unloaded.resize(1, law.dimension(), law.historyTermsOn(1));
    unloaded.displacement.setZero();
    unloaded.velocity.setZero();
    unloaded.force.setZero();
    unloaded.force_rate.setZero();
    std::shared_ptr<Law> anchored = law.anchoredAt(unloaded);
    step_laws_.push_back(anchored ? anchored : attached.law);
    samples_.push_back(unloaded);
  }
  scales_ = physicalScales(model_, 0.0);
}

void StaticContactSystem::residualScales(Eigen::Ref<Eigen::VectorXd> scales) const {
  scales.head(dofs_).setConstant(scales_.force);
  for (size_t l = 0; l < step_laws_.size(); ++l)
    for (int a = 0; a < step_laws_[l]->dimension(); ++a)
      scales[dofs_ + model_.componentIndex(static_cast<int>(l), a)] = step_laws_[l]->residualScale(scales_, a);
}

void StaticContactSystem::fill(const Eigen::Ref<const Eigen::VectorXd>& z, bool with_derivatives) {
  for (size_t l = 0; l < step_laws_.size(); ++l) {
    const Law& law = *step_laws_[l];
    const LawAttachment& w = model_.laws[l].attachment;
    LawSamples& s = samples_[l];
    const bool increments = law.rateIndependent();
    for (int a = 0; a < law.dimension(); ++a) {
      s.displacement(0, a) = w.gather(z, a);
      s.force(0, a) = z[dofs_ + model_.componentIndex(static_cast<int>(l), a)];
      s.velocity(0, a) = increments ? s.displacement(0, a) : 0.0;
      s.force_rate(0, a) = increments ? s.force(0, a) : 0.0;
    }
    law.evaluate(s, with_derivatives);
  }
}

bool StaticContactSystem::residual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) {
  fill(z, false);
  return writeResidual(z, g);
}

bool StaticContactSystem::writeResidual(const Eigen::Ref<const Eigen::VectorXd>& z, Eigen::Ref<Eigen::VectorXd> g) {
  g.head(dofs_) = model_.structure.stiffness * z.head(dofs_) - load_;
  for (size_t l = 0; l < step_laws_.size(); ++l) {
    const Law& law = *step_laws_[l];
    const LawAttachment& w = model_.laws[l].attachment;
    for (int a = 0; a < law.dimension(); ++a) {
      const int c = dofs_ + model_.componentIndex(static_cast<int>(l), a);
      for (const AttachmentTerm& t : w.row(a)) g[t.dof] -= law.forceSign() * t.weight * z[c];
      g[c] = samples_[l].psi(0, a);
    }
  }
  return g.allFinite();
}

bool StaticContactSystem::residualAndJacobian(const Eigen::Ref<const Eigen::VectorXd>& z,
                                              Eigen::Ref<Eigen::VectorXd> g, Eigen::Ref<Eigen::MatrixXd> jacobian) {
  fill(z, true);
  if (!writeResidual(z, g)) return false;
  jacobian.setZero();
  jacobian.topLeftCorner(dofs_, dofs_) = Eigen::MatrixXd(model_.structure.stiffness);
  for (size_t l = 0; l < step_laws_.size(); ++l) {
    const Law& law = *step_laws_[l];
    const LawAttachment& w = model_.laws[l].attachment;
    const LawSamples& s = samples_[l];
    const int d = law.dimension(), terms = law.historyTermsOn(1);
    const bool increments = law.rateIndependent();
    for (int a = 0; a < d; ++a) {
      const int row = dofs_ + model_.componentIndex(static_cast<int>(l), a);
      for (const AttachmentTerm& t : w.row(a)) jacobian(t.dof, row) -= law.forceSign() * t.weight;
      for (int b = 0; b < d; ++b) {
        const int ab = a * d + b;
        const int col = dofs_ + model_.componentIndex(static_cast<int>(l), b);
        // One sample: the history terms (sample 0 or the mean) read u_b too.
        double du = law.usesDisplacement() ? s.dpsi_ddisplacement(0, ab) : 0.0;
        if (increments && law.usesVelocity()) du += s.dpsi_dvelocity(0, ab);
        for (int k = 0; k < terms; ++k) du += s.history_weight(0, ab * terms + k);
        for (const AttachmentTerm& t : w.row(b)) jacobian(row, t.dof) += du * t.weight;
        double dl = s.dpsi_dforce(0, ab);
        if (increments && law.usesForceRate()) dl += s.dpsi_dforce_rate(0, ab);
        jacobian(row, col) += dl;
      }
    }
  }
  return jacobian.allFinite();
}

std::vector<LawSamples> StaticContactSystem::restSamples(const Eigen::Ref<const Eigen::VectorXd>& z) {
  fill(z, false);
  return samples_;
}

namespace {

// True when K x = F₀ has a solution without any law: the structure holds
// the load by its own stiffness, so friction (which can always stick or
// slip) and open contacts leave a static state to find.
bool stiffnessHoldsLoad(const HbModel& model, const Eigen::VectorXd& load) {
  Eigen::SimplicialLDLT<SparseMatrix> factor(model.structure.stiffness);
  if (factor.info() != Eigen::Success) return false;
  const Eigen::VectorXd x = factor.solve(load);
  if (factor.info() != Eigen::Success || !x.allFinite()) return false;
  return (model.structure.stiffness * x - load).norm() <= 1e-8 * load.norm();
}

}  // namespace

StaticContactState solveStaticContact(const HbModel& model, const std::vector<Solver*>& solvers,
                                      const SolverOptions& options) {
  StaticContactSystem system(model);
  StaticContactState state;
  for (Solver* solver : solvers) {
    state.result = solver->solve(system, Eigen::VectorXd::Zero(system.size()), options);
    if (state.result.converged()) {
      state.solver = solver->name();
      break;
    }
    state.failed.push_back(solver->name() + ": " + terminationName(state.result.termination));
  }
  if (!state.result.converged()) {
    std::string tried;
    for (const std::string& f : state.failed) tried += (tried.empty() ? "" : ", ") + f;
    if (!stiffnessHoldsLoad(model, system.load()))
      throwInputError("preload", "(static solve: " + tried + ")",
                      "no contact holds this static load: the structure is free along it or the laws cannot meet it");
    throw StaticSolveFailed("preload: the static solve did not converge (" + tried +
                            "); the structure's stiffness holds this load, so a static state exists: "
                            "the solvers did not find it");
  }
  const Eigen::VectorXd& z = state.result.solution;
  const int n = model.structure.dofs();
  state.displacement = z.head(n);
  state.forces = z.tail(z.size() - n);
  state.rest = system.restSamples(z);
  for (size_t l = 0; l < model.laws.size(); ++l) state.status.push_back(model.laws[l].law->staticStatus(state.rest[l]));
  return state;
}

StaticContactState solveStaticContact(const HbModel& model, Solver& solver, const SolverOptions& options) {
  return solveStaticContact(model, std::vector<Solver*>{&solver}, options);
}

}  // namespace eqhb
