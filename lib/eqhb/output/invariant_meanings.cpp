#include "eqhb/output/invariant_meanings.h"

#include <algorithm>
#include <utility>

namespace eqhb::output {

namespace {

// Every name a law of laws/ reports (a test checks that the shipped scenes'
// laws report no other).
const std::pair<const char*, const char*> kMeanings[] = {
    {"force_limit_excess",
     "how far |friction force| exceeds its limit muN, relative to it; a truncated series overshoots at stick-slip "
     "switches, so small values are expected"},
    {"sliding_force_error",
     "while clearly sliding, how far the force is from -muN sign(v), relative to muN; Gibbs ringing of the "
     "truncated series at each stick-slip switch keeps it at 0.1 to 0.5 on a converged solve; it falls slowly "
     "with H and is not a failure"},
    {"dissipation_deficit",
     "the share of the energy the sliding contact must dissipate (muN |v|) that it does not; near 0 on a sound "
     "solve, a large value means the force does not oppose sliding"},
    {"dae_residual",
     "how far the force samples miss the law's algebraic relation, relative to the force; aliasing of the "
     "truncated series: small, shrinking with H and N"},
    {"penetration",
     "the deepest penetration of the gap, relative to the gap's scale; ringing of the series near impacts keeps "
     "it non-zero, shrinking with H"},
    {"negative_pressure",
     "the most negative contact pressure, relative to the largest; ringing of the series where contact opens keeps "
     "it non-zero, shrinking with H"},
    {"complementarity",
     "the largest gap x pressure (0 when the contact is always either open or closed), relative; non-zero where "
     "the series rings around contact changes"},
    {"compliance_error",
     "how far the pressure is from k_n max(0, -gap), relative to the largest; ringing of the series at contact "
     "changes"},
    {"penalty_law",
     "how far the force samples miss the penalty law, relative to the force; ringing of the series at contact "
     "changes"},
    {"aft_force_error",
     "(alternating frequency-time) the largest difference between the force's series and the law evaluated in "
     "time, relative; the series of a force with switches rings, so it stays non-zero at convergence"},
};

}  // namespace

std::string invariantMeaning(const std::string& name) {
  for (const auto& [known, meaning] : kMeanings)
    if (name == known) return meaning;
  return "";
}

void writeInvariantMeanings(std::ostream& out, const std::vector<LawInvariants>& reports) {
  std::vector<std::string> seen;
  for (const auto& report : reports)
    for (const auto& entry : report.violations)
      if (std::find(seen.begin(), seen.end(), entry.first) == seen.end()) seen.push_back(entry.first);
  if (seen.empty()) return;
  out << "  what they measure (0 for the exact law; a converged truncated series only approaches it):\n";
  for (const std::string& name : seen) {
    const std::string meaning = invariantMeaning(name);
    out << "    " << name << ": " << (meaning.empty() ? "see the law's documentation" : meaning) << "\n";
  }
}

}  // namespace eqhb::output
