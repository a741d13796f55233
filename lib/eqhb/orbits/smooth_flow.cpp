#include "eqhb/orbits/smooth_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"

namespace eqhb::orbits {

namespace {

// Gauss–Legendre, 3 stages (Butcher tableau, order 6).
const double kR = std::sqrt(15.0);
const double kC[3] = {0.5 - kR / 10.0, 0.5, 0.5 + kR / 10.0};
const double kA[3][3] = {{5.0 / 36.0, 2.0 / 9.0 - kR / 15.0, 5.0 / 36.0 - kR / 30.0},
                         {5.0 / 36.0 + kR / 24.0, 2.0 / 9.0, 5.0 / 36.0 - kR / 24.0},
                         {5.0 / 36.0 + kR / 30.0, 2.0 / 9.0 + kR / 15.0, 5.0 / 36.0}};
const double kB[3] = {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0};
constexpr int kMaxSteps = 2000000;
constexpr int kMaxEvents = 200000;
// Most events in a row at one instant before the phase is called inconsistent.
constexpr int kMaxImmediateEvents = 8;
// Speeds below this fraction of the velocity scale count as rest.
constexpr double kRestSpeed = 1e-14;

}  // namespace

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
  const LinearStructure& s = model.structure;
  n_ = s.dofs();
  omega_ = model.omega;
  const Eigen::LLT<Eigen::MatrixXd> mass_factor{Eigen::MatrixXd(s.mass)};
  if (mass_factor.info() != Eigen::Success || mass_factor.matrixL().toDenseMatrix().diagonal().minCoeff() <= 0.0)
    throwInputError("structure.mass", "singular", "exact orbits need a positive definite mass (no massless DOFs)");
  mass_inverse_ = mass_factor.solve(Eigen::MatrixXd::Identity(n_, n_));
  damping_ = s.damping;
  stiffness_ = s.stiffness;
  loads_ = s.loads;
  for (size_t l = 0; l < model.laws.size(); ++l) {
    const Law* law = model.laws[l].law.get();
    Site site;
    site.dof = model.laws[l].dofs[0];
    if (const auto capability = smoothFlowSite(*law)) {  // the law's registry entry
      using Declared = SmoothFlowSite::Kind;
      site.kind = capability->kind == Declared::kCubic    ? Kind::kCubic
                  : capability->kind == Declared::kPlanar ? Kind::kPlanar
                                                          : Kind::kStribeck;
      if (site.kind == Kind::kPlanar) site.second_dof = model.laws[l].dofs[1];
      site.coefficient = capability->coefficient;
      site.drop = capability->drop;
      site.v_s = capability->v_s;
    } else {
      throwInputError("law[" + std::to_string(l) + "].type", law->type(),
                      "exact orbits handle coulomb-1d, signorini (closed form), cubic, coulomb-2d, stribeck "
                      "and coulomb-1d (smooth phases) laws; signorini does not mix with the smooth ones");
    }
    components_ += site.components();
    sites_.push_back(site);
  }
  double rate = std::max(std::sqrt((mass_inverse_ * stiffness_).cwiseAbs().rowwise().sum().maxCoeff()),
                         (mass_inverse_ * damping_).cwiseAbs().rowwise().sum().maxCoeff());
  for (const auto& load : loads_) rate = std::max(rate, load.harmonic * omega_);
  rate_ = std::max(rate, omega_);
  double force = 0.0;
  for (const auto& load : loads_) force += std::abs(load.cos_amplitude) + std::abs(load.sin_amplitude);
  for (const Site& site : sites_)
    if (site.kind != Kind::kCubic) force += site.coefficient + site.drop;
  acceleration_scale_ = mass_inverse_.cwiseAbs().rowwise().sum().maxCoeff() * force;
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
  const int g = static_cast<int>(c.dofs.size());
  c.projector = mass_inverse_;
  c.multiplier = Eigen::MatrixXd::Zero(g, n_);
  if (g > 0) {
    Eigen::MatrixXd select = Eigen::MatrixXd::Zero(g, n_);
    for (int i = 0; i < g; ++i) select(i, c.dofs[i]) = 1.0;
    const Eigen::MatrixXd pm = select * mass_inverse_;  // P M⁻¹
    c.multiplier = -(pm * select.transpose()).ldlt().solve(pm);
    c.projector = mass_inverse_ + mass_inverse_ * select.transpose() * c.multiplier;
  }
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
  b.noalias() -= stiffness_ * y.head(n_) + damping_ * y.tail(n_);
  if (db) {
    db->resize(n_, 2 * n_);
    *db << -stiffness_, -damping_;
  }
  const double speed_floor = kRestSpeed * (1.0 + y.tail(n_).cwiseAbs().maxCoeff());
  for (size_t s = 0; s < sites_.size(); ++s) {
    const Site& site = sites_[s];
    // Stuck sites act through λ; a friction site marked smooth is left out
    // (the restart guess adds its force itself).
    if (modes[s] == Mode::kStick || (site.kind != Kind::kCubic && modes[s] == Mode::kSmooth)) continue;
    if (site.kind == Kind::kCubic) {
      const double x = y[site.dof];
      b[site.dof] -= site.coefficient * x * x * x;
      if (db) (*db)(site.dof, site.dof) -= 3.0 * site.coefficient * x * x;
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

bool SmoothFlow::restartGuess(double t, const Eigen::VectorXd& y, const Modes& modes, Eigen::VectorXd& a0,
                              Eigen::VectorXd& jerk) const {
  // The planar sites at rest, held: λ and its rate.
  Modes held = modes;
  for (size_t s = 0; s < sites_.size(); ++s)
    if (sites_[s].kind == Kind::kPlanar && modes[s] == Mode::kSlide && y[n_ + sites_[s].dof] == 0.0 &&
        y[n_ + sites_[s].second_dof] == 0.0)
      held[s] = Mode::kStick;
  Eigen::VectorXd b, df, dy;
  Eigen::MatrixXd db;
  if (held == modes || !freeForce(t, y, held, b, &db)) return false;
  const Constraint& c = constraint(held);
  Eigen::VectorXd f0;
  if (!field(t, y, held, f0, nullptr)) return false;
  forcing(t, dy, &df);
  const Eigen::VectorXd lambda = c.multiplier * b, lambda_rate = c.multiplier * (df + db * f0);
  // Saturated friction μN λ̂ in place of λ: a0 = M⁻¹(b + Pᵀ μN λ̂); the
  // excess grows at d‖λ‖/dt, pushing along −λ̂.
  Eigen::VectorXd saturated = Eigen::VectorXd::Zero(n_), growth = Eigen::VectorXd::Zero(n_);
  for (size_t s = 0; s < sites_.size(); ++s) {
    if (held[s] == modes[s]) continue;
    const int row = c.first_row[s];
    const Eigen::Vector2d l = lambda.segment<2>(row);
    const double norm = l.norm();
    if (!(norm > 0.0)) return false;
    const Eigen::Vector2d unit = l / norm;
    const double rate = std::max(unit.dot(lambda_rate.segment<2>(row)), 0.0);
    saturated[sites_[s].dof] += sites_[s].coefficient * unit[0];
    saturated[sites_[s].second_dof] += sites_[s].coefficient * unit[1];
    growth[sites_[s].dof] -= rate * unit[0];
    growth[sites_[s].second_dof] -= rate * unit[1];
  }
  // The other stuck sites stay held.
  Modes others = modes;
  Eigen::VectorXd b_others;
  for (size_t s = 0; s < sites_.size(); ++s)
    if (held[s] != modes[s]) others[s] = Mode::kSmooth;  // excluded from b, its force added below
  if (!freeForce(t, y, others, b_others, nullptr)) return false;
  const Constraint& co = constraint(others);
  a0 = co.projector * (b_others + saturated);
  jerk = co.projector * growth;
  return true;
}

bool SmoothFlow::step(double t, const Eigen::VectorXd& y, double h, const Modes& modes, Eigen::VectorXd& y1,
                      Eigen::MatrixXd* dy1) const {
  const int d = 2 * n_;
  Eigen::VectorXd k(3 * d), stage(d), fi;
  Eigen::VectorXd f0;
  if (field(t, y, modes, f0, nullptr)) {
    for (int i = 0; i < 3; ++i) k.segment(i * d, d) = f0;
  } else {
    Eigen::VectorXd a0, jerk;
    if (!restartGuess(t, y, modes, a0, jerk)) return false;
    for (int i = 0; i < 3; ++i) {
      const double tau = kC[i] * h;
      k.segment(i * d, n_) = y.tail(n_) + tau * a0 + 0.5 * tau * tau * jerk;
      k.segment(i * d + n_, n_) = a0 + tau * jerk;
    }
  }
  Eigen::MatrixXd jac[3];
  Eigen::MatrixXd newton(3 * d, 3 * d);
  Eigen::VectorXd residual(3 * d);
  bool converged = false;
  for (int it = 0; it < 30; ++it) {
    for (int i = 0; i < 3; ++i) {
      stage = y;
      for (int j = 0; j < 3; ++j) stage += h * kA[i][j] * k.segment(j * d, d);
      if (!field(t + kC[i] * h, stage, modes, fi, &jac[i])) return false;
      residual.segment(i * d, d) = k.segment(i * d, d) - fi;
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) newton.block(i * d, j * d, d, d) = -h * kA[i][j] * jac[i];
    newton.diagonal().array() += 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(newton);
    const Eigen::VectorXd delta = lu.solve(residual);
    k -= delta;
    if (!k.allFinite()) return false;
    // Converged at round-off of the stage derivatives, whose scale is at
    // least the state's times the fastest rate and the accelerations the
    // loads and friction limits give (forces that cancel near rest leave
    // round-off of that size).
    const double k_scale = std::max({k.cwiseAbs().maxCoeff(), rate_ * y.cwiseAbs().maxCoeff(), acceleration_scale_});
    if (delta.cwiseAbs().maxCoeff() <= 4.0 * std::numeric_limits<double>::epsilon() * (k_scale + 1e-300)) {
      converged = true;
      if (dy1) {
        // Derivative of the converged stages (the last Newton matrix is at
        // the iterate before the final correction, which is at round-off).
        Eigen::MatrixXd rhs(3 * d, d);
        for (int i = 0; i < 3; ++i) rhs.middleRows(i * d, d) = jac[i];
        const Eigen::MatrixXd dk = lu.solve(rhs);
        *dy1 = Eigen::MatrixXd::Identity(d, d);
        for (int i = 0; i < 3; ++i) *dy1 += h * kB[i] * dk.middleRows(i * d, d);
      }
      break;
    }
  }
  if (!converged) return false;
  y1 = y;
  for (int i = 0; i < 3; ++i) y1 += h * kB[i] * k.segment(i * d, d);
  return y1.allFinite();
}

FlowResult SmoothFlow::integrate(const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
                                 FlowSamples* samples) const {
  FlowResult result;
  const int d = 2 * n_;
  if (y0.size() != d || !y0.allFinite() || !(duration >= 0.0) || !std::isfinite(t0)) {
    result.failure = "initial state or interval not finite or of the wrong size";
    return result;
  }
  Modes modes = initialModes(t0, y0);
  Eigen::VectorXd y = y0;
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Identity(d, d);
  // A state starting stuck: perturbations off the constraint return to it
  // at once (the stop saltation at t0).
  for (int dof : constraint(modes).dofs) {
    jacobian.row(n_ + dof).setZero();
    y[n_ + dof] = 0.0;
  }
  result.max_abs = y0.head(n_).cwiseAbs();
  if (samples) {
    samples->displacement.resize(samples->times.size(), n_);
    samples->velocity.resize(samples->times.size(), n_);
    samples->force.resize(samples->times.size(), components_);
  }
  size_t next_sample = 0;
  const double t_end = t0 + duration, time_scale = std::abs(t0) + std::max(duration, period());
  const double max_step = std::min(period() / 32.0, 0.2 / rate_);
  double t = t0, h = std::min(duration, 0.05 / rate_), rest_limit = std::numeric_limits<double>::infinity();
  int steps = 0, events = 0, immediate = 0;

  // Extremes of x_i (zeros of v_i) and samples over [t, t + span] of the
  // current phase, by one Gauss step from t.
  auto record = [&](double span, const Eigen::VectorXd& y_end) {
    auto at = [&](double tau) {
      Eigen::VectorXd out;
      if (tau <= 0.0) return y;
      if (tau >= span || !step(t, y, tau, modes, out, nullptr)) return y_end;
      return out;
    };
    for (int i = 0; i < n_; ++i) {
      result.max_abs[i] = std::max(result.max_abs[i], std::abs(y_end[i]));
      const double va = y[n_ + i], vb = y_end[n_ + i];
      if ((va > 0.0) != (vb > 0.0) && va != 0.0 && vb != 0.0) {
        double lo = 0.0, hi = span;
        for (int it = 0; it < 60 && hi - lo > 1e-15 * time_scale; ++it) {
          const double mid = 0.5 * (lo + hi);
          ((at(mid)[n_ + i] > 0.0) == (va > 0.0) ? lo : hi) = mid;
        }
        result.max_abs[i] = std::max(result.max_abs[i], std::abs(at(hi)[i]));
      }
    }
    if (!samples) return;
    for (; next_sample < samples->times.size() && samples->times[next_sample] <= t + span; ++next_sample) {
      const Eigen::VectorXd ys = at(samples->times[next_sample] - t);
      samples->displacement.row(next_sample) = ys.head(n_).transpose();
      samples->velocity.row(next_sample) = ys.tail(n_).transpose();
      int q = 0;
      for (size_t s = 0; s < sites_.size(); ++s) {
        const Eigen::VectorXd f = siteForce(static_cast<int>(s), samples->times[next_sample], ys, modes);
        for (int k = 0; k < f.size(); ++k) samples->force(next_sample, q++) = f[k];
      }
    }
  };
  // The event at (t, y) (y after any reset of v): new modes, saltation.
  auto applyEvent = [&](const Modes& before, const Modes& after, const Eigen::VectorXd& y_before,
                        const Eigen::RowVectorXd& gradient, double g_rate, const std::string& kind) {
    ++result.events[kind];
    if (!with_jacobian) return;
    Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(d, d);
    for (int dof : constraint(after).dofs) reset(n_ + dof, n_ + dof) = 0.0;
    Eigen::VectorXd f_before, f_after;
    if (!field(t, y_before, before, f_before, nullptr)) f_before = Eigen::VectorXd::Zero(d);
    // A slide from rest starts with the sticking force: the field is
    // continuous across the release.
    if (!field(t, y, after, f_after, nullptr)) f_after = f_before;
    if (g_rate != 0.0) jacobian = (reset + (f_after - reset * f_before) * gradient / g_rate) * jacobian;
    else jacobian = reset * jacobian;
  };

  Eigen::VectorXd big, half, small, quarter, y_event;
  Eigen::MatrixXd d_half, d_small, d_a, d_b;
  while (t < t_end) {
    const double span = std::min({h, t_end - t, rest_limit, max_step});
    if (++steps > kMaxSteps || span <= 1e-15 * time_scale) {
      result.failure = "step size underflow at t = " + formatNumber(t);
      for (size_t s = 0; s < sites_.size(); ++s)
        if (sites_[s].kind == Kind::kPlanar && modes[s] == Mode::kSlide && y[n_ + sites_[s].dof] == 0.0 &&
            y[n_ + sites_[s].second_dof] == 0.0)
          result.failure = "planar slide from rest at t = " + formatNumber(t) + " (law " + std::to_string(s + 1) +
                           ") too brief: its speed stays below round-off";
      return result;
    }
    // Step doubling: one step of h against two of h/2.
    const bool ok = step(t, y, span, modes, big, nullptr) &&
                    step(t, y, 0.5 * span, modes, half, with_jacobian ? &d_half : nullptr) &&
                    step(t + 0.5 * span, half, 0.5 * span, modes, small, with_jacobian ? &d_small : nullptr);
    if (!ok) {
      h = 0.25 * span;
      continue;
    }
    const double error = (big - small).cwiseAbs().maxCoeff() / 63.0;
    const double scale = std::max(1.0, small.cwiseAbs().maxCoeff());
    const double grow = error > 0 ? 0.9 * std::pow(kLocalTolerance * scale / error, 1.0 / 7.0) : 2.0;
    if (error > kLocalTolerance * scale) {
      h = span * std::max(0.2, grow);
      continue;
    }
    // A planar slide whose velocity turned by more than a right angle went
    // through rest inside the step: shorter steps.
    bool through_rest = false;
    for (size_t s = 0; s < sites_.size(); ++s) {
      const Site& site = sites_[s];
      if (site.kind == Kind::kPlanar && modes[s] == Mode::kSlide &&
          y[n_ + site.dof] * small[n_ + site.dof] + y[n_ + site.second_dof] * small[n_ + site.second_dof] < 0.0)
        through_rest = true;
    }
    if (through_rest) {
      h = 0.5 * span;
      rest_limit = std::min(rest_limit, h);
      continue;
    }
    // Sign-change events: bracketed at the half and the end of the step.
    const std::vector<Watch> watch = watches(modes);
    int fired = -1;
    double tau_event = span;
    for (size_t e = 0; e < watch.size(); ++e) {
      const double g_half = eventValue(watch[e], t + 0.5 * span, half, modes, nullptr, nullptr);
      const double g_end = eventValue(watch[e], t + span, small, modes, nullptr, nullptr);
      // y(τ) on the Gauss solution: two steps of τ/2 from t, as the step.
      auto state = [&](double tau) -> const Eigen::VectorXd* {
        if (tau <= 0.0) return &y;
        if (!step(t, y, 0.5 * tau, modes, quarter, nullptr) || !step(t + 0.5 * tau, quarter, 0.5 * tau, modes, big, nullptr))
          return nullptr;
        return &big;
      };
      auto g = [&](double tau) {
        const Eigen::VectorXd* at = state(tau);
        return at ? eventValue(watch[e], t + tau, *at, modes, nullptr, nullptr) : std::numeric_limits<double>::quiet_NaN();
      };
      double lo = 0.0, hi = g_half > 0.0 ? span : 0.5 * span;
      if (g_half > 0.0 && g_end > 0.0) {
        // Positive at the three points, g may still dip below 0 inside a
        // half (a pair of zeros closer than the step: a brief excursion of
        // the stick force, a velocity just touching 0). Where ġ goes from −
        // to + lies a minimum; if g <= 0 there, the first zero is before it.
        auto slope = [&](double tau, const Eigen::VectorXd& at) {
          Eigen::RowVectorXd gradient;
          double time_derivative = 0.0;
          Eigen::VectorXd f;
          eventValue(watch[e], t + tau, at, modes, &gradient, &time_derivative);
          return field(t + tau, at, modes, f, nullptr) ? time_derivative + gradient.dot(f) : 0.0;
        };
        const double s0 = slope(0.0, y), s1 = slope(0.5 * span, half), s2 = slope(span, small);
        double a = 0.0, b = 0.0;
        if (s0 < 0.0 && s1 > 0.0) b = 0.5 * span;
        else if (s1 < 0.0 && s2 > 0.0) a = 0.5 * span, b = span;
        else continue;
        for (int it = 0; it < 100 && b - a > 4.0 * std::numeric_limits<double>::epsilon() * time_scale; ++it) {
          const double mid = 0.5 * (a + b);
          const Eigen::VectorXd* at = state(mid);
          if (!at) break;
          (slope(mid, *at) < 0.0 ? a : b) = mid;
        }
        if (!(g(b) <= 0.0)) continue;  // passes by without reaching 0
        hi = b;
      }
      double g_lo = g(0.0), g_hi = g(hi);
      if (!(g_hi <= 0.0)) continue;
      if (!(g_lo > 0.0)) {
        // Leaves its set at once: the event fires at the start.
        hi = 0.0;
      } else {
        int side = 0;
        for (int it = 0; it < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * time_scale; ++it) {
          double tau = hi - g_hi * (hi - lo) / (g_hi - g_lo);
          if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
          const double value = g(tau);
          if (std::isnan(value)) break;
          if (value > 0.0) {
            lo = tau;
            g_lo = value;
            if (side == -1) g_hi *= 0.5;  // Illinois
            side = -1;
          } else {
            hi = tau;
            g_hi = value;
            if (side == 1) g_lo *= 0.5;
            side = 1;
            if (value == 0.0) break;
          }
        }
      }
      if (fired < 0 || hi < tau_event) {
        fired = static_cast<int>(e);
        tau_event = hi;
      }
    }
    if (fired >= 0) {
      if (tau_event <= 0.0) {
        if (++immediate > kMaxImmediateEvents) {
          result.failure = "no consistent phase at t = " + formatNumber(t) + " (" + watch[fired].kind + ", law " +
                           std::to_string(watch[fired].site + 1) + ")";
          return result;
        }
        y_event = y;
        d_b = Eigen::MatrixXd::Identity(d, d);
        d_a = d_b;
      } else if (!step(t, y, 0.5 * tau_event, modes, quarter, with_jacobian ? &d_a : nullptr) ||
                 !step(t + 0.5 * tau_event, quarter, 0.5 * tau_event, modes, y_event, with_jacobian ? &d_b : nullptr)) {
        h = 0.5 * span;
        continue;
      } else {
        immediate = 0;
      }
      if (++events > kMaxEvents) {
        result.failure = "more than " + std::to_string(kMaxEvents) + " events: accumulation of stick-slip";
        return result;
      }
      record(tau_event, y_event);
      if (with_jacobian) jacobian = d_b * d_a * jacobian;
      t += tau_event;
      y = y_event;
      const Watch& w = watch[fired];
      Eigen::RowVectorXd gradient;
      double g_time = 0.0;
      eventValue(w, t, y, modes, &gradient, &g_time);
      Eigen::VectorXd f_before;
      const double g_rate = field(t, y, modes, f_before, nullptr) ? g_time + gradient.dot(f_before) : 0.0;
      const Eigen::VectorXd y_before = y;
      Modes after = modes;
      std::string kind = w.kind;
      const Site& site = sites_[w.site];
      if (w.kind == "stop") {  // Stribeck velocity through 0
        y[n_ + site.dof] = 0.0;
        after = restModes(w.site, t, y, modes);
        kind = after[w.site] == Mode::kStick ? "stick" : "reversal";
      } else if (site.kind == Kind::kPlanar) {
        after[w.site] = Mode::kSlide;
      } else {
        after[w.site] = w.branch > 0 ? Mode::kSlipNegative : Mode::kSlipPositive;
      }
      applyEvent(modes, after, y_before, gradient, g_rate, kind);
      modes = after;
      h = std::max(span, 0.01 / rate_);
      rest_limit = std::numeric_limits<double>::infinity();
      continue;
    }
    record(span, small);
    if (with_jacobian) jacobian = d_small * d_half * jacobian;
    t += span;
    y = small;
    h = span * std::min(2.0, grow);
    rest_limit = std::numeric_limits<double>::infinity();
    // Planar slides heading to rest: d‖v‖/dt = v̂ · a.
    Eigen::VectorXd f;
    if (!field(t, y, modes, f, nullptr)) {
      result.failure = "planar friction at rest in a slide at t = " + formatNumber(t);
      return result;
    }
    for (size_t s = 0; s < sites_.size(); ++s) {
      const Site& site = sites_[s];
      if (site.kind != Kind::kPlanar || modes[s] != Mode::kSlide) continue;
      const Eigen::Vector2d v(y[n_ + site.dof], y[n_ + site.second_dof]),
          a(f[n_ + site.dof], f[n_ + site.second_dof]);
      const double speed = v.norm(), rate = v.dot(a) / speed;
      if (!(rate < 0.0)) continue;
      const double to_rest = speed / -rate;
      // Rest when the predicted time to it is tiny, or the speed is within
      // a hundred times the round-off floor of the field (slow approaches).
      const bool resting = to_rest <= kRestTime * time_scale ||
                           speed <= 100.0 * kRestSpeed * (1.0 + y.tail(n_).cwiseAbs().maxCoeff());
      if (!resting || t + to_rest >= t_end) {
        rest_limit = std::min(rest_limit, 0.9 * to_rest);
        continue;
      }
      // At rest: linear extrapolation over the remaining to_rest.
      if (++events > kMaxEvents) {
        result.failure = "more than " + std::to_string(kMaxEvents) + " events: accumulation of stick-slip";
        return result;
      }
      Eigen::RowVectorXd gradient = Eigen::RowVectorXd::Zero(d);
      gradient[n_ + site.dof] = v[0] / speed;
      gradient[n_ + site.second_dof] = v[1] / speed;
      const Eigen::VectorXd y_before = y;
      record(to_rest, y + to_rest * f);
      y += to_rest * f;
      t += to_rest;
      y[n_ + site.dof] = y[n_ + site.second_dof] = 0.0;
      const Modes after = restModes(static_cast<int>(s), t, y, modes);
      // The saltation uses the field just before rest (its limit).
      const double t_rest = t;
      t -= to_rest;
      const Eigen::VectorXd y_rest = y;
      y = y_before;
      Eigen::VectorXd f_after;
      ++result.events[after[s] == Mode::kStick ? "stick" : "reversal"];
      if (with_jacobian) {
        Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(d, d);
        for (int dof : constraint(after).dofs) reset(n_ + dof, n_ + dof) = 0.0;
        if (!field(t_rest, y_rest, after, f_after, nullptr)) f_after = reset * f;
        jacobian = (reset + (f_after - reset * f) * gradient / rate) * jacobian;
      }
      t = t_rest;
      y = y_rest;
      modes = after;
      rest_limit = std::numeric_limits<double>::infinity();
      h = std::max(h, 0.01 / rate_);
      break;
    }
  }
  result.end = y;
  if (with_jacobian) result.jacobian = jacobian;
  result.ok = true;
  result.phases = 1 + static_cast<int>(events);
  return result;
}

}  // namespace eqhb::orbits
