#include "eqhb/studies/study_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>

#include "eqhb/error.h"
#include "eqhb/round_trip.h"

namespace eqhb {

namespace {

bool parseDouble(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

// Uniform double in [0, 1) from 53 random bits (portable, unlike
// std::uniform_real_distribution).
double unitUniform(std::mt19937_64& random) { return static_cast<double>(random() >> 11) * 0x1.0p-53; }

}  // namespace

VariedParameter parseVariedParameter(const std::string& text, bool count_required) {
  const std::size_t equals = text.find('=');
  const std::string form = count_required ? "PATH=FROM:TO:COUNT" : "PATH=FROM:TO[:COUNT]";
  if (equals == std::string::npos || equals == 0) throwInputError("vary", text, "must be " + form);
  VariedParameter p;
  p.path = text.substr(0, equals);
  for (const auto& path : split(p.path, ','))
    if (path.empty()) throwInputError("vary", text, "has an empty PATH in the list A,B,…");
  const auto parts = split(text.substr(equals + 1), ':');
  if (parts.size() != 3 && (count_required || parts.size() != 2)) throwInputError("vary", text, "must be " + form);
  if (!parseDouble(parts[0], &p.from)) throwInputError("vary " + p.path + " FROM", parts[0], "must be a finite number");
  if (!parseDouble(parts[1], &p.to)) throwInputError("vary " + p.path + " TO", parts[1], "must be a finite number");
  p.count = 1;
  if (parts.size() == 3) {
    char* end = nullptr;
    const long count = std::strtol(parts[2].c_str(), &end, 10);
    if (parts[2].empty() || *end != '\0' || count < 1 || count > 1000000)
      throwInputError("vary " + p.path + " COUNT", parts[2], "must be an integer in [1, 1000000]");
    p.count = static_cast<int>(count);
  }
  if (p.count > 1 && p.from == p.to)
    throwInputError("vary " + p.path + " TO", parts[1], "must differ from FROM when COUNT > 1");
  return p;
}

StudyPlan makeGridPlan(const std::vector<VariedParameter>& parameters, long max_samples) {
  if (parameters.empty()) throwInputError("vary", "(none)", "give at least one PATH=FROM:TO:COUNT");
  long total = 1;
  for (const auto& p : parameters) {
    total *= p.count;
    if (total > max_samples)
      throwInputError("vary", "(grid)", "the grid has more than " + std::to_string(max_samples) + " samples");
  }
  StudyPlan plan;
  plan.parameters = parameters;
  const int n = static_cast<int>(parameters.size());
  auto value = [&](int p, int k) {
    const auto& v = parameters[p];
    return v.count == 1 ? v.from : v.from + (v.to - v.from) * k / (v.count - 1);
  };
  // Mixed-radix counter, last digit fastest.
  std::vector<int> digit(n, 0);
  for (long s = 0; s < total; ++s) {
    std::vector<double> sample(n);
    for (int p = 0; p < n; ++p) sample[p] = value(p, digit[p]);
    plan.samples.push_back(std::move(sample));
    plan.continues.push_back(digit[n - 1] != 0 && s % kWarmChain != 0);
    for (int p = n - 1; p >= 0; --p) {
      if (++digit[p] < parameters[p].count) break;
      digit[p] = 0;
    }
  }
  return plan;
}

StudyPlan makeLatinHypercubePlan(const std::vector<VariedParameter>& parameters, int count, std::uint64_t seed) {
  if (parameters.empty()) throwInputError("vary", "(none)", "give at least one PATH=FROM:TO");
  if (count < 1 || count > 10000000) throwInputError("lhs", std::to_string(count), "must be in [1, 10000000]");
  const int n = static_cast<int>(parameters.size());
  std::mt19937_64 random(seed);
  std::vector<std::vector<double>> unit(count, std::vector<double>(n));
  std::vector<int> strata(count);
  for (int p = 0; p < n; ++p) {
    std::iota(strata.begin(), strata.end(), 0);
    for (int i = count - 1; i > 0; --i) std::swap(strata[i], strata[random() % static_cast<std::uint64_t>(i + 1)]);
    for (int i = 0; i < count; ++i) unit[i][p] = (strata[i] + unitUniform(random)) / count;
  }
  // Greedy nearest-neighbour chain in the unit cube from the sample nearest
  // the origin, so that consecutive samples are close (warm starts).
  std::vector<int> order;
  std::vector<bool> used(count, false);
  auto distance2 = [&](int a, int b) {
    double d = 0.0;
    for (int p = 0; p < n; ++p) d += (unit[a][p] - unit[b][p]) * (unit[a][p] - unit[b][p]);
    return d;
  };
  // O(count²): beyond kChainLimit samples, order by the first parameter.
  constexpr int kChainLimit = 20000;
  if (count > kChainLimit) {
    std::vector<int> by_first(count);
    std::iota(by_first.begin(), by_first.end(), 0);
    std::sort(by_first.begin(), by_first.end(), [&](int a, int b) { return unit[a][0] < unit[b][0]; });
    order = by_first;
  }
  int current = 0;
  for (int i = 1; i < count && order.empty(); ++i) {
    double a = 0.0, b = 0.0;
    for (int p = 0; p < n; ++p) a += unit[i][p], b += unit[current][p];
    if (a < b) current = i;
  }
  for (int k = 0; k < count && static_cast<int>(order.size()) < count; ++k) {
    order.push_back(current);
    used[current] = true;
    int next = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i)
      if (!used[i] && distance2(current, i) < best) best = distance2(current, i), next = i;
    current = next;
  }
  StudyPlan plan;
  plan.parameters = parameters;
  for (int i : order) {
    plan.continues.push_back(plan.samples.size() % kWarmChain != 0);
    std::vector<double> sample(n);
    for (int p = 0; p < n; ++p) sample[p] = parameters[p].from + (parameters[p].to - parameters[p].from) * unit[i][p];
    plan.samples.push_back(std::move(sample));
  }
  return plan;
}

std::vector<std::string> parameterPaths(const VariedParameter& parameter) { return split(parameter.path, ','); }

std::vector<std::string> sampleOverrides(const StudyPlan& plan, int sample, int parameter) {
  const std::string value = formatRoundTrip(plan.samples[sample][parameter]);
  std::vector<std::string> overrides;
  for (const auto& path : parameterPaths(plan.parameters[parameter])) overrides.push_back(path + "=" + value);
  return overrides;
}

std::string sampleOverride(const StudyPlan& plan, int sample, int parameter) {
  return plan.parameters[parameter].path + "=" + formatRoundTrip(plan.samples[sample][parameter]);
}

}  // namespace eqhb
