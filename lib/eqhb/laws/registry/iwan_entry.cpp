// iwan: a four-parameter Iwan element of Jenkins sliders in parallel, in the
// alternating frequency–time form only (laws/joints/iwan_sliders.h).
#include <cmath>

#include "eqhb/laws/joints/iwan_sliders.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry iwanEntry() {
  LawEntry e = lawEntry("iwan",
                        "Iwan element: Jenkins sliders in parallel, Segalman's four-parameter slip-displacement density "
                        "(alternating frequency-time form) on 1 DOF");
  e.parameters = {{"muN", "", "> 0", "slip force F_S: the force when every slider slips"},
                  {"k_t", "", "> 0", "stiffness K_T when every slider sticks"},
                  {"chi", "0", "> -1 and <= 10", "χ: density R φ^χ of slip displacements φ (micro-slip D ∝ a^(χ+3))"},
                  {"beta", "0", ">= 0", "β: the share of the sliders that slip at the largest φ (S δ(φ − φ_max))"},
                  {"sliders", "20", "integer in [1, 10000]", "equal cells of (0, φ_max), one slider each (+1 if β > 0)"}};
  // No equality form: the force is a functional of the displacement's history.
  e.parse_aft = [](LawTable& t) -> std::shared_ptr<Law> {
    IwanParameters p;
    p.slip_force = t.positive("muN", std::nullopt);
    p.stiffness = t.positive("k_t", std::nullopt);
    p.chi = t.number("chi", 0.0);
    if (!(p.chi > -1.0 && p.chi <= 10.0)) t.fail(t.path("chi"), formatNumber(p.chi), "must be in (-1, 10]");
    p.beta = t.number("beta", 0.0);
    if (!(p.beta >= 0.0) || !std::isfinite(p.beta)) t.fail(t.path("beta"), formatNumber(p.beta), "must be >= 0");
    const double cells = t.number("sliders", 20.0);
    if (cells != std::floor(cells) || cells < 1 || cells > 10000)
      t.fail(t.path("sliders"), formatNumber(cells), "must be an integer in [1, 10000]");
    p.cells = static_cast<int>(cells);
    if (t.components() != 1) t.fail(t.path(t.componentsKey()), t.dofsText(), "an iwan law acts on 1 DOF");
    return std::make_shared<JenkinsAft>(iwanSliders(p), "iwan");
  };
  e.examples = {{"iwan_uniform", 1, "muN = 1.2\nk_t = 2.0\nsliders = 10"},
                {"iwan_four_parameter", 1, "muN = 1.2\nk_t = 2.0\nchi = -0.5\nbeta = 0.5\nsliders = 12"}};
  return e;
}

}  // namespace eqhb
