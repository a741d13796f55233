#include "compliant_study.h"

#include <cmath>
#include <sstream>

#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/fourier_transform.h"
#include "eqhb/harmonic_balance/hb_systems.h"
#include "eqhb/laws/joints/contact_friction.h"
#include "eqhb/scenes/scene.h"
#include "report_number.h"

namespace eqhb::bench {

namespace {

struct Solved {
  CompliantRow row;
  HbModel model;
  Eigen::VectorXd full;  // empty unless converged
};

Solved solveFromRest(const std::filesystem::path& path, const std::vector<std::string>& set, bool condensed) {
  const Scene scene = loadScene(path.string(), set);
  Solved s;
  s.model = scene.model;
  s.row.scene = scene.name;
  s.row.system = condensed ? "condensed" : "full";
  const auto* law = dynamic_cast<const ContactFriction*>(scene.model.laws.empty() ? nullptr : scene.model.laws[0].law.get());
  if (!law) throwInputError("law[0].type", scene.name, "the compliant study needs a contact-friction law first");
  if (law->parameters().normal_stiffness) s.row.k_n = *law->parameters().normal_stiffness;
  auto system = makeHbSystem(scene.model, condensed);
  const SolverResult r = makeSolver("dogleg")->solve(*system, Eigen::VectorXd::Zero(system->size()), {});
  s.row.converged = r.converged();
  s.row.termination = terminationName(r.termination);
  s.row.iterations = r.iterations;
  s.row.residual_evaluations = r.residual_evaluations;
  s.row.seconds = r.seconds;
  s.row.distance = NAN;
  s.row.penetration = NAN;
  if (!r.converged()) return s;
  s.full = system->fullCoefficients(r.solution);
  // Penetration max(−g)/max|g| on 8N samples of the normal displacement.
  const int n = 8 * scene.model.samples, nb = scene.model.basis.size();
  FourierTransform transform(scene.model.basis, n);
  Eigen::VectorXd x_n(n);
  transform.synthesize(s.full.data() + scene.model.laws[0].attachment.dof(0) * nb, x_n.data());
  const Eigen::ArrayXd gap = law->parameters().gap - x_n.array();
  s.row.penetration = std::max(0.0, -gap.minCoeff()) / std::max(gap.abs().maxCoeff(), 1e-300);
  return s;
}

std::string number(double x) { return bench::reportNumber(x, 3, "-"); }

}  // namespace

std::vector<CompliantRow> compliantStudy(const std::filesystem::path& path, const std::vector<double>& stiffnesses) {
  std::vector<CompliantRow> rows;
  for (bool condensed : {true, false}) {
    Solved exact = solveFromRest(path, {"law[0].form=\"min\""}, condensed);
    const int n = exact.model.structure.dofs() * exact.model.basis.size();
    exact.row.distance = exact.full.size() ? 0.0 : NAN;
    rows.push_back(exact.row);
    for (double k_n : stiffnesses) {
      Solved s = solveFromRest(path, {"law[0].form=\"compliant\"", "law[0].k_n=" + formatNumber(k_n)}, condensed);
      if (s.full.size() && exact.full.size())
        s.row.distance = (s.full.head(n) - exact.full.head(n)).norm() / exact.full.head(n).norm();
      rows.push_back(s.row);
    }
  }
  return rows;
}

std::string compliantIntroduction() {
  return "contact-friction-2d with the elastic layer p = k_n max(0, −g) (form = \"compliant\") and with the exact "
         "min form, each solved from rest by the own dogleg on the condensed and the full system. Distance: "
         "relative L2 distance of the displacement coefficients to the exact answer on the same system; "
         "penetration: max(−g) / max|g| sampled at 8N instants (compliant.csv).\n\n";
}

std::string compliantReport(const std::vector<CompliantRow>& rows) {
  std::ostringstream t;
  t << "| scene | system | normal form | k_n | converged | iterations | f-evals | s | distance to Signorini | "
       "penetration |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const CompliantRow& r : rows)
    t << "| " << r.scene << " | " << r.system << " | " << (r.k_n > 0.0 ? "compliant" : "min (exact)") << " | "
      << (r.k_n > 0.0 ? number(r.k_n) : "∞") << " | " << (r.converged ? "yes" : "**no** (" + r.termination + ")")
      << " | " << r.iterations << " | " << r.residual_evaluations << " | " << number(r.seconds) << " | "
      << number(r.distance) << " | " << number(r.penetration) << " |\n";
  return t.str();
}

}  // namespace eqhb::bench
