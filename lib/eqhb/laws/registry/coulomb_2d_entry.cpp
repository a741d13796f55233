// coulomb-2d: isotropic Coulomb friction in a plane of two DOFs (laws/coulomb_2d.h).
#include "eqhb/laws/coulomb_2d.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry coulomb2DEntry() {
  LawEntry e = lawEntry("coulomb-2d", "isotropic Coulomb friction on two DOFs (a plane)");
  e.forms = {"max", "projection", "smoothed", "tanh"};
  e.parameters = withRho({{"muN", "", ">= 0", "friction limit μN"},
                          {"form", "max", "max|projection|smoothed|tanh", "smoothed, tanh: regularised"},
                          {"epsilon", "", "> 0", "the smoothed form's rounding ε (a force squared); unset: scale-free, (μN / 100)²"},
                          {"alpha", "", "> 0", "slope α (1/velocity) of the tanh form; unset: scale-free (law.h)"}});
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double mu_n = t.frictionLimit("muN");
    const RhoSetting rho = t.rho();
    const std::optional<double> epsilon = t.optionalPositive("epsilon");
    const std::optional<double> alpha = t.optionalPositive("alpha");
    return std::make_shared<Coulomb2D>(mu_n, parseCoulomb2DForm(t.form("max")), rho, epsilon, alpha);
  };
  e.examples = {{"coulomb2d-max", 2, "muN = 1.5\nform = \"max\"\nrho = 0.7"},
                {"coulomb2d-projection", 2, "muN = 1.5\nform = \"projection\"\nrho = 0.7"},
                {"coulomb2d-smoothed", 2, "muN = 1.5\nform = \"smoothed\"\nrho = 0.7\nepsilon = 0.3"},
                {"coulomb2d-tanh", 2, "muN = 1.5\nform = \"tanh\"\nrho = 0.7\nalpha = 2.0"}};
  e.smooth_flow = coefficientSite<Coulomb2D>(SmoothFlowSite::Kind::kPlanar, &Coulomb2D::muN);
  return e;
}

}  // namespace eqhb
