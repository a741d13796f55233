// The pseudo-arclength sweep behind sweepArclength (continuation.h), in
// three files: its loop and the tests on each point found (arclength.cpp),
// the ways on where the curve cannot be followed (arclength_recovery.cpp),
// and the record of the points and of why it stopped (arclength_record.cpp).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "eqhb/continuation/arclength_steps.h"
#include "eqhb/continuation/bordered_system.h"
#include "eqhb/continuation/continuation.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb::arclength {

// The scale of z never drops below this fraction of the largest magnitude
// met so far, or of the problem's own size of z (HbSystem::unknownScale):
// near rest (an antiresonance) a relative scale would blow up, and on a
// stretch where every law is idle (a contact not yet reached) the condensed
// unknowns are exactly zero: a floor from ‖z‖ alone would make the first
// contact force infinitely large in the scaled unknowns.
constexpr double kScaleFloorFraction = 1e-3;

// A corrected point lies within this many steps of the current one (a
// corrector that went further left the curve).
constexpr double kLocalReach = 2.0;

// Where a bridge tries its fixed-ω point: these fractions of the range ahead.
constexpr double kBridgeFractions[] = {1e-3, 1e-2, 3e-2};

struct ArcPoint {
  Eigen::VectorXd z;
  double omega = 0.0;
  Eigen::VectorXd direction;  // tangent (dz, dω) in physical units
};

std::string at(double omega);

// What the loop does after a step or a test: go on with the point found,
// try again from the current point (the step halved, or bridged), or stop
// (the reason recorded).
enum class Next { kGoOn, kRetry, kStop };

// One step from the current point: the scales and the scaled point ŷ and
// tangent τ it starts from, the corrector's result ŷ_new, and what the
// tests find at ŷ_new.
struct Trial {
  ArcScales s;
  Eigen::VectorXd y, t;
  SolverResult r;
  double omega_new = 0.0;
  Eigen::VectorXd t_new;  // the tangent at ŷ_new (the secant where the Jacobian gives none)
  bool regular = true;    // the bordered Jacobian at ŷ_new is regular
  double turn = 0.0;      // the angle from τ to t_new
};

class ArclengthSweep {
 public:
  ArclengthSweep(const HbModel& model, Solver& solver, const SolverOptions& solver_options,
                 const ContinuationOptions& options, const Progress& progress);
  Curve run();

 private:
  // arclength.cpp: the first point and the loop.
  bool startCurve();
  void trace();
  Trial predictAndCorrect();
  SolverResult correct(const ArcScales& s, const Eigen::VectorXd& y, const Eigen::VectorXd& t);
  // The named tests on a step, each kGoOn where the point passes.
  Next correctorConverged(const Trial& trial);
  Next insideTheRange(Trial& trial);
  Next leftAtTheStart();
  Next tangentFound(Trial& trial);
  Next turnedLittle(Trial& trial);
  Next notRetracing(const Trial& trial);
  void accept(const Trial& trial);
  Next bridgeOrStop(const std::string& reason);
  Next goOnFromTheNewPoint();
  std::string remedies() const;

  // arclength_recovery.cpp: where the curve cannot be followed.
  bool bridge(double heading);
  bool bridgeFromTheFrontier();
  std::string branchEnd(const Trial& trial);
  TracedPath wholeCurve() const;
  bool switchToFullSystem();
  bool refineSamples();
  SolverResult correctAtFixedOmega(const ArcScales& s, const Eigen::VectorXd& current, const Eigen::VectorXd& tangent,
                                   double step);
  bool secantTangent(const ArcScales& s, double heading, Eigen::VectorXd* tangent);
  bool landOnTheEnd(const ArcScales& s, const Eigen::VectorXd& y, const Eigen::VectorXd& y_new, double step);

  // arclength_record.cpp: scales, points and the stop reason.
  ArcScales scales() const;
  double scaleFloor(double also) const;
  void record(const ArcPoint& point, const SolverResult& r, double tangent_omega, const std::string& fallback = "");
  void finishAtTheEnd();
  void stop(const std::string& reason);
  // "; law 1's force ... is not resolved ..." from the curve's worst-resolved point, or empty.
  std::string unresolvedAlongTheCurve() const;

  HbModel model_;
  Solver& solver_;
  const SolverOptions& solver_options_;
  const ContinuationOptions& options_;
  const Progress& progress_;
  double lo_, hi_, direction_;
  std::unique_ptr<HbSystem> system_;
  int n_ = 0;
  ArcPoint current_;
  double largest_norm_ = 0.0;
  double unknown_scale_ = 0.0;  // HbSystem::unknownScale at the start
  ArclengthStep step_;
  KinkTest kink_;
  FoldWatch folds_;
  TracedPath traced_;
  bool by_omega_ = false;             // the corrector holds ω (correctAtFixedOmega)
  std::vector<std::string> bridged_;  // "ω_from -> ω_to" of each bridge
  double ended_at_ = NAN;             // ω where branchEnd found the branch ends (the next bridge's start)
  std::string full_from_;             // ω where the sweep went on on the full system
  int scene_samples_ = 0;             // N of the model given (refineSamples raises model_.samples)
  std::vector<std::string> refined_;  // "N = 2048 from omega = ..." of each refinement
  Curve curve_;
};

}  // namespace eqhb::arclength
