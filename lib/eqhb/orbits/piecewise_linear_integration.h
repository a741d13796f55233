// One call of PiecewiseLinearFlow::integrate (piecewise_linear_flow.h):
// phase after phase, its parts kept apart —
//   step control      the march over the phase's grid by exp(Â Δ)
//                     (piecewise_linear_integration.cpp)
//   event location    sign changes of the phase's event functionals in a grid
//                     interval, located on the exact exponential
//                     (piecewise_linear_events.cpp)
//   event handling    reset, new modes, saltation (piecewise_linear_events.cpp)
//   recording         extremes of x_i and the samples over an interval
//                     (piecewise_linear_integration.cpp)
#pragma once

#include <vector>

#include "eqhb/orbits/piecewise_linear_flow.h"

namespace eqhb::orbits {

// Zero of g(τ) = cᵀ exp(Â (τ − a)) z_a on (a, b] with g(a) > 0 >= g(b):
// Newton on the exact exponential, kept inside the bracket by bisection, to
// round-off in τ. Returns the first τ with g(τ) <= 0 and the state there.
double locateZero(const Eigen::RowVectorXd& c, const Eigen::MatrixXd& generator, const Eigen::VectorXd& z_a,
                  double a, double b, double time_scale, Eigen::VectorXd* z_root);

class PiecewiseLinearFlow::Integration {
 public:
  Integration(const PiecewiseLinearFlow& flow, bool with_jacobian, FlowSamples* samples);
  FlowResult run(const Eigen::VectorXd& y0, double t0, double duration);

 private:
  // The modes and Jacobian at the start; false, with the failure written,
  // when the state penetrates a wall.
  bool start(const Eigen::VectorXd& y0, double t0, double duration);

  // Where a phase ends: at its first event (fired >= 0) or at the end of
  // the interval, tau after its start.
  struct PhaseEnd {
    int fired = -1;
    double tau = 0.0;
    Eigen::VectorXd z;
  };

  // ---- step control
  // Marches the phase over its grid to its end; false with the failure written.
  bool marchPhase(const Phase& p, const std::vector<Event>& watch, PhaseEnd& end);
  // Moves the state and the Jacobian to the end of the phase.
  void advance(const Phase& p, const PhaseEnd& end);

  // ---- event location
  // The first event in the grid interval [tau_a, tau_b] of the phase (from
  // z_a to z_b) into `end`; false with the failure written.
  bool locateEvents(const Phase& p, const std::vector<Event>& watch, double tau_a, const Eigen::VectorXd& z_a,
                    double tau_b, const Eigen::VectorXd& z_b, PhaseEnd& end);

  // ---- event handling
  // Reset, new modes and saltation at the event `ev` the state has reached;
  // false with the failure written.
  bool handleEvent(const Phase& p, const Event& ev);

  // ---- recording
  // Extremes of x_i over [tau_a, tau_end] of the phase and the samples in it.
  void record(const Phase& p, double tau_a, const Eigen::VectorXd& z_a, double tau_end,
              const Eigen::VectorXd& z_end);

  const PiecewiseLinearFlow& flow_;
  const int n_, m_, laws_;
  const bool with_jacobian_;
  FlowSamples* samples_;
  FlowResult result_;
  std::vector<Mode> modes_;
  Eigen::VectorXd z_;
  Eigen::MatrixXd jacobian_;
  double t_ = 0.0, t_end_ = 0.0, time_scale_ = 0.0, velocity_scale_ = 0.0;
  int event_count_ = 0, immediate_events_ = 0;
  size_t next_sample_ = 0;
};

}  // namespace eqhb::orbits
