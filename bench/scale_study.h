// Scale study: how the harmonic-balance systems and the backends grow with
// the structure. Generated chains (scenes/scene_generator) give
//   - full systems from ~10² to ≥ 10⁵ unknowns (DOFs × basis size), and
//   - condensed systems from 1 to ≥ 100 contact components;
// per backend: time per solve, per residual + Jacobian, set-up time and peak
// memory (getrusage of a child process that runs just that case), and the
// log–log slopes of those against the unknowns. Structures of the shipped
// scenes (beam-joint-large) and a Brake–Reuss-sized problem are timed per
// frequency point and over a frequency response.
#pragma once

#include <string>
#include <vector>

namespace eqhb::bench {

struct ScaleRow {
  std::string study;    // "full", "condensed" or a structure case
  std::string solver;
  int dofs = 0, contacts = 0, unknowns = 0;
  bool converged = false;
  std::string termination;  // or why the case did not run
  int iterations = 0, residual_evaluations = 0, jacobian_evaluations = 0;
  double setup_seconds = 0.0, solve_seconds = 0.0, residual_jacobian_seconds = 0.0;
  double peak_mib = 0.0;
};

// Forcing frequency of the generated chains. The generator's default, 0.8 x the
// first eigenfrequency, falls to ~1e-4 for thousands of DOFs: a quasi-static
// chain on which the full system stalls from rest (see the report); 0.3 lies in
// the pass band of every chain (m = k = 1: 0 < omega < 2) and keeps the
// physics of the cases comparable as the chain grows.
constexpr double kScaleOmega = 0.3;

// Runs the study (quick: the smallest sizes and the own dogleg only).
std::vector<ScaleRow> runScaleStudy(bool quick, const std::vector<std::string>& backends,
                                    const std::string& problems);

// Least-squares slope of log y against log x (NaN with fewer than 2 points).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

void writeScaleCsv(const std::string& path, const std::vector<ScaleRow>& rows);
// The report section: tables, slopes, structure timings.
std::string scaleReport(const std::vector<ScaleRow>& rows);

}  // namespace eqhb::bench
