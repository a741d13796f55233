#include "eqhb/harmonic_balance/problem_scales.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "eqhb/harmonic_balance/dynamic_stiffness_factors.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/hb_systems.h"

namespace eqhb {

PhysicalScales physicalScales(const HbModel& model, double response) {
  const LinearStructure& s = model.structure;
  double force = 0.0, length = std::isfinite(response) ? std::abs(response) : 0.0;
  for (const auto& load : s.loads) force = std::max(force, std::hypot(load.cos_amplitude, load.sin_amplitude));
  for (const auto& attached : model.laws) {
    force = std::max(force, std::abs(attached.law->forceLevel()));
    length = std::max(length, std::abs(attached.law->displacementLevel()));
  }
  const double w = model.omega;
  double stiffness = 0.0;
  for (const auto& attached : model.laws)
    for (int i : attached.attachment.dofs())
      if (i >= 0 && i < s.dofs())
        stiffness = std::max({stiffness, std::abs(s.stiffness.coeff(i, i)), w * std::abs(s.damping.coeff(i, i)),
                              w * w * std::abs(s.mass.coeff(i, i))});
  PhysicalScales scales;
  if (!(force > 0.0) && !(length > 0.0)) return scales;  // all 1: nothing sets a scale
  if (!(force > 0.0)) force = stiffness * length;
  if (!(length > 0.0) && stiffness > 0.0) length = force / stiffness;
  if (!(force > 0.0) || !(length > 0.0) || !std::isfinite(force) || !std::isfinite(length) || !(w > 0.0))
    return PhysicalScales{};
  scales.force = force;
  scales.displacement = length;
  scales.velocity = w * length;
  return scales;
}

double linearResponseAtLaws(const HbModel& model, bool sparse) {
  if (model.structure.loads.empty() || model.laws.empty()) return 0.0;
  const int n = model.structure.dofs(), nb = model.basis.size();
  const Eigen::VectorXd f = forcingCoefficients(model);
  DynamicStiffnessFactors factors(model.structure, model.basis, sparse);
  factors.factorize(model.structure, model.omega);
  double most = 0.0;
  const auto& ks = model.basis.harmonics();
  for (size_t h = 0; h < ks.size(); ++h) {
    const int w = ks[h] == 0 ? 1 : 2, o = model.basis.offset(static_cast<int>(h));
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(w * n, 1);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < w; ++r) rhs(r * n + i, 0) = f[i * nb + o + r];
    if (rhs.isZero(0.0)) continue;
    const Eigen::MatrixXd x = factors.solve(static_cast<int>(h), rhs);
    for (const auto& attached : model.laws)
      for (int a = 0; a < attached.attachment.dimension(); ++a) {
        const double u = attached.attachment.gather(x.col(0), a);
        most = std::max(most, w == 1 ? std::abs(u) : std::hypot(u, attached.attachment.gather(x.col(0).tail(n), a)));
      }
  }
  return most;
}

namespace {
// Row a of a law's attachment W.
struct ComponentRow {
  const LawAttachment* attachment;
  int a;
  const std::vector<AttachmentTerm>& terms() const { return attachment->row(a); }
};

// |W_a A_k⁻¹ W_aᵀ| for each row W_a in `rows` (|(A_k⁻¹)_ii| for a grounded
// component on DOF i), for every harmonic k of `basis` at ω: one row per
// harmonic. Throws where some A_k is singular.
std::vector<std::vector<double>> compliances(const HbModel& model, const HarmonicSet& basis,
                                             const std::vector<ComponentRow>& rows) {
  const LinearStructure& s = model.structure;
  const int n = s.dofs();
  DynamicStiffnessFactors factors(s, basis, n >= kSparseCondensationFromDofs);
  factors.factorize(s, model.omega);
  std::vector<std::vector<double>> out;
  for (size_t h = 0; h < basis.harmonics().size(); ++h) {
    const int width = basis.harmonics()[h] == 0 ? 1 : 2;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(width * n, 1);
    std::vector<double> row;
    for (const ComponentRow& c : rows) {
      for (const AttachmentTerm& term : c.terms()) rhs(term.dof, 0) = term.weight;
      const Eigen::MatrixXd x = factors.solve(static_cast<int>(h), rhs);
      for (const AttachmentTerm& term : c.terms()) rhs(term.dof, 0) = 0.0;
      const double re = c.attachment->gather(x.col(0), c.a);
      row.push_back(width == 1 ? std::abs(re) : std::hypot(re, c.attachment->gather(x.col(0).tail(n), c.a)));
    }
    out.push_back(row);
  }
  return out;
}

// The compliance a law sees at each DOF in `dofs`: the smaller of the static
// |(K⁻¹)_ii| and the dynamic |G_ii(ω)| at the fundamental (A₁ = K − ω²M + iωC).
// Near a resonance of the free structure |G| grows without bound while the
// contact itself stiffens the structure there (damper at ω = 1: ρ from |G|
// alone stalled the solver); above the resonances the mass makes |G| the
// smaller. Without K (a free body) the dynamic value alone; where A₁ is
// singular too (an undamped resonance), 1/max(K_ii, ωC_ii, ω²M_ii).
std::vector<double> drivingPointCompliances(const HbModel& model, const std::vector<ComponentRow>& rows) {
  try {
    const auto both = compliances(model, HarmonicSet(HarmonicKind::kAll, 1), rows);  // k = 0 and 1
    std::vector<double> out;
    for (size_t a = 0; a < rows.size(); ++a) out.push_back(std::min(both[0][a], both[1][a]));
    return out;
  } catch (const std::exception&) {
  }
  try {
    return compliances(model, HarmonicSet(HarmonicKind::kOdd, 1), rows).front();
  } catch (const std::exception&) {
  }
  const LinearStructure& s = model.structure;
  const double w = model.omega;
  std::vector<double> out;
  for (const ComponentRow& c : rows) {
    double most = 0.0;  // the stiffest DOF of the row
    for (const AttachmentTerm& term : c.terms()) {
      const int i = term.dof;
      most = std::max({most, std::abs(s.stiffness.coeff(i, i)), w * std::abs(s.damping.coeff(i, i)),
                       w * w * std::abs(s.mass.coeff(i, i))});
    }
    out.push_back(1.0 / most);
  }
  return out;
}

// LawScales of each law in `laws` (indices into model.laws), the largest
// compliance over its DOFs; nullopt where nothing gives one (no stiffness,
// mass or damping at the DOF).
std::vector<std::optional<LawScales>> lawScales(const HbModel& model, const std::vector<int>& laws,
                                                bool static_only = false) {
  std::vector<ComponentRow> rows;
  for (int l : laws)
    for (int a = 0; a < model.laws[l].attachment.dimension(); ++a) rows.push_back({&model.laws[l].attachment, a});
  std::vector<double> compliance;
  if (!static_only) {
    compliance = drivingPointCompliances(model, rows);
  } else {
    try {
      compliance = compliances(model, HarmonicSet(HarmonicKind::kAll, 1), rows)[0];  // k = 0: K⁻¹
    } catch (const std::exception&) {
      compliance.assign(rows.size(), 0.0);  // K singular: no scale
    }
  }
  std::vector<std::optional<LawScales>> out;
  size_t next = 0;
  for (int l : laws) {
    double largest = 0.0;
    for (int a = 0; a < model.laws[l].attachment.dimension(); ++a) largest = std::max(largest, compliance[next++]);
    if (largest > 0.0 && std::isfinite(largest)) out.push_back(LawScales{model.omega, largest});
    else out.push_back(std::nullopt);
  }
  return out;
}
}  // namespace

namespace {
HbModel scaleFreeRhos(HbModel model, bool static_only) {
  // Only laws that ask for it cost a factorisation (probed with unit scales).
  std::vector<int> wanted;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l)
    if (model.laws[l].law->withScaleFreeRho(LawScales{})) wanted.push_back(l);
  if (wanted.empty()) return model;
  const auto scales = lawScales(model, wanted, static_only);
  for (size_t k = 0; k < wanted.size(); ++k)
    if (scales[k]) {  // else ρ stays its factor
      AttachedLaw& attached = model.laws[wanted[k]];
      attached.law = attached.law->withScaleFreeRho(*scales[k]);
    }
  return model;
}
}  // namespace

HbModel withScaleFreeRhos(HbModel model) { return scaleFreeRhos(std::move(model), false); }

HbModel withStaticScaleFreeRhos(HbModel model) { return scaleFreeRhos(std::move(model), true); }

namespace {
std::string widthSentence(const HbModel& model, int l, const LawScales& scales) {
  const auto width = model.laws[l].law->compareWidth(scales);
  if (!width) return "";
  const double ratio = width->in_use / width->scale_free;
  if (ratio <= kWidthMisscale && ratio >= 1.0 / kWidthMisscale) return "";
  return "law[" + std::to_string(l) + "] (" + model.laws[l].law->type() + "): " + width->key + " = " +
         formatNumber(width->in_use) + " is " + formatNumber(ratio) + " times the scale-free " + width->key + " = " +
         formatNumber(width->scale_free) + " of this contact at omega = " + formatNumber(model.omega) +
         " (a transition of 1/100 of its slip velocity scale muN omega |G|); a width this far from it "
         "can make the regularised friction a damper or too stiff to converge: leave " + width->key +
         " unset (scale-free)";
}
}  // namespace

std::string widthScaleAdvice(const HbModel& scene_model, int l) {
  const HbModel model = withScaleFreeRhos(scene_model);  // the widths a system would use
  if (!model.laws[l].law->compareWidth(LawScales{})) return "";
  const auto scales = lawScales(model, {l});
  return scales.front() ? widthSentence(model, l, *scales.front()) : "";
}

std::vector<std::string> scaleAdvice(const HbModel& scene_model) {
  const HbModel model = withScaleFreeRhos(scene_model);  // the ρ and widths a system would use
  std::vector<int> scaled;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l)
    if (model.laws[l].law->compareRho(LawScales{}) || model.laws[l].law->compareWidth(LawScales{}))
      scaled.push_back(l);
  std::vector<std::string> out;
  if (scaled.empty()) return out;
  const auto scales = lawScales(model, scaled);
  for (size_t k = 0; k < scaled.size(); ++k) {
    if (!scales[k]) continue;
    const Law& law = *model.laws[scaled[k]].law;
    if (const std::string width = widthSentence(model, scaled[k], *scales[k]); !width.empty()) out.push_back(width);
    const auto rho = law.compareRho(*scales[k]);
    if (!rho) continue;
    const double ratio = rho->in_use / rho->scale_free;
    if (ratio <= kRhoMisscale && ratio >= 1.0 / kRhoMisscale) continue;
    out.push_back("law[" + std::to_string(scaled[k]) + "] (" + law.type() +
                  "): rho = " + formatNumber(rho->in_use) + " is " + formatNumber(ratio) +
                  " times the scale-free rho = " + formatNumber(rho->scale_free) +
                  " of this structure at omega = " + formatNumber(model.omega) +
                  "; a rho this far from it can keep the solver from converging: leave rho unset "
                  "(scale-free) or set rho_factor");
  }
  return out;
}

}  // namespace eqhb
