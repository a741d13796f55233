// coulomb-1d: Coulomb friction on one DOF (laws/coulomb_1d.h).
#include "eqhb/laws/coulomb_1d.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry coulomb1DEntry() {
  LawEntry e = lawEntry("coulomb-1d", "Coulomb friction on one DOF");
  e.forms = {"minmax", "projection", "tanh", "piecewise"};
  e.parameters = withRho({{"muN", "", ">= 0", "friction limit μN"},
                          {"form", "minmax", "minmax|projection|tanh|piecewise", "tanh, piecewise: regularised"},
                          {"beta", "", "> 0", "slope β (1/velocity) of the regularised forms; unset: scale-free (law.h)"}});
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double mu_n = t.frictionLimit("muN");
    const RhoSetting rho = t.rho();
    const std::optional<double> beta = t.optionalPositive("beta");
    return std::make_shared<Coulomb1D>(mu_n, parseCoulombForm(t.form("minmax")), rho, beta);
  };
  e.examples = {{"coulomb1d-minmax", 1, "muN = 1.3\nform = \"minmax\"\nrho = 0.8"},
                {"coulomb1d-projection", 1, "muN = 1.3\nform = \"projection\"\nrho = 0.8"},
                {"coulomb1d-tanh", 1, "muN = 1.3\nform = \"tanh\"\nrho = 0.8\nbeta = 7.0"},
                {"coulomb1d-piecewise", 1, "muN = 1.3\nform = \"piecewise\"\nrho = 0.8\nbeta = 7.0"}};
  // A constant limit: a Stribeck slider without drop between events.
  e.smooth_flow = coefficientSite<Coulomb1D>(SmoothFlowSite::Kind::kStribeck, &Coulomb1D::muN);
  e.piecewise_linear_flow = [](const Law& law) -> std::optional<PiecewiseLinearSite> {
    PiecewiseLinearSite site;
    site.limit = static_cast<const Coulomb1D&>(law).muN();
    return site;
  };
  return e;
}

}  // namespace eqhb
