// One call of SmoothFlow::integrate (smooth_flow.h): the loop over steps and
// its parts, kept apart —
//   step control      step doubling with the local error test, the cut of a
//                     step in which a planar slide went through rest
//                     (smooth_flow_integration.cpp)
//   event location    sign changes of the watched functions bracketed in the
//                     step, located by the Illinois method
//                     (smooth_flow_event_location.cpp)
//   event handling    the step to the event, the new modes, the saltation;
//                     planar slides brought to rest (smooth_flow_events.cpp)
//   recording         extremes of x_i and the samples over a step
//                     (smooth_flow_integration.cpp)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eqhb/orbits/smooth_flow.h"

namespace eqhb::orbits {

class SmoothFlow::Integration {
 public:
  Integration(const SmoothFlow& flow, const Eigen::VectorXd& y0, double t0, double duration, bool with_jacobian,
              FlowSamples* samples);
  FlowResult run();

 private:
  // ---- step control
  // False, with the failure written, once the steps have become too many or
  // too short.
  bool stepSizeAcceptable(double span);
  // The step of `span` by step doubling into half_ and small_ (the end), with
  // its error below the tolerance; false (h_ cut) otherwise.
  bool stepWithinTolerance(double span);
  // True (h_ and the rest limit cut) if a planar slide went through rest in
  // the step just taken.
  bool passesThroughRest(double span);
  // Moves to the end of the step and sets the next step size.
  void acceptStep(double span);

  // ---- event location
  struct FirstEvent {
    int watch = -1;    // index into the watches, −1 if none fires in the step
    double tau = 0.0;  // time from t_
  };
  FirstEvent locateFirstEvent(const std::vector<Watch>& watch, double span);
  // The first zero of w's function inside the step, if it has one.
  std::optional<double> locateEvent(const Watch& w, double span);
  // Positive at the start, half and end of the step, the function may still
  // dip to 0 between; the instant of its minimum there if it does.
  std::optional<double> dipBelowZero(const Watch& w, double span);
  // Illinois iteration on [lo, hi] with g(lo) = g_lo > 0 >= g(hi) = g_hi;
  // the end hi.
  double illinois(const Watch& w, double lo, double hi, double g_lo, double g_hi);
  double eventFunction(const Watch& w, double tau);
  // dg/dt along the flow at t_ + tau, y_at.
  double eventSlope(const Watch& w, double tau, const Eigen::VectorXd& y_at);
  // y(t_ + tau) on the Gauss solution (two steps of tau/2, as the step), or null.
  const Eigen::VectorXd* stateAt(double tau);

  // ---- event handling
  enum class Outcome { kDone, kRetry, kFailed };
  // Steps to the event tau after t_ and applies it.
  Outcome takeEvent(const Watch& w, double tau, double span);
  // The new modes and the saltation at the event of w just reached.
  void handleEvent(const Watch& w);
  void applyEvent(const Modes& before, const Modes& after, const Eigen::VectorXd& y_before,
                  const Eigen::RowVectorXd& gradient, double g_rate, const std::string& kind);
  // Planar slides heading to rest: rest reached by extrapolation when it is
  // near, the steps limited otherwise; false with the failure written.
  bool bringSlidesToRest();
  void restPlanarSlide(int s, const Eigen::VectorXd& f, double to_rest, double rate);
  bool countEvent();

  // ---- recording
  // Extremes of x_i (zeros of v_i) and samples over [t_, t_ + span] of the
  // current phase, by one Gauss step from t_.
  void record(double span, const Eigen::VectorXd& y_end);
  Eigen::VectorXd stateOnStep(double tau, double span, const Eigen::VectorXd& y_end) const;

  const SmoothFlow& flow_;
  const int n_, d_;
  const bool with_jacobian_;
  FlowSamples* samples_;
  FlowResult result_;
  Modes modes_;
  Eigen::VectorXd y_;
  Eigen::MatrixXd jacobian_;
  double t_ = 0.0, t_end_ = 0.0, time_scale_ = 0.0, max_step_ = 0.0;
  double h_ = 0.0, rest_limit_ = 0.0, grow_ = 0.0;
  int steps_ = 0, events_ = 0, immediate_ = 0;
  size_t next_sample_ = 0;
  // The states of a step: one of h, two of h/2 (half_, then small_ at the
  // end), and their derivatives; scratch states for event location.
  Eigen::VectorXd big_, half_, small_, quarter_, y_event_, scratch_quarter_, scratch_end_;
  Eigen::MatrixXd d_half_, d_small_, d_a_, d_b_;
};

}  // namespace eqhb::orbits
