// A converged (or not) harmonic-balance answer in physical terms: per DOF and
// per law component, the Fourier coefficients and the largest magnitude over
// one period (sampled on the model's N instants).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"

namespace eqhb {

struct ChannelSummary {
  std::string label;           // "x1", "law1.r" ...
  Eigen::VectorXd coefficients;  // HarmonicSet layout
  double max_abs = 0.0;        // max over the period of |value|
  double max_abs_rate = 0.0;   // max over the period of |d/dt value|
  Eigen::VectorXd samples;     // value at t_i = iT/N
};

struct HbSolution {
  std::vector<ChannelSummary> displacements;  // one per DOF
  std::vector<ChannelSummary> forces;         // one per law component
};

// The one labelling of a solution's channels, in every output: DOF i
// (0-based) is "x<i+1>" unless the model names it; component a of law l is "law<l+1>.lambda", with the
// component's number after it for a law of more than one ("law2.lambda1").
std::string dofLabel(int dof);
// The model's name of DOF `dof` (HbModel::dof_names: "w3", "theta3"), else dofLabel(dof).
std::string dofLabel(const HbModel& model, int dof);
std::string lawComponentLabel(const HbModel& model, int law, int component);
// Every law component's label, in the order of the λ channels.
std::vector<std::string> lawComponentLabels(const HbModel& model);

// full = [x_1..x_n, λ_1..λ_L] coefficients (FullSystem layout).
HbSolution summarize(const HbModel& model, const Eigen::VectorXd& full);

// |(a₁, b₁)|, the amplitude of the first harmonic of one channel (0 if the
// basis has no harmonic 1).
double firstHarmonicAmplitude(const HarmonicSet& basis, const double* coefficients);

// The same channels on another harmonic set: shared harmonics are copied,
// the others are zero (continuation in H; both models have the same DOFs
// and laws).
Eigen::VectorXd transferCoefficients(const HbModel& from, const HbModel& to, const Eigen::VectorXd& full);

}  // namespace eqhb
