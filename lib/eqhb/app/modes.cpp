#include "eqhb/app/modes.h"

#include <algorithm>
#include <cmath>

#include "eqhb/app/solver_choice.h"
#include "eqhb/backends/registry.h"
#include "eqhb/error.h"
#include "eqhb/harmonic_balance/problem_scales.h"
#include "eqhb/modes/mode_synthesis.h"
#include "eqhb/preload/operating_point.h"
#include "eqhb/preload/static_contact.h"

namespace eqhb::app {

bool ModesOptions::isValid(std::string* why) const {
  if (mode < 1) return refuseOption(why, "mode", std::to_string(mode), "must be >= 1");
  if (branch != "auto" && branch != "held" && branch != "sliding")
    return refuseOption(why, "branch", branch, "must be auto, held or sliding");
  if (from && (!(*from > 0.0) || !std::isfinite(*from)))
    return refuseOption(why, "from", formatNumber(*from), "must be finite and > 0 (a modal amplitude)");
  if (to && (!(*to > 0.0) || !std::isfinite(*to)))
    return refuseOption(why, "to", formatNumber(*to), "must be finite and > 0 (a modal amplitude)");
  if (from && to && !(*to > *from))
    return refuseOption(why, "to", formatNumber(*to), "must be > from (" + formatNumber(*from) + ")");
  if (points < 2) return refuseOption(why, "points", std::to_string(points), "must be >= 2");
  if (!(backbone_time_limit >= 0.0) || !std::isfinite(backbone_time_limit))
    return refuseOption(why, "backbone_time_limit", formatNumber(backbone_time_limit),
                        "must be finite and >= 0 (seconds; 0 = none)");
  return solver_options.isValid(why);
}

namespace {
bool hasConstantLoad(const HbModel& model) {
  for (const HarmonicLoad& load : model.structure.loads)
    if (load.harmonic == 0 && (load.cos_amplitude != 0.0 || load.sin_amplitude != 0.0)) return true;
  return false;
}

// The force at which law l's component c slips: its force level; for a law
// without one (a contact pressed only by a scene's [[preload]]), about a
// static state where it is pressed, its friction components (those after
// its normal one) slip at the margin its static friction limit leaves,
// μN − |r_t|, and its normal one is not counted.
double slipLevel(const HbModel& model, int l, int c, const StaticContactState* at_rest) {
  const double own = std::abs(model.laws[l].law->forceLevel());
  if (own > 0.0) return own;
  const std::optional<StaticStatus>* status = at_rest ? &at_rest->status[l] : nullptr;
  if (status && *status && (*status)->friction_limit && *(*status)->friction_limit > 0.0)
    return c == 0 ? 0.0 : *(*status)->friction_limit - (*status)->tangential_force.value_or(0.0);
  return 0.0;
}

// The modal amplitude at which the first law reaches its force level (a
// friction law its slip limit μN) on the linear mode: the laws' forces are
// those that supply the mode's reaction (K − ω² M) φ per unit amplitude
// (lawForcesFor); 0 when no law has a force level or a force. About a
// static state, slipLevel's margin (blade-tip-damper's pressed damper
// slides from a ≈ 5e-6; without it the range fell back on the length scale
// and began at 4.2e-4, past the whole transition).
double onsetAmplitude(const HbModel& model, const LinearMode& mode, const StaticContactState* at_rest) {
  const LinearStructure& s = model.structure;
  const Eigen::VectorXd forces =
      lawForcesFor(model, s.stiffness * mode.shape - mode.omega * mode.omega * (s.mass * mode.shape));
  double onset = 0.0;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    for (int c = 0; c < model.laws[l].law->dimension(); ++c) {
      const double level = slipLevel(model, l, c, at_rest);
      const double per_amplitude = std::abs(forces[model.componentIndex(l, c)]);
      if (!(level > 0.0) || !(per_amplitude > 0.0)) continue;
      const double a = level / per_amplitude;
      if (onset == 0.0 || a < onset) onset = a;
    }
  }
  return onset;
}

// The modal amplitude at which a contact closed at rest (a bolt's pressed
// interface) would open on the linear mode: its static normal force over
// the normal force the mode's reaction asks of it per unit amplitude (a
// contact's first component is its normal one); 0 when none is closed.
double separationAmplitude(const HbModel& model, const LinearMode& mode, const StaticContactState& at_rest) {
  const LinearStructure& s = model.structure;
  const Eigen::VectorXd forces =
      lawForcesFor(model, s.stiffness * mode.shape - mode.omega * mode.omega * (s.mass * mode.shape));
  double separation = 0.0;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const std::optional<StaticStatus>& status = at_rest.status[l];
    if (!status || !status->normal_force || !(*status->normal_force > 0.0)) continue;
    const double per_amplitude = std::abs(forces[model.componentIndex(l, 0)]);
    if (!(per_amplitude > 0.0)) continue;
    const double a = *status->normal_force / per_amplitude;
    if (separation == 0.0 || a < separation) separation = a;
  }
  return separation;
}

// The default range (ModesOptions): 10⁻² .. 10³ times the onset amplitude,
// else the scene's length scale over max|φ|. About a static state whose
// contacts are pressed, the range ends at kPastSeparation times where the
// first would open on the linear mode (not below 10 times the onset): a
// joint's micro- and macroslip lie below, and further on the joint
// separates, a different and far costlier regime that --to can still ask
// for. The linear mode's estimate is rough once the contacts slip (the lap
// joint opens at 13 times it, the damper slides from 1.4 to 1.7 times it),
// hence the margin.
constexpr double kPastSeparation = 3.0;

// The amplitude at which the friction contacts, all sliding on the free
// mode, alone would give ζ = 1 (ModesOptions): 2 Σ level |w·φ| / (π ω²);
// 0 when no law has a force level.
double slidingDampingAmplitude(const HbModel& model, const LinearMode& mode, const StaticContactState* at_rest) {
  const int n = model.structure.dofs();
  double sum = 0.0;
  for (int l = 0; l < static_cast<int>(model.laws.size()); ++l) {
    const Eigen::MatrixXd w = model.laws[l].attachment.transposeDense(n);
    for (int c = 0; c < model.laws[l].law->dimension(); ++c)
      sum += slipLevel(model, l, c, at_rest) * std::abs(w.col(c).dot(mode.shape));
  }
  return 2.0 * sum / (M_PI * mode.omega * mode.omega);
}

// ModesOptions::branch: "auto" is sliding when the scene's sweep range holds
// the free mode K's frequency and not the held one's.
ModeBranch chosenBranch(const Scene& scene, const ModesOptions& o, const StaticContactState* at_rest) {
  if (o.branch == "held") return ModeBranch::kHeld;
  if (o.branch == "sliding") return ModeBranch::kSliding;
  if (!scene.sweep_from || !scene.sweep_to || scene.model.laws.empty()) return ModeBranch::kHeld;
  const double low = std::min(*scene.sweep_from, *scene.sweep_to), high = std::max(*scene.sweep_from, *scene.sweep_to);
  const auto inside = [&](const std::vector<LinearMode>& modes) {
    return o.mode <= static_cast<int>(modes.size()) && modes[o.mode - 1].omega >= low &&
           modes[o.mode - 1].omega <= high;
  };
  const bool held = inside(startingModes(scene.model, ModeBranch::kHeld, at_rest));
  const bool sliding = inside(startingModes(scene.model, ModeBranch::kSliding, at_rest));
  return sliding && !held ? ModeBranch::kSliding : ModeBranch::kHeld;
}

BackboneOptions chosenRange(const HbModel& model, const ModesOptions& o, ModeBranch branch,
                            const StaticContactState* at_rest) {
  const std::vector<LinearMode> modes = startingModes(model, branch, at_rest);
  const int count = static_cast<int>(modes.size());
  if (o.mode > count)
    throwInputError("mode", std::to_string(o.mode),
                    "must be in [1, " + std::to_string(count) + "]: the linearised structure has " +
                        std::to_string(count) + " mode(s)");
  const LinearMode& mode = modes[o.mode - 1];
  BackboneOptions b;
  b.mode = o.mode;
  b.branch = branch;
  b.points = o.points;
  const double sliding_reach = branch == ModeBranch::kSliding ? slidingDampingAmplitude(model, mode, at_rest) : 0.0;
  if (sliding_reach > 0.0) {
    b.from = o.from ? *o.from : 2.0 * sliding_reach;
    b.to = o.to ? *o.to : 1e3 * sliding_reach;
    if (!(b.to > b.from))
      throwInputError(o.to ? "to" : "from", formatNumber(o.to ? b.to : b.from),
                      "the range must have to > from (from = " + formatNumber(b.from) + ", to = " +
                          formatNumber(b.to) + ")");
    return b;
  }
  double reach = onsetAmplitude(model, mode, at_rest);
  if (!(reach > 0.0)) {
    HbModel unforced = model;
    unforced.structure.loads.clear();
    unforced.omega = mode.omega;
    reach = physicalScales(unforced, 0.0).displacement / mode.shape.cwiseAbs().maxCoeff();
  }
  b.from = o.from ? *o.from : 1e-2 * reach;
  b.to = o.to ? *o.to : 1e3 * reach;
  if (!o.to && at_rest) {
    const double separation = separationAmplitude(model, mode, *at_rest);
    if (separation > 0.0) b.to = std::clamp(kPastSeparation * separation, 10.0 * reach, b.to);
  }
  if (!(b.to > b.from))
    throwInputError(o.to ? "to" : "from", formatNumber(o.to ? b.to : b.from),
                    "the range must have to > from (from = " + formatNumber(b.from) + ", to = " +
                        formatNumber(b.to) + ")");
  return b;
}
}  // namespace

ModesRun modes(const SceneSettings& scene, const ModesOptions& o, const BackboneProgress& progress) {
  std::string why;
  if (!o.isValid(&why)) throw InputError(why);
  ModesRun run;
  run.scene = loadScene(scene);
  if (o.synthesis) synthesisForcing(run.scene.model);
  run.solver = o.solver;
  // A mode vibrates about the structure's static state under its constant
  // loads: a scene's [[preload]] is settled already; constant forcing (a
  // centrifugal load pressing a damper) is settled here.
  if (!run.scene.at_rest && hasConstantLoad(run.scene.model)) {
    auto statics = makeSolver("dogleg");
    run.scene.at_rest = solveStaticContact(run.scene.model, *statics, SolverOptions{});
    run.scene.model = anchoredAtRest(std::move(run.scene.model), *run.scene.at_rest);
  }
  const StaticContactState* at_rest = run.scene.at_rest ? &*run.scene.at_rest : nullptr;
  run.options = chosenRange(run.scene.model, o, chosenBranch(run.scene, o, at_rest), at_rest);
  run.options.time_limit = o.backbone_time_limit;
  run.options.condensed = o.condensed;
  auto solver = makeSolver(o.solver);
  run.backbone = followBackbone(run.scene.model, *solver, o.solver_options, run.options, progress, at_rest);
  return run;
}

}  // namespace eqhb::app
