// polynomial: a polynomial spring kept as a DAE (laws/polynomial_stiffness.h).
#include <cmath>

#include "eqhb/laws/polynomial_stiffness.h"
#include "eqhb/laws/registry/entry_support.h"

namespace eqhb {

LawEntry polynomialEntry() {
  LawEntry e = lawEntry("polynomial", "polynomial spring, force −Σ c_k x^p_k (as the DAE f + Σ c_k x^p_k = 0)");
  e.parameters = {{"coefficients", "", "finite", "c_k, one per exponent"},
                  {"exponents", "", "integers in [1, 25]", "p_k"}};
  e.parse = [](LawTable& t) -> std::shared_ptr<Law> {
    const std::vector<double> coefficients = t.numbers("coefficients"), given = t.numbers("exponents");
    std::vector<int> exponents;
    for (size_t k = 0; k < given.size(); ++k) {
      if (given[k] != std::floor(given[k]) || given[k] < 1 || given[k] > PolynomialStiffness::kMaxExponent)
        t.fail(t.path("exponents[" + std::to_string(k) + "]"), formatNumber(given[k]),
               "must be an integer in [1, " + std::to_string(PolynomialStiffness::kMaxExponent) + "]");
      exponents.push_back(static_cast<int>(given[k]));
    }
    if (coefficients.size() != exponents.size())
      t.fail(t.path("coefficients"), std::to_string(coefficients.size()) + " values",
             "must be as many as the exponents (" + std::to_string(exponents.size()) + ")");
    return std::make_shared<PolynomialStiffness>(coefficients, exponents);
  };
  e.examples = {{"polynomial-odd", 1, "coefficients = [0.5, -0.2, 0.05]\nexponents = [1, 3, 5]"},
                {"polynomial-quadratic", 1, "coefficients = [0.3, 0.4]\nexponents = [2, 3]"}};
  e.smooth_flow = [](const Law& law) -> std::optional<SmoothFlowSite> {
    SmoothFlowSite site;
    site.kind = SmoothFlowSite::Kind::kForce;
    const PolynomialStiffness spring = static_cast<const PolynomialStiffness&>(law);
    site.force = [spring](double x, double, double* f, double* df_dx, double* df_dv) {
      *f = -spring.force(x);
      *df_dx = -spring.slope(x);
      *df_dv = 0.0;
    };
    return site;
  };
  return e;
}

}  // namespace eqhb
