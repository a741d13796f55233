#include "eqhb/orbits/piecewise_linear_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/laws/signorini.h"
#include "eqhb/orbits/flow_dynamics.h"

namespace eqhb::orbits {

namespace {

// A constraint force within this fraction of its limit is on the limit.
constexpr double kTieTolerance = 1e-13;

}  // namespace

bool PiecewiseLinearFlow::constrains(const LawSite& site, Mode mode) {
  // Elastic sliders and walls act by springs, never by a held DOF.
  return site.slider < 0 && site.penalty == 0.0 && (mode == Mode::kStick || mode == Mode::kClosed);
}

bool PiecewiseLinearFlow::supports(const HbModel& model) {
  for (const auto& attached : model.laws)
    if (!piecewiseLinearSite(*attached.law)) return false;
  return true;
}

PiecewiseLinearFlow::PiecewiseLinearFlow(const HbModel& model, double restitution)
    : restitution_(restitution) {
  model.validate();
  requireGroundedLaws(model.laws, "exact orbits (shooting)");
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  const LinearStructure& s = model.structure;
  n_ = s.dofs();
  omega_ = model.omega;
  dynamics_ = DenseDynamics(s);
  constant_load_ = Eigen::VectorXd::Zero(n_);
  for (const auto& load : s.loads) {
    if (load.harmonic == 0) {
      constant_load_[load.dof] += load.cos_amplitude;
      continue;
    }
    auto it = std::find(harmonics_.begin(), harmonics_.end(), load.harmonic);
    if (it == harmonics_.end()) {
      harmonics_.push_back(load.harmonic);
      cos_load_.push_back(Eigen::VectorXd::Zero(n_));
      sin_load_.push_back(Eigen::VectorXd::Zero(n_));
      it = harmonics_.end() - 1;
    }
    const auto h = it - harmonics_.begin();
    cos_load_[h][load.dof] += load.cos_amplitude;
    sin_load_[h][load.dof] += load.sin_amplitude;
  }
  m_ = 2 * n_;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const Law* law = model.laws[l].law.get();
    LawSite site;
    site.dof = model.laws[l].attachment.dof(0);
    if (const auto capability = piecewiseLinearSite(*law)) {  // the law's registry entry
      site.contact = capability->contact;
      site.limit = capability->limit;
      site.gap = capability->gap;
      site.stiffness = capability->stiffness;
      site.penalty = capability->penalty;
      if (site.stiffness > 0.0) site.slider = m_++;
    } else {
      throwInputError("law[" + std::to_string(l) + "].type", law->type(),
                      "exact orbits handle coulomb-1d, jenkins on 1 DOF, signorini, penalty-contact (closed form), cubic, "
                      "polynomial, "
                      "quadratic-damping, coulomb-2d, stribeck and coulomb-1d (smooth phases) laws; signorini does "
                      "not mix with the smooth ones");
    }
    sites_.push_back(site);
  }
  nz_ = m_ + 1 + 2 * static_cast<int>(harmonics_.size());
  // Fastest rate: natural frequency bound, damping rate, forcing.
  Eigen::MatrixXd stuck_stiffness = dynamics_.stiffness;  // every elastic slider stuck, every elastic wall pressed
  for (const LawSite& site : sites_) stuck_stiffness(site.dof, site.dof) += site.stiffness + site.penalty;
  rate_ = fastestRate(dynamics_.mass_inverse, stuck_stiffness, dynamics_.damping, harmonics_, omega_);
}

Eigen::VectorXd PiecewiseLinearFlow::augment(const Eigen::VectorXd& y, double t) const {
  Eigen::VectorXd z(nz_);
  z.head(m_) = y;
  refreshForcing(z, t);
  return z;
}

void PiecewiseLinearFlow::refreshForcing(Eigen::VectorXd& z, double t) const {
  z[m_] = 1.0;
  for (size_t h = 0; h < harmonics_.size(); ++h) {
    z[m_ + 1 + 2 * h] = std::cos(harmonics_[h] * omega_ * t);
    z[m_ + 2 + 2 * h] = std::sin(harmonics_[h] * omega_ * t);
  }
}

const PiecewiseLinearFlow::Phase& PiecewiseLinearFlow::phase(const std::vector<Mode>& modes) const {
  auto found = phases_.find(modes);
  if (found != phases_.end()) return found->second;
  Phase p;
  Eigen::VectorXd sliding = Eigen::VectorXd::Zero(n_);
  for (size_t l = 0; l < sites_.size(); ++l) {
    const int dof = sites_[l].dof;
    if (modes[l] == Mode::kSlipPositive) sliding[dof] -= sites_[l].limit;
    if (modes[l] == Mode::kSlipNegative) sliding[dof] += sites_[l].limit;
    if (constrains(sites_[l], modes[l])) p.constrained.push_back(dof);
  }
  // b = B z: the force on the structure except the constraint forces.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n_, nz_);
  b.leftCols(n_) = -dynamics_.stiffness;
  b.middleCols(n_, n_) = -dynamics_.damping;
  // A stuck elastic slider: force −k_t (x − w) on its DOF.
  for (size_t l = 0; l < sites_.size(); ++l)
    if (sites_[l].slider >= 0 && modes[l] == Mode::kStick) {
      b(sites_[l].dof, sites_[l].dof) -= sites_[l].stiffness;
      b(sites_[l].dof, sites_[l].slider) += sites_[l].stiffness;
    }
  // A pressed elastic wall: force −k_n (x − g0) on its DOF.
  for (size_t l = 0; l < sites_.size(); ++l)
    if (sites_[l].penalty > 0.0 && modes[l] == Mode::kClosed) {
      b(sites_[l].dof, sites_[l].dof) -= sites_[l].penalty;
      sliding[sites_[l].dof] += sites_[l].penalty * sites_[l].gap;
    }
  b.col(m_) = constant_load_ + sliding;
  for (size_t h = 0; h < harmonics_.size(); ++h) {
    b.col(m_ + 1 + 2 * h) = cos_load_[h];
    b.col(m_ + 2 + 2 * h) = sin_load_[h];
  }
  const HeldDofs held = holdDofs(dynamics_.mass_inverse, p.constrained);
  const Eigen::MatrixXd& q = held.projector;
  p.constraint_force = p.constrained.empty() ? Eigen::MatrixXd::Zero(0, nz_) : Eigen::MatrixXd(held.multiplier * b);
  p.generator = Eigen::MatrixXd::Zero(nz_, nz_);
  p.generator.block(0, n_, n_, n_).setIdentity();
  p.generator.middleRows(n_, n_) = q * b;
  for (size_t l = 0; l < sites_.size(); ++l)  // a slipping slider moves with its DOF: ẇ = ẋ
    if (sites_[l].slider >= 0 && modes[l] != Mode::kStick) p.generator(sites_[l].slider, n_ + sites_[l].dof) = 1.0;
  for (size_t h = 0; h < harmonics_.size(); ++h) {
    const double kw = harmonics_[h] * omega_;
    const int c = m_ + 1 + 2 * static_cast<int>(h);
    p.generator(c, c + 1) = -kw;  // d/dt cos = −kω sin
    p.generator(c + 1, c) = kw;   // d/dt sin = kω cos
  }
  p.grid = std::min(period() / 32.0, 0.2 / rate_);
  p.grid_step = (p.generator * p.grid).exp();
  return phases_.emplace(modes, std::move(p)).first->second;
}

std::vector<PiecewiseLinearFlow::Event> PiecewiseLinearFlow::events(const std::vector<Mode>& modes,
                                                                     const Phase& p) const {
  std::vector<Event> out;
  auto constraintRow = [&](int dof) -> Eigen::RowVectorXd {
    const auto i = std::find(p.constrained.begin(), p.constrained.end(), dof) - p.constrained.begin();
    return p.constraint_force.row(i);
  };
  for (size_t l = 0; l < sites_.size(); ++l) {
    const LawSite& site = sites_[l];
    Event e;
    e.law = static_cast<int>(l);
    e.functional = Eigen::RowVectorXd::Zero(nz_);
    switch (modes[l]) {
      case Mode::kSlipPositive:
      case Mode::kSlipNegative:
        e.functional[n_ + site.dof] = modes[l] == Mode::kSlipPositive ? 1.0 : -1.0;
        e.kind = "stop";
        out.push_back(e);
        break;
      case Mode::kStick: {
        const Eigen::RowVectorXd r = site.slider >= 0 ? springForceRow(site) : constraintRow(site.dof);
        e.kind = "slip";
        e.functional = -r;  // μN − r
        e.functional[m_] += site.limit;
        out.push_back(e);
        e.functional = r;   // μN + r
        e.functional[m_] += site.limit;
        out.push_back(e);
        break;
      }
      case Mode::kOpen:
        e.functional[site.dof] = -1.0;  // g0 − x
        e.functional[m_] = site.gap;
        e.kind = site.penalty > 0.0 ? "touch" : "impact";
        out.push_back(e);
        break;
      case Mode::kClosed:
        if (site.penalty > 0.0) {  // pressed while x − g0 > 0
          e.functional[site.dof] = 1.0;
          e.functional[m_] = -site.gap;
        } else {
          e.functional = -constraintRow(site.dof);  // pressure p = −(force on the structure)
        }
        e.kind = "release";
        out.push_back(e);
        break;
    }
  }
  return out;
}

std::vector<PiecewiseLinearFlow::Mode> PiecewiseLinearFlow::chooseModes(const Eigen::VectorXd& z,
                                                                        std::vector<Mode> modes,
                                                                        const std::vector<bool>& free_choice) const {
  // Kinematics first: a moving DOF slides, an open gap stays open; a DOF at
  // rest (or at the wall) is tried constrained.
  for (size_t l = 0; l < sites_.size(); ++l) {
    if (!free_choice[l]) continue;
    const LawSite& site = sites_[l];
    const double v = z[n_ + site.dof];
    if (site.penalty > 0.0) {
      // Elastic wall: pressed beyond g0, or at g0 moving into it.
      const double into = z[site.dof] - site.gap;
      modes[l] = (into > 0.0 || (into == 0.0 && v > 0.0)) ? Mode::kClosed : Mode::kOpen;
    } else if (site.slider >= 0) {
      // Elastic: stuck inside the limit; on it, slipping where the DOF moves
      // against the spring force (r = −μN while ẋ > 0), else stuck.
      const double r = springForceRow(site).dot(z);
      const double tie = kTieTolerance * std::max(site.limit, std::numeric_limits<double>::min());
      modes[l] = (r <= -site.limit + tie && v > 0.0)  ? Mode::kSlipPositive
                 : (r >= site.limit - tie && v < 0.0) ? Mode::kSlipNegative
                                                      : Mode::kStick;
    } else if (site.contact)
      modes[l] = (z[site.dof] < site.gap || v < 0.0) ? Mode::kOpen : Mode::kClosed;
    else
      modes[l] = v > 0.0 ? Mode::kSlipPositive : v < 0.0 ? Mode::kSlipNegative : Mode::kStick;
  }
  // Then release, one at a time, the constraint whose force is the most out
  // of its admissible set (exact Coulomb: stick iff |r| <= μN, slide against
  // r; Signorini: closed iff p >= 0).
  for (size_t round = 0; round <= sites_.size(); ++round) {
    const Phase& p = phase(modes);
    int worst = -1;
    double worst_excess = 0.0;
    Mode release = Mode::kOpen;
    for (size_t l = 0; l < sites_.size(); ++l) {
      if (!free_choice[l] || !constrains(sites_[l], modes[l])) continue;
      const auto i = std::find(p.constrained.begin(), p.constrained.end(), sites_[l].dof) - p.constrained.begin();
      const double f = p.constraint_force.row(i).dot(z);
      // At a tie (force on the boundary of its set to round-off) the rate
      // of the force decides: leaving the set releases.
      const double rate = p.constraint_force.row(i).dot(p.generator * z);
      const double tie = kTieTolerance * std::max({std::abs(f), sites_[l].limit, std::numeric_limits<double>::min()});
      double excess = sites_[l].contact ? f : std::abs(f) - sites_[l].limit;  // contact: −p
      const double direction = std::abs(f) > tie ? f : rate;
      if (std::abs(excess) <= tie) {
        const double outward = sites_[l].contact ? rate : (direction > 0.0 ? rate : -rate);
        excess = outward > 0.0 ? tie * 0.5 + std::numeric_limits<double>::min() : 0.0;
      }
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = static_cast<int>(l);
        release = sites_[l].contact ? Mode::kOpen : (direction > 0.0 ? Mode::kSlipNegative : Mode::kSlipPositive);
      }
    }
    if (worst < 0) break;
    modes[worst] = release;
  }
  return modes;
}

Eigen::RowVectorXd PiecewiseLinearFlow::springForceRow(const LawSite& site) const {
  Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(nz_);  // r = −k_t (x − w)
  r[site.dof] = -site.stiffness;
  r[site.slider] = site.stiffness;
  return r;
}

double PiecewiseLinearFlow::lawForce(int l, Mode mode, const Phase& p, const Eigen::VectorXd& z) const {
  const LawSite& site = sites_[l];
  if (mode == Mode::kSlipPositive) return -site.limit;
  if (mode == Mode::kSlipNegative) return site.limit;
  if (mode == Mode::kOpen) return 0.0;
  if (site.penalty > 0.0) return site.penalty * (z[site.dof] - site.gap);  // pressed: the pressure
  if (site.slider >= 0) return springForceRow(site).dot(z);                // stuck behind its spring
  // Held: the constraint force (a closed wall's pressure is minus it).
  const auto i = std::find(p.constrained.begin(), p.constrained.end(), site.dof) - p.constrained.begin();
  const double f = p.constraint_force.row(i).dot(z);
  return mode == Mode::kClosed ? -f : f;
}

}  // namespace eqhb::orbits
