// jenkins: a Coulomb slider behind a spring k_t, on 1 or 2 DOFs (laws/joints/jenkins.h).
#include "eqhb/laws/joints/elastic_friction_aft.h"
#include "eqhb/laws/joints/jenkins.h"
#include "eqhb/laws/joints/jenkins_aft.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry jenkinsEntry() {
  LawEntry e = lawEntry("jenkins",
                        "elastic dry friction (a spring k_t in series with a Coulomb slider) on 1 or 2 DOFs");
  e.forms = {"minmax", "projection", "max"};
  e.parameters = withRho({{"muN", "", ">= 0", "friction limit μN"},
                          {"k_t", "", "> 0", "tangential stiffness"},
                          {"form", "minmax (1 DOF), max (2)", "minmax|projection|max", "minmax: one DOF"},
                          {"formulation", "aft on 1 DOF without form or rho, else equality", "equality|aft",
                           "aft: the force by the return map over the period (a radial return on the disc of "
                           "radius muN on 2 DOFs; form and ρ unused)"}});
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const double mu_n = t.frictionLimit("muN");
    const double k_t = t.positive("k_t", std::nullopt);
    const RhoSetting rho = t.rho();
    const int m = t.components();
    if (m != 1 && m != 2) t.fail(t.path(t.componentsKey()), t.dofsText(), "a jenkins law acts on 1 or 2 DOFs");
    const std::string name = t.form(m == 1 ? "minmax" : "max");
    if (name == "minmax" && m != 1)
      t.fail(t.path("form"), "\"minmax\"", "the minmax form is one-dimensional; use max or projection");
    return std::make_shared<Jenkins>(m, mu_n, k_t, parseFrictionForm(name, t.path("form")), rho);
  };
  // On one DOF the AFT form by default (law_registry.h: exact force, and on
  // NLvib's example 07 the arclength sweep completes where the equality
  // form's kinks stop it).
  e.aft_by_default = [](const LawTable& t) { return t.components() == 1; };
  e.in_aft_form = [](const Law& law) {
    return dynamic_cast<const JenkinsAft*>(&law) != nullptr || dynamic_cast<const ElasticFrictionAft*>(&law) != nullptr;
  };
  e.parse_aft = [](LawTable& t) -> std::shared_ptr<Law> {
    const double mu_n = t.frictionLimit("muN");
    const double k_t = t.positive("k_t", std::nullopt);
    // form and ρ belong to the equality form; read (and checked) so that a
    // scene switches formulation by one key.
    t.rho();
    const int m = t.components();
    t.form(m == 1 ? "minmax" : "max");
    if (m != 1 && m != 2) t.fail(t.path(t.componentsKey()), t.dofsText(), "a jenkins law acts on 1 or 2 DOFs");
    if (m == 1) return std::make_shared<JenkinsAft>(std::vector<JenkinsAft::Slider>{{mu_n, k_t}});
    // On a plane: elastic-friction's tangential return map with the limit
    // held at muN (laws/joints/elastic_friction_aft.h).
    ElasticFrictionParameters plane;
    plane.tangents = 2;
    plane.k_t = k_t;
    plane.constant_limit = mu_n;
    return std::make_shared<ElasticFrictionAft>(plane);
  };
  e.examples = {{"jenkins1_minmax", 1, "muN = 1.2\nk_t = 2.0\nform = \"minmax\"\nrho = 0.9"},
                {"jenkins1_projection", 1, "muN = 1.2\nk_t = 2.0\nform = \"projection\"\nrho = 0.9"},
                {"jenkins2_max", 2, "muN = 1.2\nk_t = 2.0\nform = \"max\"\nrho = 0.9"},
                {"jenkins2_projection", 2, "muN = 1.2\nk_t = 2.0\nform = \"projection\"\nrho = 0.9"},
                // The return map over the period (JenkinsAft): its Jacobian across samples.
                {"jenkins1_aft", 1, "muN = 1.2\nk_t = 2.0\nformulation = \"aft\""},
                {"jenkins2_aft", 2, "muN = 1.2\nk_t = 2.0\nformulation = \"aft\""}};
  // On one DOF: a slider behind a spring, closed form between events.
  e.piecewise_linear_flow = [](const Law& law) -> std::optional<PiecewiseLinearSite> {
    PiecewiseLinearSite site;
    if (const auto* aft = dynamic_cast<const JenkinsAft*>(&law)) {
      site.limit = aft->muN();
      site.stiffness = aft->sliders().front().k_t;
      return site;
    }
    const auto* jenkins_pointer = dynamic_cast<const Jenkins*>(&law);
    if (!jenkins_pointer || jenkins_pointer->dimension() != 1) return std::nullopt;  // a plane: no 1-D site
    const Jenkins& jenkins = *jenkins_pointer;
    site.limit = jenkins.muN();
    site.stiffness = jenkins.stiffness();
    return site;
  };
  return e;
}

}  // namespace eqhb
