#include "eqhb/laws/joints/friction_kernels.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "eqhb/error.h"
#include "eqhb/laws/form_names.h"

namespace eqhb {

namespace {
constexpr FormName<FrictionForm> kFrictionFormNames[] = {
    {FrictionForm::kMinMax, "minmax"}, {FrictionForm::kProjection, "projection"}, {FrictionForm::kMax, "max"}};
}  // namespace

FrictionForm parseFrictionForm(const std::string& name, const std::string& field) {
  return parseForm(kFrictionFormNames, name, field, "must be minmax (one tangential DOF), projection or max");
}

std::string frictionFormName(FrictionForm form) { return formName(kFrictionFormNames, form); }

namespace {

void friction1D(FrictionForm form, double rho, double u, double r, double limit, FrictionPoint& o) {
  switch (form) {
    case FrictionForm::kMinMax: {
      const MinMaxBranch branch = minMaxBranch(rho, u, r, limit);
      o.psi[0] = branch.psi;
      const double lower = branch.lower ? 1.0 : 0.0, upper = branch.upper ? 1.0 : 0.0;
      o.d_u[0] = 1.0 - lower - upper;
      o.d_r[0] = rho * (lower + upper);
      o.d_limit[0] = rho * (lower - upper);
      break;
    }
    case FrictionForm::kProjection: {
      const double trial = r - rho * u;
      if (std::abs(trial) <= limit) {
        o.psi[0] = rho * u;
        o.d_u[0] = rho, o.d_r[0] = 0.0, o.d_limit[0] = 0.0;
      } else {
        o.psi[0] = r - std::copysign(limit, trial);
        o.d_u[0] = 0.0, o.d_r[0] = 1.0, o.d_limit[0] = -std::copysign(1.0, trial);
      }
      break;
    }
    case FrictionForm::kMax: {
      const double s = r - rho * u, norm = std::abs(s);
      if (norm <= limit) {  // sticking: Ψ = L ρ u
        o.psi[0] = limit * rho * u;
        o.d_u[0] = limit * rho, o.d_r[0] = 0.0, o.d_limit[0] = rho * u;
      } else {  // sliding: Ψ = r |s| − L s
        const double sign = std::copysign(1.0, s);
        o.psi[0] = r * norm - limit * s;
        o.d_r[0] = norm - limit + r * sign;
        o.d_u[0] = limit * rho - rho * r * sign;
        o.d_limit[0] = -s;
      }
      break;
    }
  }
}

void friction2D(FrictionForm form, double rho, const double* u_in, const double* r_in, double limit,
                FrictionPoint& o) {
  const Eigen::Vector2d r(r_in[0], r_in[1]), u(u_in[0], u_in[1]);
  const Eigen::Vector2d s = r - rho * u;
  const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
  Eigen::Vector2d psi, dl = Eigen::Vector2d::Zero();
  Eigen::Matrix2d dr = Eigen::Matrix2d::Zero(), du = Eigen::Matrix2d::Zero();
  const double norm = s.norm();
  if (form == FrictionForm::kProjection) {
    if (norm <= limit) {  // Ψ = ρ u
      psi = rho * u;
      du = rho * identity;
    } else {  // Ψ = r − L s/‖s‖
      const Eigen::Matrix2d dproj = (limit / norm) * (identity - s * s.transpose() / (norm * norm));
      psi = r - limit * s / norm;
      dr = identity - dproj;
      du = rho * dproj;
      dl = -s / norm;
    }
  } else {  // max
    if (norm <= limit) {  // sticking: Ψ = L ρ u
      psi = limit * rho * u;
      du = limit * rho * identity;
      dl = rho * u;
    } else {  // sliding: Ψ = r ‖s‖ − L s
      psi = r * norm - limit * s;
      dr = (norm - limit) * identity + r * s.transpose() / norm;
      du = limit * rho * identity - rho * r * s.transpose() / norm;
      dl = -s;
    }
  }
  for (int a = 0; a < 2; ++a) {
    o.psi[a] = psi[a];
    o.d_limit[a] = dl[a];
    for (int b = 0; b < 2; ++b) {
      o.d_u[a * 2 + b] = du(a, b);
      o.d_r[a * 2 + b] = dr(a, b);
    }
  }
}

}  // namespace

void evaluateFriction(FrictionForm form, int m, double rho, const double* u, const double* r, double limit,
                      FrictionPoint& out) {
  if (m == 1) friction1D(form, rho, u[0], r[0], limit, out);
  else friction2D(form, rho, u, r, limit, out);
}

LocalVector minimiseOnDisc(const LocalMatrix& a, const LocalVector& b, double radius) {
  const Eigen::Index m = b.size();
  LocalVector lambda(m);
  if (m == 1) {
    lambda[0] = std::clamp(-b[0] / a(0, 0), -radius, radius);
    return lambda;
  }
  auto project = [radius](LocalVector& x) {
    const double norm = x.norm();
    if (norm > radius) x *= radius / norm;
  };
  // Step 1/L with L the largest eigenvalue of A: a contraction on the disc.
  const Eigen::Matrix2d a2 = a.topLeftCorner(2, 2);
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(a2).eigenvalues().maxCoeff();
  lambda = -b / largest;
  project(lambda);
  for (int iteration = 0; iteration < 10000; ++iteration) {
    LocalVector next = lambda - (a * lambda + b) / largest;
    project(next);
    const double change = (next - lambda).norm();
    lambda = next;
    if (change <= 1e-15 * std::max(radius, 1e-300)) break;
  }
  return lambda;
}

double scaleFreeFrictionRho(FrictionForm form, double mobility) {
  return kScaleFreeRhoWeight * (form == FrictionForm::kMinMax ? mobility : 1.0 / mobility);
}

double frictionResidualScale(FrictionForm form, double rho, const PhysicalScales& s) {
  switch (form) {
    case FrictionForm::kMinMax: return std::min(s.velocity, rho * s.force);      // u and ρ r
    case FrictionForm::kProjection: return std::min(rho * s.velocity, s.force);  // ρ u and r
    case FrictionForm::kMax: break;
  }
  return s.force * std::min(s.force, rho * s.velocity);  // r‖s‖ and L s
}

}  // namespace eqhb
