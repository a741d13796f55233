// contact-friction: unilateral contact with friction under it (laws/joints/contact_friction.h).
#include "eqhb/laws/joints/contact_friction.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

namespace {

// dofs = [normal, tangential (, tangential)], or between two nodes a normal
// and one or two tangents.
std::shared_ptr<Law> parseContactFriction(LawTable& t) {
  const std::string& field = t.field();
  const std::vector<int>& dofs = t.dofs();
  const std::string normal_form = t.text("form", std::string("min"));
  if (t.components() != 2 && t.components() != 3)
    t.fail(t.path(t.componentsKey()), t.dofsText(),
           "a contact-friction law acts on [normal, tangential] or [normal, tangential, tangential]");
  for (size_t a = 1; a < dofs.size(); ++a)
    if (dofs[a] == dofs[0])
      t.fail(field + ".dofs", std::to_string(dofs[0] + 1), "the normal DOF is also a tangential DOF");
  ContactFrictionParameters p;
  p.tangential = t.components() - 1;
  auto non_negative = [&](const char* key, const char* what) {
    const double x = t.number(key, std::nullopt);
    if (x < 0.0) t.fail(t.path(key), formatNumber(x), std::string(what) + " must be >= 0");
    return x;
  };
  auto positive_optional = [&](const char* key, const char* what) -> std::optional<double> {
    if (!t.has(key)) return std::nullopt;
    const double x = t.number(key, std::nullopt);
    if (!(x > 0.0)) t.fail(t.path(key), formatNumber(x), std::string(what) + " must be > 0");
    return x;
  };
  p.mu = non_negative("mu", "friction coefficient");
  p.preload = non_negative("preload", "normal preload N0");
  p.gap = t.number("gap", 0.0);
  p.rho = t.rho();
  p.normal = parseNormalForm(normal_form, field + ".form");
  p.normal_stiffness = positive_optional("k_n", "contact stiffness");
  if (p.normal == NormalForm::kCompliant && !p.normal_stiffness)
    t.fail(field + ".k_n", "(missing)", "form = \"compliant\" needs a contact stiffness k_n > 0");
  if (p.normal != NormalForm::kCompliant && p.normal_stiffness)
    t.fail(field + ".k_n", formatNumber(*p.normal_stiffness),
           "a contact stiffness is only used by form = \"compliant\"");
  p.tangential_stiffness = positive_optional("k_t", "tangential stiffness");
  const std::string friction = t.text("friction_form", std::string("projection"));
  p.friction = parseFrictionForm(friction, field + ".friction_form");
  if (p.friction == FrictionForm::kMinMax && p.tangential != 1)
    t.fail(field + ".friction_form", "\"minmax\"", "the minmax form has one tangential DOF; use max or projection");
  return std::make_shared<ContactFriction>(p);
}

std::string example(const std::string& forms) {
  return "mu = 0.4\npreload = 0.7\ngap = 0.2\nrho = 0.8\n" + forms;
}

}  // namespace

LawEntry contactFrictionEntry() {
  LawEntry e = lawEntry("contact-friction",
                        "unilateral contact on a normal DOF with Coulomb friction on 1 or 2 tangential DOFs");
  // And "compliant", which needs k_n: not a form --form can set alone.
  e.forms = {"min", "fischer-burmeister"};
  e.parameters = withRho({{"mu", "", ">= 0", "friction coefficient μ"},
                          {"preload", "", ">= 0", "normal preload N0"},
                          {"gap", "0", "finite", "g0, the initial gap"},
                          {"form", "min", "min|fischer-burmeister|compliant", "normal law (compliant needs k_n)"},
                          {"k_n", "", "> 0", "contact stiffness of the compliant form (only there)"},
                          {"friction_form", "projection", "projection|max|minmax", "minmax: one tangential DOF"},
                          {"k_t", "", "> 0", "optional tangential stiffness: elastic friction"}});
  e.parse = parseContactFriction;
  e.examples = {
      {"cf1_min_minmax", 2, example("form = \"min\"\nfriction_form = \"minmax\"")},
      {"cf1_fb_projection", 2, example("form = \"fischer-burmeister\"\nfriction_form = \"projection\"")},
      {"cf1_compliant_max", 2, example("form = \"compliant\"\nk_n = 3.0\nfriction_form = \"max\"")},
      {"cf2_min_projection", 3, example("form = \"min\"\nfriction_form = \"projection\"")},
      {"cf2_fb_max", 3, example("form = \"fischer-burmeister\"\nfriction_form = \"max\"")},
      {"cf2_compliant_projection_kt", 3,
       example("form = \"compliant\"\nk_n = 3.0\nfriction_form = \"projection\"\nk_t = 2.5")},
      {"cf1_min_minmax_kt", 2, example("form = \"min\"\nfriction_form = \"minmax\"\nk_t = 1.5")},
      // Elastic dry friction in 3D under an exact (Signorini) normal.
      {"cf2_min_projection_kt", 3, example("form = \"min\"\nfriction_form = \"projection\"\nk_t = 1.5")}};
  return e;
}

}  // namespace eqhb
