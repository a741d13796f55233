#include "eqhb/output/backbone_hdf5.h"

#include <cmath>

#include "eqhb/harmonic_balance/hb_solution.h"
#include "eqhb/output/hdf5_file.h"

namespace eqhb::output {

namespace {

// Per point `value(point)`, NaN where the point did not converge.
template <typename Value>
std::vector<double> converged(const std::vector<BackbonePoint>& points, Value value) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const BackbonePoint& p : points) out.push_back(p.converged ? value(p) : NAN);
  return out;
}

// Every point's DOF coefficients [m x n x h], cosine or sine (the JSON's
// coefficientsJson: the sine of harmonic 0 is 0).
std::vector<double> coefficients(const HbModel& model, const std::vector<BackbonePoint>& points, bool sine) {
  const HarmonicSet& basis = model.basis;
  const int n = model.structure.dofs(), nb = basis.size(), h = static_cast<int>(basis.harmonics().size());
  std::vector<double> out;
  out.reserve(points.size() * n * h);
  for (const BackbonePoint& p : points)
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < h; ++k) {
        const int at = i * nb + basis.offset(k);
        out.push_back(!p.converged ? NAN : !sine ? p.full[at] : basis.harmonics()[k] == 0 ? 0.0 : p.full[at + 1]);
      }
  return out;
}

}  // namespace

void writeBackboneHdf5(const std::string& path, const app::ModesRun& run) {
  const Backbone& b = run.backbone;
  const HbModel& model = run.scene.model;
  const auto& points = b.points;
  const std::size_t m = points.size(), n = static_cast<std::size_t>(model.structure.dofs()),
                    h = model.basis.harmonics().size();
  Hdf5File file(path);
  file.attribute("/", "scene", run.scene.name);
  file.attribute("/", "solver", run.solver);
  file.attribute("/", "mode", run.options.mode);
  file.attribute("/", "from", run.options.from);
  file.attribute("/", "to", run.options.to);
  file.attribute("/", "complete", b.complete() ? 1.0 : 0.0);
  file.attribute("/", "failed_points", b.failed_points);
  file.attribute("/", "seconds", b.seconds);
  file.attribute("/", "linear_omega", b.start.omega);
  file.attribute("/", "linear_damping_ratio", b.start.damping_ratio);
  if (!b.stop.why.empty()) {
    file.attribute("/", "stop_why", b.stop.why);
    file.attribute("/", "stop_amplitude", b.stop.amplitude);
    file.attribute("/", "stop_omega", b.stop.omega);
    file.attribute("/", "stop_damping_ratio", b.stop.damping_ratio);
  }
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < n; ++i) labels.push_back(dofLabel(model, static_cast<int>(i)));
  file.strings("/dof_labels", labels);
  file.doubles("/linear_shape", std::vector<double>(b.start.shape.data(), b.start.shape.data() + b.start.shape.size()));
  std::vector<std::int64_t> harmonics(model.basis.harmonics().begin(), model.basis.harmonics().end());
  file.integers("/harmonics", harmonics);
  file.group("/folds");
  std::vector<double> fold_amplitude, fold_omega, fold_zeta;
  for (const BackboneFold& f : b.folds) {
    fold_amplitude.push_back(f.amplitude);
    fold_omega.push_back(f.omega);
    fold_zeta.push_back(f.damping_ratio);
  }
  file.doubles("/folds/amplitude", fold_amplitude);
  file.doubles("/folds/omega", fold_omega);
  file.doubles("/folds/damping_ratio", fold_zeta);

  file.group("/points");
  std::vector<double> amplitude, seconds, max_abs;
  std::vector<std::int64_t> ok, iterations;
  std::vector<std::string> terminations;
  for (const BackbonePoint& p : points) {
    amplitude.push_back(p.amplitude);
    seconds.push_back(p.seconds);
    ok.push_back(p.converged ? 1 : 0);
    iterations.push_back(p.iterations);
    terminations.push_back(p.termination);
    for (std::size_t i = 0; i < n; ++i) max_abs.push_back(p.converged && i < p.max_abs.size() ? p.max_abs[i] : NAN);
  }
  file.doubles("/points/amplitude", amplitude);
  file.doubles("/points/seconds", seconds);
  file.integers("/points/converged", ok);
  file.integers("/points/iterations", iterations);
  file.strings("/points/termination", terminations);
  file.doubles("/points/omega", converged(points, [](const BackbonePoint& p) { return p.omega; }));
  file.doubles("/points/xi", converged(points, [](const BackbonePoint& p) { return p.xi; }));
  file.doubles("/points/damping_ratio", converged(points, [](const BackbonePoint& p) { return p.damping_ratio; }));
  file.doubles("/points/dissipated_energy",
               converged(points, [](const BackbonePoint& p) { return p.dissipated_energy; }));
  file.matrix("/points/max_abs", max_abs, m, n);
  file.array("/points/cos", coefficients(model, points, false), {m, n, h});
  file.array("/points/sin", coefficients(model, points, true), {m, n, h});
  file.close();
}

}  // namespace eqhb::output
