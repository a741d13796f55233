// The monodromy of the linearised dynamics over a harmonic-balance orbit for
// laws that act by springs: penalty contact (laws/penalty_contact.h),
// elastic dry friction with one slider (Jenkins, in the AFT form of
// laws/joints/jenkins_aft.h or the exact form of laws/joints/jenkins.h),
// each on one relative coordinate u = w·x (grounded: one DOF; between two
// nodes: both), and the elastic-friction element with one tangent
// (laws/joints/elastic_friction_aft.h) on its two, [u_n; u_t]. Used by
// MonodromyStability (monodromy_stability.h) when every law of a model is
// one of these.
//
// A "channel" below is one coordinate a law acts on: a penalty contact and
// a Jenkins slider are one each; an elastic-friction element is two, its
// normal contact (a penalty spring k_n beyond the gap g0) and its slider on
// u_t, whose limit μ p = μ k_n (u_n − g0) follows the normal channel.
//
// Per channel and sample the state is read from the solution as the law
// itself reads it: a penalty contact is closed where u > g0; a Jenkins
// slider sticks where its return map over the samples of u (JenkinsAft::
// evaluate, the same passes and anchors as the harmonic balance) leaves the
// trial force inside ±μN; an elastic-friction slider is free where its
// contact is open, stuck where its trial force is inside ±μp and slips with
// the trial's sign where it is not, by the law's return map (elastic_
// friction_aft.h) but started at a closing contact from u_t at the closing
// instant (classifyElasticSlider says why). Between two switching instants
// every channel is in one state and a perturbation y = [δq; δq̇; δz] obeys
//   M δq̈ + C δq̇ + (K + Σ_closed k_n w wᵀ + Σ_stuck k_t w wᵀ
//                    + Σ_slipping s μ k_n w_t w_nᵀ) δq = Σ_stuck k_t w δz,
// δż = 0,                                                               (1)
// whose transition over a phase of length τ is exp(A τ) exactly; the last
// sum is an elastic-friction slider slipping with T = s μ p (s = ±1), whose
// force follows its normal coordinate (a Jenkins slider's limit is fixed).
//
// z is the slider's anchor: stuck, the force is −k_t (u − z) with z set at
// the stick onset; slipping, it is the constant ±μN and z = u ∓ μN/k_t
// follows u (ż = u̇). The exact flow of [x; v; z] is continuous in x and v
// at every switch (the forces are continuous), so the only saltation is in
// z. With S = I + (f⁺ − f⁻) ∇gᵀ / ġ⁻:
//   stick → slip, g = −k_t (u − z) ∓ μN, ∇g = −k_t [wᵀ 0 −1], ġ⁻ = −k_t u̇,
//     f⁺ − f⁻ = [0; 0; u̇]  ⇒  δz⁺ = δz + (wᵀδx − δz) = wᵀ δx;        (2)
//   slip → stick, g = u̇: ż = u̇ = 0 on both sides, S = I.             (3)
// By (2) a slipping slider's perturbation is δz = wᵀδx: its δz carries
// nothing of its own while it slips, so it is not propagated there (its row
// of (1) is 0 and its force term absent) and is set at the stick onset,
//   δz := wᵀ δx  at slip → stick,                                       (4)
// which is (3) applied to the slaved δz. An elastic-friction slider's
// anchor while it slips is z = u_t − s μ k_n (u_n − g0)/k_t, and the same
// steps give
//   δz := w_tᵀ δx − s (μ k_n / k_t) w_nᵀ δx  at slip → stick;            (4')
// where its contact closes into stick the anchor is u_t at the closing
// instant t_c, which moves by δt_c = −w_nᵀδx / u̇_n:
//   δz := w_tᵀ δx − (u̇_t / u̇_n) w_nᵀ δx  at open → stuck.               (4'')
// A penalty contact's field is continuous at u = g0 (and the slider's force
// is 0 there on both sides): S = I. A slider that never slips keeps the
// anchor the harmonic balance gives it (the period's mean of u, or its
// static position): it is a spring k_t without a z, as in the harmonic
// balance's Jacobian, so an orbit that never slips nor opens has the linear
// structure's multipliers (the neutral drift of a stuck anchor, a
// multiplier 1, is left out as Hill's method leaves it out). A slider that
// slips has one z: the multipliers are 2m + (sliders that slip), one of
// them 0 per such slider (δz is forgotten while it slips); an
// elastic-friction slider that never sticks has none.
//
// Switching instants lie between two samples, placed by linear
// interpolation of what vanishes there: u − g0 (contact, and an
// elastic-friction slider's switches to or from free), the slider's rate
// u̇ (Jenkins) or u̇_t − s μ k_n u̇_n / k_t (elastic friction) at a stick
// onset, |trial force| − limit at a slip onset. A slider whose slip turns
// over between two slipping samples (a stick shorter than a sample) is
// taken as slipping.
//
// The product is formed in the phases' modal coordinates
// (spring_law_modes.cpp). A phase's generator is A = [A₁₁ B; 0 0]: A₁₁ the
// structure's with the stuck and closed springs in, B the stuck anchors'
// forces. A₁₁ depends on the laws' states in the phase only, not on which
// sliders slip somewhere in the period (that set changes along a curve and
// with it every phase's B): A₁₁ = V D V⁻¹ is decomposed once per set of
// states, and a = V⁻¹ (x + A₁₁⁻¹ B z) obeys ȧ = D a. Modes that a phase
// damps below PhaseExponential::kNegligibleGrowth are dropped, so the
// product carries only the modes that outlast their phase.
#pragma once

#include <Eigen/Dense>
#include <map>
#include <memory>
#include <vector>

#include "eqhb/harmonic_balance/hb_model.h"
#include "eqhb/laws/law.h"
#include "eqhb/stability/phase_exponential.h"

namespace eqhb {

class FourierTransform;
class JenkinsAft;

class SpringLawMonodromy {
 public:
  // The propagation's dynamics (m x m) come from MonodromyStability: the
  // full structure's or a reduction's that keeps every law's coordinate
  // exactly; `law_directions` holds per law and component, in order, its w
  // in q (u = wᵀq): one per channel.
  SpringLawMonodromy(const HbModel& model, const Eigen::MatrixXd& mass_inverse, const Eigen::MatrixXd& damping,
                     const Eigen::MatrixXd& stiffness, const std::vector<Eigen::VectorXd>& law_directions);
  ~SpringLawMonodromy();
  SpringLawMonodromy(const SpringLawMonodromy&) = delete;
  SpringLawMonodromy& operator=(const SpringLawMonodromy&) = delete;
  // True when every law is a penalty contact or a Jenkins element (exact,
  // or AFT with one slider) on one coordinate (grounded or relative), or an
  // elastic-friction element with one tangent, and there is one at least.
  static bool supports(const HbModel& model);
  // The sets of states whose decompositions are kept at most (a cache).
  static constexpr size_t kMaxCachedSets = 256;
  // The Floquet multipliers of `full` ([x; λ] on the model's basis) at
  // ω: 2m + the sliders that slip, those of dropped modes as 0.
  // `exponentials` counts the phases' exponentials applied.
  const Eigen::VectorXcd& multipliers(double omega, const Eigen::VectorXd& full, long& exponentials,
                                      long& syntheses);

 private:
  // A channel's state in a phase. Penalty contacts and Jenkins sliders are
  // free or held (open / closed, slipping / stuck); an elastic-friction
  // slider also slips with T = +μp or −μp, a force that follows u_n.
  enum State : char { kFree = 0, kHeld = 1, kSlipPositive = 2, kSlipNegative = 3 };
  struct Switch {
    double time = 0.0;
    int law = 0;              // the channel
    char state = kFree;       // its state after it
    double normal_reset = 0;  // an anchor reset's weight on w_nᵀδx ((4'), (4''))
  };
  // The modes of A₁₁ for one set of stuck or closed laws (header), and
  // where a unit anchor displacement of each stuck slider moves them.
  struct ActiveModes {
    PhaseExponential exponential;  // of A₁₁ in [δq; δq̇/Ω]
    Eigen::MatrixXd anchor_shift;  // 2m x laws: column l = A₁₁⁻¹ B_l for a stuck slider l, else 0
    Eigen::MatrixXd anchor_modes;  // V⁻¹ anchor_shift
    std::vector<int> sliders;      // the stuck sliders (their columns above)
    bool usable = false;           // decomposed, and A₁₁ invertible if a slider is stuck
  };
  void classify(double omega, const Eigen::VectorXd& full, long& syntheses);
  // Channel l's state at sample k (active_).
  char& state(int k, int l) { return active_[static_cast<size_t>(k) * laws_ + l]; }
  char state(int k, int l) const { return active_[static_cast<size_t>(k) * laws_ + l]; }
  // The states of the elastic-friction element whose normal channel is
  // `normal` (its slider the next), from u_ (u_n, u_t).
  void classifyElasticSlider(const Law& law, int normal);
  void findSwitches(double omega);
  // A₁₁ of (1) for the laws' states `active`, and K with their springs in.
  Eigen::MatrixXd structuralGenerator(const std::vector<char>& active, Eigen::MatrixXd& stiffness) const;
  // A₁₁'s modes, decomposed once per set of states (spring_law_modes.cpp).
  const ActiveModes& activeModes(const std::vector<char>& active);
  // The whole A of (1) with the current slots, once per key: the route
  // where some A₁₁ is not decomposed.
  const PhaseExponential& generator(const std::vector<char>& active);
  // The length of phase j (from switch j to the next, round the period).
  double phaseLength(size_t j, double period) const;
  bool resetsAnchor(const Switch& s) const;
  // The anchor's perturbation a reset sets ((4), (4'), (4'')) from δq (the
  // top m rows of `x`), into `row`.
  template <typename Row, typename Block>
  void resetAnchor(const Switch& s, const Block& x, Row&& row) const {
    row.noalias() = direction_[s.law].transpose() * x.topRows(m_);
    if (s.normal_reset != 0.0)
      row.noalias() += s.normal_reset * direction_[partner_[s.law]].transpose() * x.topRows(m_);
  }
  // An elastic-friction slider's switch between sample k and `next`, from
  // state a to b: its instant and its anchor's reset (the header's).
  Switch elasticSliderSwitch(int l, int k, int next, char a, char b, double step) const;
  // multipliers_ from the product in the phases' leading modes (header;
  // spring_law_modes.cpp), every phase's ActiveModes usable.
  void chainLeadingModes(double period);
  // multipliers_ from Φ = Π exp(A_j τ_j) with the resets, formed in full.
  void chainInFull(double period);
  void eigenvaluesOf(const Eigen::Ref<const Eigen::MatrixXd>& phi, Eigen::Index size);

  HbModel model_;
  std::unique_ptr<FourierTransform> transform_;
  int m_ = 0, laws_ = 0;                    // laws_: the channels (the header)
  double scale_ = 1.0;                      // Ω of the scaled velocities (generator())
  Eigen::MatrixXd mass_inverse_, damping_, stiffness_;
  std::vector<Eigen::VectorXd> direction_;  // per law: w in q (m)
  std::vector<double> spring_;              // per law: k_n or k_t
  std::vector<bool> contact_;
  std::vector<double> gap_;                 // g0 (contacts)
  std::vector<double> limit_;               // μN (Jenkins sliders), μ (elastic-friction sliders)
  std::vector<int> partner_;                // per channel: an elastic-friction slider's normal channel, else -1
  std::vector<int> first_channel_;          // per law: its first channel
  std::vector<std::unique_ptr<JenkinsAft>> readers_;  // per law: an exact Jenkins law's slider's return map
  std::vector<int> slot_;                   // per law: its z's index among the slipping sliders, or -1
  int sliders_ = 0;                         // z's at this point
  std::vector<LawSamples> samples_;         // per law: a Jenkins slider's samples for its return map
  Eigen::MatrixXd u_, rate_, force_;        // N x channels (force: a slider's T, an elastic contact's p)
  Eigen::VectorXd buffer_, derivative_;     // coefficient buffers (one channel)
  std::vector<char> active_;                // N x channels, row-major: each one's State
  std::vector<Switch> switches_;
  std::vector<char> current_;
  std::map<std::vector<char>, ActiveModes> modes_;  // by the laws' states; cleared between points only
  std::map<std::pair<std::vector<char>, std::vector<int>>, PhaseExponential> generators_;
  std::vector<std::vector<char>> phase_states_;     // per phase of the point: the laws' states
  std::vector<const ActiveModes*> phase_modes_;     // and its modes
  std::vector<double> phase_length_;
  std::vector<Eigen::Index> kept_;                  // per phase: the modes that outlast it
  // Storage reused from point to point: the product in a phase's leading
  // modes (2m rows at most) and the anchors (sliders), the same in
  // [δq; δq̇/Ω], the product reduced to the kept modes, the whole Φ.
  Eigen::MatrixXd modal_, anchors_, physical_, reduced_;
  Eigen::MatrixXd scratch_, phi_;
  Eigen::EigenSolver<Eigen::MatrixXd> eigen_;
  Eigen::VectorXcd multipliers_;
};

}  // namespace eqhb
