// The samples of a parameter study: a grid or a Latin hypercube over scene
// values addressed by override paths (the paths of `--set`, e.g. law[0].muN).
//
// Samples are ordered so that a worker taking a run of consecutive samples
// can start each from the previous one's solution where `continues` says
// so: along a grid line (the last parameter varies fastest, always from
// FROM to TO; a line starts afresh), along a greedy nearest-neighbour chain
// of the hypercube. Grid lines all run the same way on purpose: peak
// tracking follows resonances that exist at a line's start, so the walk
// direction must be one the user chose (see peak_tracking.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace eqhb {

struct VariedParameter {
  std::string path;  // override path, as for --set; "A,B,…": several set to one value
  double from = 0.0, to = 0.0;
  int count = 0;     // grid points (>= 1); unused by a Latin hypercube
};

// Parses "PATH=FROM:TO:COUNT" (or "PATH=FROM:TO" when `count_required` is
// false). Throws InputError naming --vary and the rule.
VariedParameter parseVariedParameter(const std::string& text, bool count_required);

// Warm starts run along chains of at most kWarmChain samples: the first
// sample of every block of kWarmChain (in study order) starts cold, and
// workers are handed whole blocks. So every sample starts from the same
// state whatever the number of workers, and a study gives the same rows
// serially, on threads and on MPI ranks (on a rippled, stick-dominated
// resonance top, a peak depends on where its search started). Sixteen keeps
// the extra cold starts near a tenth of a study's cost.
constexpr int kWarmChain = 16;

struct StudyPlan {
  std::vector<VariedParameter> parameters;
  std::vector<std::vector<double>> samples;  // samples[i][p], in study order
  std::vector<bool> continues;  // sample i may start from sample i − 1's solution (never at a block start)
};

// The full grid (product of every parameter's COUNT points from FROM to TO)
// in lines of the last parameter. Throws InputError if it is empty or larger
// than `max_samples`.
StudyPlan makeGridPlan(const std::vector<VariedParameter>& parameters, long max_samples = 10000000);

// `count` samples of a Latin hypercube: every parameter's range cut into
// `count` equal strata, one sample per stratum, strata paired by independent
// random permutations, a uniform point inside each stratum. Reproducible
// from `seed` on every platform (std::mt19937_64, own integer/real mapping).
StudyPlan makeLatinHypercubePlan(const std::vector<VariedParameter>& parameters, int count, std::uint64_t seed);

// The override "PATH=VALUE" of parameter p for a sample, VALUE printed so
// that it reads back to the same double (one per path of a linked "A,B").
std::string sampleOverride(const StudyPlan& plan, int sample, int parameter);
std::vector<std::string> sampleOverrides(const StudyPlan& plan, int sample, int parameter);
// The paths of a parameter ("A,B" → A, B).
std::vector<std::string> parameterPaths(const VariedParameter& parameter);

}  // namespace eqhb
