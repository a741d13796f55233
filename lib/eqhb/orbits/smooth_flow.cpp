#include "eqhb/orbits/smooth_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/cubic_stiffness.h"
#include "eqhb/laws/stribeck.h"
#include "eqhb/orbits/flow_dynamics.h"

namespace eqhb::orbits {

bool SmoothFlow::supports(const HbModel& model) {
  if (model.laws.empty()) return false;
  for (const auto& attached : model.laws)
    if (!smoothFlowSite(*attached.law)) return false;
  return true;
}

std::unique_ptr<Flow> makeFlow(const HbModel& model, double restitution) {
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  // Closed form where every law allows it; Coulomb 1D mixed with smooth
  // laws goes with them (a Stribeck law without drop).
  if (!PiecewiseLinearFlow::supports(model) && SmoothFlow::supports(model)) return std::make_unique<SmoothFlow>(model);
  return std::make_unique<PiecewiseLinearFlow>(model, restitution);
}

SmoothFlow::SmoothFlow(const HbModel& model) {
  model.validate();
  requireGroundedLaws(model.laws, "exact orbits (shooting)");
  const LinearStructure& s = model.structure;
  n_ = s.dofs();
  omega_ = model.omega;
  dynamics_ = DenseDynamics(s);
  loads_ = s.loads;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const Law* law = model.laws[l].law.get();
    Site site;
    site.dof = model.laws[l].attachment.dof(0);
    if (const auto capability = smoothFlowSite(*law)) {  // the law's registry entry
      using Declared = SmoothFlowSite::Kind;
      site.kind = capability->kind == Declared::kCubic    ? Kind::kCubic
                  : capability->kind == Declared::kForce  ? Kind::kForce
                  : capability->kind == Declared::kPlanar ? Kind::kPlanar
                                                          : Kind::kStribeck;
      site.force = capability->force;
      if (site.kind == Kind::kPlanar) site.second_dof = model.laws[l].attachment.dof(1);
      site.coefficient = capability->coefficient;
      site.drop = capability->drop;
      site.v_s = capability->v_s;
    } else {
      throwInputError("law[" + std::to_string(l) + "].type", law->type(),
                      "exact orbits handle coulomb-1d, signorini (closed form), cubic, polynomial, "
                      "quadratic-damping, coulomb-2d, stribeck and coulomb-1d (smooth phases) laws; signorini "
                      "does not mix with the smooth ones");
    }
    components_ += site.components();
    sites_.push_back(site);
  }
  std::vector<int> harmonics;
  for (const auto& load : loads_) harmonics.push_back(load.harmonic);
  rate_ = fastestRate(dynamics_.mass_inverse, dynamics_.stiffness, dynamics_.damping, harmonics, omega_);
  double force = 0.0;
  for (const auto& load : loads_) force += std::abs(load.cos_amplitude) + std::abs(load.sin_amplitude);
  for (const Site& site : sites_)
    if (!site.alwaysSmooth()) force += site.coefficient + site.drop;
  acceleration_scale_ = dynamics_.mass_inverse.cwiseAbs().rowwise().sum().maxCoeff() * force;
}

const SmoothFlow::Constraint& SmoothFlow::constraint(const Modes& modes) const {
  auto found = constraints_.find(modes);
  if (found != constraints_.end()) return found->second;
  Constraint c;
  for (size_t s = 0; s < sites_.size(); ++s) {
    c.first_row.push_back(modes[s] == Mode::kStick ? static_cast<int>(c.dofs.size()) : -1);
    if (modes[s] != Mode::kStick) continue;
    c.dofs.push_back(sites_[s].dof);
    if (sites_[s].kind == Kind::kPlanar) c.dofs.push_back(sites_[s].second_dof);
  }
  HeldDofs held = holdDofs(dynamics_.mass_inverse, c.dofs);
  c.projector = std::move(held.projector);
  c.multiplier = std::move(held.multiplier);
  return constraints_.emplace(modes, std::move(c)).first->second;
}

void SmoothFlow::forcing(double t, Eigen::VectorXd& f, Eigen::VectorXd* df) const {
  f.setZero(n_);
  if (df) df->setZero(n_);
  for (const auto& load : loads_) {
    const double w = load.harmonic * omega_, c = std::cos(w * t), s = std::sin(w * t);
    f[load.dof] += load.cos_amplitude * c + load.sin_amplitude * s;
    if (df) (*df)[load.dof] += w * (-load.cos_amplitude * s + load.sin_amplitude * c);
  }
}

bool SmoothFlow::freeForce(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& b,
                           Eigen::MatrixXd* db) const {
  forcing(t, b, nullptr);
  b.noalias() -= dynamics_.stiffness * y.head(n_) + dynamics_.damping * y.tail(n_);
  if (db) {
    db->resize(n_, 2 * n_);
    *db << -dynamics_.stiffness, -dynamics_.damping;
  }
  const double speed_floor = kRestSpeed * (1.0 + y.tail(n_).cwiseAbs().maxCoeff());
  for (size_t s = 0; s < sites_.size(); ++s) {
    const Site& site = sites_[s];
    // Stuck sites act through λ; a friction site marked smooth is left out
    // (the restart guess adds its force itself).
    if (modes[s] == Mode::kStick || (!site.alwaysSmooth() && modes[s] == Mode::kSmooth)) continue;
    if (site.kind == Kind::kCubic) {
      const double x = y[site.dof];
      b[site.dof] -= site.coefficient * x * x * x;
      if (db) (*db)(site.dof, site.dof) -= 3.0 * site.coefficient * x * x;
    } else if (site.kind == Kind::kForce) {
      double f = 0.0, df_dx = 0.0, df_dv = 0.0;
      site.force(y[site.dof], y[n_ + site.dof], &f, &df_dx, &df_dv);
      b[site.dof] += f;
      if (db) {
        (*db)(site.dof, site.dof) += df_dx;
        (*db)(site.dof, n_ + site.dof) += df_dv;
      }
    } else if (site.kind == Kind::kStribeck) {
      // Slip in direction σ: force −σ L(σ v) on the continuation of L past
      // v = 0, smooth, so that the stop is a plain sign change of v.
      const double sigma = modes[s] == Mode::kSlipPositive ? 1.0 : -1.0, v = y[n_ + site.dof];
      const double decay = site.drop * std::exp(-sigma * v / site.v_s);
      b[site.dof] -= sigma * (site.coefficient + decay);
      if (db) (*db)(site.dof, n_ + site.dof) += decay / site.v_s;
    } else {
      const int a = site.dof, c = site.second_dof;
      const Eigen::Vector2d v(y[n_ + a], y[n_ + c]);
      const double speed = v.norm();
      if (!(speed > speed_floor)) return false;
      b[a] -= site.coefficient * v[0] / speed;
      b[c] -= site.coefficient * v[1] / speed;
      if (db) {
        // ∂(−μN v/‖v‖)/∂v = −μN (I − v̂ v̂ᵀ)/‖v‖
        const Eigen::Matrix2d d = -site.coefficient * (Eigen::Matrix2d::Identity() - v * v.transpose() / (speed * speed)) / speed;
        (*db)(a, n_ + a) += d(0, 0);
        (*db)(a, n_ + c) += d(0, 1);
        (*db)(c, n_ + a) += d(1, 0);
        (*db)(c, n_ + c) += d(1, 1);
      }
    }
  }
  return true;
}

bool SmoothFlow::field(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& dy,
                       Eigen::MatrixXd* jacobian) const {
  Eigen::VectorXd b;
  Eigen::MatrixXd db;
  if (!freeForce(t, y, modes, b, jacobian ? &db : nullptr)) return false;
  const Constraint& c = constraint(modes);
  dy.resize(2 * n_);
  dy.head(n_) = y.tail(n_);
  dy.tail(n_) = c.projector * b;
  if (jacobian) {
    jacobian->setZero(2 * n_, 2 * n_);
    jacobian->topRightCorner(n_, n_).setIdentity();
    jacobian->bottomRows(n_) = c.projector * db;
  }
  return true;
}

Eigen::VectorXd SmoothFlow::siteForce(int s, double t, const Eigen::VectorXd& y, const Modes& modes) const {
  const Site& site = sites_[s];
  Eigen::VectorXd out(site.components());
  if (modes[s] == Mode::kStick) {
    Eigen::VectorXd b;
    freeForce(t, y, modes, b, nullptr);
    const Constraint& c = constraint(modes);
    return (c.multiplier * b).segment(c.first_row[s], site.components());
  }
  if (site.kind == Kind::kCubic) {
    out[0] = -site.coefficient * std::pow(y[site.dof], 3);
  } else if (site.kind == Kind::kForce) {
    double df_dx = 0.0, df_dv = 0.0;
    site.force(y[site.dof], y[n_ + site.dof], &out[0], &df_dx, &df_dv);
  } else if (site.kind == Kind::kStribeck) {
    const double sigma = modes[s] == Mode::kSlipPositive ? 1.0 : -1.0;
    out[0] = -sigma * (site.coefficient + site.drop * std::exp(-sigma * y[n_ + site.dof] / site.v_s));
  } else {
    const Eigen::Vector2d v(y[n_ + site.dof], y[n_ + site.second_dof]);
    const double speed = v.norm();
    out = speed > 0.0 ? Eigen::VectorXd(-site.coefficient * v / speed) : Eigen::VectorXd::Zero(2);
  }
  return out;
}

std::vector<SmoothFlow::Watch> SmoothFlow::watches(const Modes& modes) const {
  std::vector<Watch> out;
  for (size_t s = 0; s < sites_.size(); ++s) {
    const int site = static_cast<int>(s);
    if (sites_[s].kind == Kind::kStribeck) {
      if (modes[s] == Mode::kStick) {
        out.push_back({site, 1, "slip"});
        out.push_back({site, -1, "slip"});
      } else {
        out.push_back({site, 0, "stop"});
      }
    } else if (sites_[s].kind == Kind::kPlanar && modes[s] == Mode::kStick) {
      out.push_back({site, 0, "slip"});
    }
  }
  return out;
}

double SmoothFlow::eventValue(const Watch& w, double t, const Eigen::VectorXd& y, const Modes& modes,
                              Eigen::RowVectorXd* gradient, double* time_derivative) const {
  const Site& site = sites_[w.site];
  if (modes[w.site] != Mode::kStick) {  // Stribeck slip: g = σ v
    const double sigma = modes[w.site] == Mode::kSlipPositive ? 1.0 : -1.0;
    if (gradient) {
      gradient->setZero(2 * n_);
      (*gradient)[n_ + site.dof] = sigma;
      *time_derivative = 0.0;
    }
    return sigma * y[n_ + site.dof];
  }
  Eigen::VectorXd b, df;
  Eigen::MatrixXd db;
  freeForce(t, y, modes, b, gradient ? &db : nullptr);
  const Constraint& c = constraint(modes);
  const int row = c.first_row[w.site], k = site.components();
  const Eigen::VectorXd lambda = c.multiplier.middleRows(row, k) * b;
  // g = limit − (direction of λ) · λ, with ∇g = −direction · ∇λ.
  Eigen::VectorXd direction(k);
  double limit = 0.0;
  if (site.kind == Kind::kPlanar) {
    limit = site.coefficient;
    const double norm = lambda.norm();
    direction = norm > 0.0 ? Eigen::VectorXd(lambda / norm) : Eigen::VectorXd::Zero(2);
  } else {
    limit = site.coefficient + site.drop;
    direction = Eigen::VectorXd::Constant(1, w.branch);
  }
  if (gradient) {
    forcing(t, b, &df);
    *gradient = -direction.transpose() * c.multiplier.middleRows(row, k) * db;
    *time_derivative = -direction.dot(c.multiplier.middleRows(row, k) * df);
  }
  return limit - direction.dot(lambda);
}

SmoothFlow::Modes SmoothFlow::restModes(int s, double t, const Eigen::VectorXd& y, Modes modes) const {
  modes[s] = Mode::kStick;
  const Eigen::VectorXd lambda = siteForce(s, t, y, modes);
  const Site& site = sites_[s];
  if (site.kind == Kind::kPlanar) {
    if (lambda.norm() > site.coefficient) modes[s] = Mode::kSlide;
  } else if (std::abs(lambda[0]) > site.coefficient + site.drop) {
    // Slides against the force it would need.
    modes[s] = lambda[0] > 0.0 ? Mode::kSlipNegative : Mode::kSlipPositive;
  }
  return modes;
}

SmoothFlow::Modes SmoothFlow::initialModes(double t, const Eigen::VectorXd& y) const {
  Modes modes(sites_.size(), Mode::kSmooth);
  for (size_t s = 0; s < sites_.size(); ++s) {
    const Site& site = sites_[s];
    if (site.kind == Kind::kPlanar) modes[s] = Mode::kSlide;
    if (site.kind == Kind::kStribeck) {
      const double v = y[n_ + site.dof];
      modes[s] = v > 0.0 ? Mode::kSlipPositive : Mode::kSlipNegative;
    }
  }
  for (size_t s = 0; s < sites_.size(); ++s) {
    const Site& site = sites_[s];
    const bool rest = site.kind == Kind::kStribeck ? y[n_ + site.dof] == 0.0
                      : site.kind == Kind::kPlanar  ? y[n_ + site.dof] == 0.0 && y[n_ + site.second_dof] == 0.0
                                                    : false;
    if (rest) modes = restModes(static_cast<int>(s), t, y, modes);
  }
  return modes;
}

}  // namespace eqhb::orbits
