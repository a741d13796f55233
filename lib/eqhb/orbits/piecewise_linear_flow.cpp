#include "eqhb/orbits/piecewise_linear_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "eqhb/error.h"
#include "eqhb/laws/law_registry.h"

namespace eqhb::orbits {

namespace {

// Most events in one integration: beyond, impacts or stick-slip accumulate.
constexpr int kMaxEvents = 200000;
// Most events in a row at one instant before the phase is called inconsistent.
constexpr int kMaxImmediateEvents = 8;
// A constraint force within this fraction of its limit is on the limit.
constexpr double kTieTolerance = 1e-13;

// Zero of g(τ) = cᵀ exp(Â (τ − a)) z_a on (a, b] with g(a) > 0 >= g(b):
// Newton on the exact exponential, kept inside the bracket by bisection, to
// round-off in τ. Returns the first τ with g(τ) <= 0 and the state there.
double locateZero(const Eigen::RowVectorXd& c, const Eigen::MatrixXd& generator, const Eigen::VectorXd& z_a,
                  double a, double b, double time_scale, Eigen::VectorXd* z_root) {
  double lo = a, hi = b;
  const double g_lo = c.dot(z_a);
  Eigen::VectorXd z_hi = (generator * (b - a)).exp() * z_a;
  double g_hi = c.dot(z_hi);
  double tau = hi - g_hi * (hi - lo) / (g_hi - g_lo);  // secant start
  const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * time_scale;
  for (int it = 0; it < 200 && hi - lo > tolerance; ++it) {
    if (!(tau > lo && tau < hi)) tau = 0.5 * (lo + hi);
    const Eigen::VectorXd z = (generator * (tau - a)).exp() * z_a;
    const double g = c.dot(z);
    if (g > 0.0) {
      lo = tau;
    } else {
      hi = tau;
      z_hi = z;
      g_hi = g;
      if (g == 0.0) break;
    }
    const double slope = c.dot(generator * z);
    const double next = slope != 0.0 ? tau - g / slope : 0.5 * (lo + hi);
    // A Newton step that barely moves a bracket end is replaced by bisection
    // when it stalls on one side.
    tau = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
  }
  *z_root = z_hi;
  return hi;
}

}  // namespace

bool PiecewiseLinearFlow::supports(const HbModel& model) {
  for (const auto& attached : model.laws)
    if (!piecewiseLinearSite(*attached.law)) return false;
  return true;
}

PiecewiseLinearFlow::PiecewiseLinearFlow(const HbModel& model, double restitution)
    : restitution_(restitution) {
  model.validate();
  if (!(restitution >= 0.0 && restitution <= 1.0))
    throwInputError("restitution", formatNumber(restitution), "must be in [0, 1]");
  const LinearStructure& s = model.structure;
  n_ = s.dofs();
  omega_ = model.omega;
  // Massless DOFs would make the phases differential-algebraic.
  const Eigen::LLT<Eigen::MatrixXd> mass_factor{Eigen::MatrixXd(s.mass)};
  if (mass_factor.info() != Eigen::Success || mass_factor.matrixL().toDenseMatrix().diagonal().minCoeff() <= 0.0)
    throwInputError("structure.mass", "singular", "exact orbits need a positive definite mass (no massless DOFs)");
  mass_inverse_ = mass_factor.solve(Eigen::MatrixXd::Identity(n_, n_));
  damping_ = s.damping;
  stiffness_ = s.stiffness;
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
    site.dof = model.laws[l].dofs[0];
    if (const auto capability = piecewiseLinearSite(*law)) {  // the law's registry entry
      site.contact = capability->contact;
      site.limit = capability->limit;
      site.gap = capability->gap;
      site.stiffness = capability->stiffness;
      if (site.stiffness > 0.0) site.slider = m_++;
    } else {
      throwInputError("law[" + std::to_string(l) + "].type", law->type(),
                      "exact orbits handle coulomb-1d, jenkins on 1 DOF, signorini (closed form), cubic, coulomb-2d, stribeck "
                      "and coulomb-1d (smooth phases) laws; signorini does not mix with the smooth ones");
    }
    sites_.push_back(site);
  }
  nz_ = m_ + 1 + 2 * static_cast<int>(harmonics_.size());
  // Fastest rate: natural frequency bound, damping rate, forcing.
  Eigen::MatrixXd stuck_stiffness = stiffness_;  // with every elastic slider stuck
  for (const LawSite& site : sites_)
    if (site.slider >= 0) stuck_stiffness(site.dof, site.dof) += site.stiffness;
  double rate = std::max(std::sqrt((mass_inverse_ * stuck_stiffness).cwiseAbs().rowwise().sum().maxCoeff()),
                         (mass_inverse_ * damping_).cwiseAbs().rowwise().sum().maxCoeff());
  for (int k : harmonics_) rate = std::max(rate, k * omega_);
  rate_ = std::max(rate, omega_);
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
    if (sites_[l].slider < 0 && (modes[l] == Mode::kStick || modes[l] == Mode::kClosed)) p.constrained.push_back(dof);
  }
  // b = B z: the force on the structure except the constraint forces.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n_, nz_);
  b.leftCols(n_) = -stiffness_;
  b.middleCols(n_, n_) = -damping_;
  // A stuck elastic slider: force −k_t (x − w) on its DOF.
  for (size_t l = 0; l < sites_.size(); ++l)
    if (sites_[l].slider >= 0 && modes[l] == Mode::kStick) {
      b(sites_[l].dof, sites_[l].dof) -= sites_[l].stiffness;
      b(sites_[l].dof, sites_[l].slider) += sites_[l].stiffness;
    }
  b.col(m_) = constant_load_ + sliding;
  for (size_t h = 0; h < harmonics_.size(); ++h) {
    b.col(m_ + 1 + 2 * h) = cos_load_[h];
    b.col(m_ + 2 + 2 * h) = sin_load_[h];
  }
  Eigen::MatrixXd q = mass_inverse_;
  const int g = static_cast<int>(p.constrained.size());
  p.constraint_force = Eigen::MatrixXd::Zero(g, nz_);
  if (g > 0) {
    Eigen::MatrixXd select = Eigen::MatrixXd::Zero(g, n_);
    for (int i = 0; i < g; ++i) select(i, p.constrained[i]) = 1.0;
    const Eigen::MatrixXd pm = select * mass_inverse_;  // P M⁻¹
    const Eigen::MatrixXd multiplier = -(pm * select.transpose()).ldlt().solve(pm);  // −(P M⁻¹ Pᵀ)⁻¹ P M⁻¹
    q = mass_inverse_ + mass_inverse_ * select.transpose() * multiplier;
    p.constraint_force = multiplier * b;
  }
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
        e.kind = "impact";
        out.push_back(e);
        break;
      case Mode::kClosed:
        e.functional = -constraintRow(site.dof);  // pressure p = −(force on the structure)
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
    if (site.slider >= 0) {
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
      if (!free_choice[l] || sites_[l].slider >= 0 || (modes[l] != Mode::kStick && modes[l] != Mode::kClosed)) continue;
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
  switch (mode) {
    case Mode::kSlipPositive: return -site.limit;
    case Mode::kSlipNegative: return site.limit;
    case Mode::kOpen: return 0.0;
    case Mode::kStick:
      if (site.slider >= 0) return springForceRow(site).dot(z);
      [[fallthrough]];
    case Mode::kClosed: {
      const auto i = std::find(p.constrained.begin(), p.constrained.end(), site.dof) - p.constrained.begin();
      const double f = p.constraint_force.row(i).dot(z);
      return mode == Mode::kClosed ? -f : f;
    }
  }
  return 0.0;
}

FlowResult PiecewiseLinearFlow::integrate(const Eigen::VectorXd& y0, double t0, double duration,
                                          bool with_jacobian, FlowSamples* samples) const {
  FlowResult result;
  if (y0.size() != m_ || !y0.allFinite() || !(duration >= 0.0) || !std::isfinite(t0)) {
    result.failure = "initial state or interval not finite or of the wrong size";
    return result;
  }
  const int laws = static_cast<int>(sites_.size());
  Eigen::VectorXd z = augment(y0, t0);
  for (const LawSite& site : sites_)
    if (site.contact && z[site.dof] > site.gap) {
      result.failure = "the initial state penetrates the wall (x" + std::to_string(site.dof + 1) + " = " +
                       formatNumber(z[site.dof]) + " > gap " + formatNumber(site.gap) + ")";
      return result;
    }
  std::vector<Mode> modes = chooseModes(z, std::vector<Mode>(laws, Mode::kOpen), std::vector<bool>(laws, true));
  // A slipping elastic slider starts where its spring holds the limit:
  // w = x ∓ μN/k_t (a state beyond the limit is brought back onto it, and
  // a perturbation of w alone does not move the orbit).
  for (int l = 0; l < laws; ++l)
    if (sites_[l].slider >= 0 && modes[l] != Mode::kStick)
      z[sites_[l].slider] =
          z[sites_[l].dof] + (modes[l] == Mode::kSlipPositive ? -1.0 : 1.0) * sites_[l].limit / sites_[l].stiffness;
  Eigen::MatrixXd jacobian;
  if (with_jacobian) {
    // A state starting constrained: perturbations off the constraint return
    // to it at once (the stop / plastic-impact saltation at t0).
    jacobian = Eigen::MatrixXd::Identity(m_, m_);
    for (int l = 0; l < laws; ++l) {
      if (sites_[l].slider < 0 && (modes[l] == Mode::kStick || modes[l] == Mode::kClosed))
        jacobian.row(n_ + sites_[l].dof).setZero();
      if (sites_[l].slider >= 0 && modes[l] != Mode::kStick) {  // δw = δx
        jacobian.row(sites_[l].slider).setZero();
        jacobian(sites_[l].slider, sites_[l].dof) = 1.0;
      }
      if (modes[l] == Mode::kClosed) jacobian.row(sites_[l].dof).setZero();
    }
  }
  result.max_abs = y0.head(n_).cwiseAbs();
  double velocity_scale = std::max(y0.tail(n_).cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  const double t_end = t0 + duration, time_scale = std::abs(t0) + std::max(duration, period());
  size_t next_sample = 0;
  if (samples) {
    const int count = static_cast<int>(samples->times.size());
    samples->displacement.resize(count, n_);
    samples->velocity.resize(count, n_);
    samples->force.resize(count, laws);
  }
  double t = t0;
  int event_count = 0, immediate_events = 0;
  while (true) {
    const Phase& p = phase(modes);
    const std::vector<Event> watch = events(modes, p);
    ++result.phases;
    // March on the grid until an event or the end.
    Eigen::VectorXd z_a = z, z_b;
    double tau_a = 0.0;
    const double span = t_end - t;
    int fired = -1;
    double tau_event = span;
    Eigen::VectorXd z_event;
    while (true) {
      const double tau_b = std::min(tau_a + p.grid, span);
      z_b = (tau_b - tau_a == p.grid) ? Eigen::VectorXd(p.grid_step * z_a)
                                      : Eigen::VectorXd((p.generator * (tau_b - tau_a)).exp() * z_a);
      for (size_t e = 0; e < watch.size(); ++e) {
        const double g_a = watch[e].functional.dot(z_a), g_b = watch[e].functional.dot(z_b);
        Eigen::VectorXd z_root;
        double tau = 0.0;
        if (g_b > 0.0) {
          // Positive at both ends, g may still dip below 0 inside (a pair of
          // zeros closer than the grid: a near-grazing impact, a brief
          // excursion of the stick force). ġ = cᵀÂ z is a linear functional
          // too: where it goes from − to +, its zero is the minimum of g; if
          // g <= 0 there, the first zero lies between the start and it.
          if (!(g_a > 0.0)) continue;
          const Eigen::RowVectorXd slope = watch[e].functional * p.generator;
          if (!(slope.dot(z_a) < 0.0 && slope.dot(z_b) > 0.0)) continue;
          Eigen::VectorXd z_min;
          const double tau_min = locateZero(-slope, p.generator, z_a, tau_a, tau_b, time_scale, &z_min);
          if (watch[e].functional.dot(z_min) > 0.0) continue;  // passes by without reaching 0
          tau = locateZero(watch[e].functional, p.generator, z_a, tau_a, tau_min, time_scale, &z_root);
        } else if (!(g_a > 0.0)) {
          // A phase that leaves its set at once (a tie resolved one order
          // too low): the event fires at its start.
          if (tau_a != 0.0 || g_b == 0.0) continue;
          if (++immediate_events > kMaxImmediateEvents) {
            result.failure = "no consistent phase at t = " + formatNumber(t) + " (" + watch[e].kind + ", law " +
                             std::to_string(watch[e].law + 1) + ")";
            return result;
          }
          z_root = z_a;
        } else {
          tau = locateZero(watch[e].functional, p.generator, z_a, tau_a, tau_b, time_scale, &z_root);
        }
        if (fired < 0 || tau < tau_event) {
          fired = static_cast<int>(e);
          tau_event = tau;
          z_event = z_root;
        }
      }
      const double tau_end = fired >= 0 ? tau_event : tau_b;
      const Eigen::VectorXd& z_end = fired >= 0 ? z_event : z_b;
      // Extremes of x_i: where v_i changes sign inside the interval.
      for (int i = 0; i < n_; ++i) {
        const double va = z_a[n_ + i], vb = z_end[n_ + i];
        result.max_abs[i] = std::max(result.max_abs[i], std::abs(z_end[i]));
        if ((va > 0.0 && vb <= 0.0) || (va < 0.0 && vb >= 0.0)) {
          Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(nz_);
          c[n_ + i] = va > 0.0 ? 1.0 : -1.0;
          Eigen::VectorXd z_turn;
          locateZero(c, p.generator, z_a, tau_a, tau_end, time_scale, &z_turn);
          result.max_abs[i] = std::max(result.max_abs[i], std::abs(z_turn[i]));
        }
      }
      velocity_scale = std::max(velocity_scale, z_end.segment(n_, n_).cwiseAbs().maxCoeff());
      if (samples) {
        for (; next_sample < samples->times.size() && samples->times[next_sample] <= t + tau_end; ++next_sample) {
          const double ts = samples->times[next_sample];
          const Eigen::VectorXd zs = (p.generator * (ts - t - tau_a)).exp() * z_a;
          samples->displacement.row(next_sample) = zs.head(n_).transpose();
          samples->velocity.row(next_sample) = zs.segment(n_, n_).transpose();
          for (int l = 0; l < laws; ++l) samples->force(next_sample, l) = lawForce(l, modes[l], p, zs);
        }
      }
      if (fired >= 0 || tau_b >= span) {
        if (fired < 0) z_event = z_b;
        tau_event = tau_end;
        break;
      }
      tau_a = tau_b;
      z_a = z_b;
    }
    if (tau_event > 0.0) immediate_events = 0;
    if (with_jacobian) jacobian = (p.generator * tau_event).exp().topLeftCorner(m_, m_) * jacobian;
    t += tau_event;
    z = z_event;
    refreshForcing(z, t);
    if (fired < 0) break;

    // The event: reset, new modes, saltation.
    if (++event_count > kMaxEvents) {
      result.failure = "more than " + std::to_string(kMaxEvents) + " events: accumulation of impacts or stick-slip";
      return result;
    }
    const Event& ev = watch[fired];
    const LawSite& site = sites_[ev.law];
    const Eigen::VectorXd f_before = (p.generator * z).head(m_);
    const double g_rate = ev.functional.dot(p.generator * z);
    Eigen::MatrixXd reset = Eigen::MatrixXd::Identity(m_, m_);
    std::vector<bool> free_choice(laws, false);
    std::string kind = ev.kind;
    if (ev.kind == "stop" && site.slider >= 0) {
      // The DOF turns back with the spring force on the limit: the force
      // leaves it inwards, the slider stops (no reset of the state).
      modes[ev.law] = Mode::kStick;
      kind = "stick";
    } else if (ev.kind == "stop") {
      z[n_ + site.dof] = 0.0;
      free_choice[ev.law] = true;
      modes = chooseModes(z, modes, free_choice);
      kind = modes[ev.law] == Mode::kStick ? "stick" : "reversal";
    } else if (ev.kind == "slip") {
      const double r = lawForce(ev.law, Mode::kStick, p, z);
      modes[ev.law] = r > 0.0 ? Mode::kSlipNegative : Mode::kSlipPositive;
    } else if (ev.kind == "impact") {
      z[site.dof] = site.gap;
      const double bounce = -restitution_ * z[n_ + site.dof];
      if (bounce < -kPlasticImpactRatio * velocity_scale) {
        z[n_ + site.dof] = bounce;
        reset(n_ + site.dof, n_ + site.dof) = -restitution_;
        modes[ev.law] = Mode::kOpen;
      } else {
        z[n_ + site.dof] = 0.0;
        reset(n_ + site.dof, n_ + site.dof) = 0.0;
        free_choice[ev.law] = true;
        modes = chooseModes(z, modes, free_choice);
      }
    } else {  // release
      modes[ev.law] = Mode::kOpen;
    }
    ++result.events[kind];
    if (with_jacobian) {
      const Phase& after = phase(modes);
      const Eigen::VectorXd f_after = (after.generator * z).head(m_);
      const Eigen::RowVectorXd gradient = ev.functional.head(m_);
      // A grazing event (ġ = 0) has no saltation term: the event time does
      // not move to first order.
      if (g_rate != 0.0) {
        const Eigen::MatrixXd saltation = reset + (f_after - reset * f_before) * gradient / g_rate;
        jacobian = saltation * jacobian;
      } else {
        jacobian = reset * jacobian;
      }
    }
  }
  result.end = z.head(m_);
  result.jacobian = jacobian;
  result.ok = true;
  return result;
}

}  // namespace eqhb::orbits
