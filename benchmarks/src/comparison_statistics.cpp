#include "arcplan/benchmarks/comparison_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include <boost/math/distributions/hypergeometric.hpp>
#include <boost/math/distributions/normal.hpp>

#include "arcplan/common/error.h"

namespace arcplan::benchmarks {
namespace {

// Tables whose probability is within this relative margin of the observed one count as equally
// likely (the hypergeometric terms of mirror-image tables differ only by rounding).
constexpr double kEqualProbability = 1e-7;
// Largest n1 + n2 for the exact U distribution: C(60, 30) ~ 1.2e17 counts still fit in int64.
constexpr std::size_t kExactLimit = 60;

// Number of arrangements of m values of the first sample among n of the second giving each U =
// 0..mn: the coefficients of the Gaussian binomial [m+n choose m]_q, built as the product over
// i = 1..m of (1 - q^(n+i)) / (1 - q^i). Every partial product is itself a Gaussian binomial, so the
// division is exact and the integers never exceed C(m+n, m).
std::vector<std::int64_t> exactUCounts(std::size_t m, std::size_t n) {
  const std::size_t degree = m * n;
  std::vector<std::int64_t> counts(degree + 1, 0);
  counts[0] = 1;
  for (std::size_t i = 1; i <= m; ++i) {
    for (std::size_t k = degree + 1; k-- > n + i;) counts[k] -= counts[k - n - i];  // descending: old values
    for (std::size_t k = i; k <= degree; ++k) counts[k] += counts[k - i];
  }
  return counts;
}

double exactTwoSidedP(double u, std::size_t m, std::size_t n) {
  const auto counts = exactUCounts(m, n);
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  // With no ties U is a whole number.
  const auto observed = static_cast<std::size_t>(std::llround(u));
  double lower = 0.0, upper = 0.0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (k <= observed) lower += static_cast<double>(counts[k]);
    if (k >= observed) upper += static_cast<double>(counts[k]);
  }
  return std::min(1.0, 2.0 * std::min(lower, upper) / total);
}

}  // namespace

double fisherExactTwoSided(int successesA, int failuresA, int successesB, int failuresB) {
  if (successesA < 0 || failuresA < 0 || successesB < 0 || failuresB < 0) {
    throw Error("Fisher's exact test: counts must not be negative");
  }
  const unsigned sampleA = static_cast<unsigned>(successesA + failuresA);
  const unsigned total = sampleA + static_cast<unsigned>(successesB + failuresB);
  const unsigned successes = static_cast<unsigned>(successesA + successesB);
  if (sampleA == 0 || sampleA == total || successes == 0 || successes == total) return 1.0;
  const boost::math::hypergeometric_distribution<double> null(successes, sampleA, total);
  const double observed = boost::math::pdf(null, static_cast<unsigned>(successesA));
  const unsigned lowest = sampleA + successes > total ? sampleA + successes - total : 0;
  const unsigned highest = std::min(successes, sampleA);
  double p = 0.0;
  for (unsigned k = lowest; k <= highest; ++k) {
    const double probability = boost::math::pdf(null, k);
    if (probability <= observed * (1.0 + kEqualProbability)) p += probability;
  }
  return std::min(1.0, p);
}

MannWhitneyResult mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) throw Error("Mann-Whitney U test: both samples need at least one value");
  for (const auto* sample : {&a, &b}) {
    for (double value : *sample) {
      if (!std::isfinite(value)) throw Error("Mann-Whitney U test: values must be finite");
    }
  }
  const double m = static_cast<double>(a.size()), n = static_cast<double>(b.size());
  MannWhitneyResult result;
  for (double x : a) {
    for (double y : b) result.u += x > y ? 1.0 : (x == y ? 0.5 : 0.0);
  }
  result.rankBiserial = 2.0 * result.u / (m * n) - 1.0;

  // Tie groups of the pooled sample, for the variance correction.
  std::vector<double> pooled(a);
  pooled.insert(pooled.end(), b.begin(), b.end());
  std::sort(pooled.begin(), pooled.end());
  double tieTerm = 0.0;
  for (std::size_t i = 0; i < pooled.size();) {
    std::size_t j = i;
    while (j < pooled.size() && pooled[j] == pooled[i]) ++j;
    const double t = static_cast<double>(j - i);
    tieTerm += t * t * t - t;
    i = j;
  }

  if (tieTerm == 0.0 && pooled.size() <= kExactLimit) {
    result.exact = true;
    result.pValue = exactTwoSidedP(result.u, a.size(), b.size());
    return result;
  }
  const double total = m + n;
  const double variance = m * n / 12.0 * ((total + 1.0) - tieTerm / (total * (total - 1.0)));
  if (!(variance > 0.0)) {  // every value tied: no evidence of a difference
    result.pValue = 1.0;
    return result;
  }
  const double z = std::max(0.0, std::abs(result.u - m * n / 2.0) - 0.5) / std::sqrt(variance);
  const boost::math::normal_distribution<double> standardNormal;
  result.pValue = std::min(1.0, 2.0 * boost::math::cdf(boost::math::complement(standardNormal, z)));
  return result;
}

std::vector<double> holmAdjusted(const std::vector<double>& pValues) {
  std::vector<std::size_t> order(pValues.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return pValues[i] < pValues[j]; });
  std::vector<double> adjusted(pValues.size());
  double running = 0.0;
  const double m = static_cast<double>(pValues.size());
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    running = std::max(running, std::min(1.0, (m - static_cast<double>(rank)) * pValues[order[rank]]));
    adjusted[order[rank]] = running;
  }
  return adjusted;
}

double quantileOfSorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) throw Error("quantile of an empty sample");
  const double position = std::clamp(p, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const auto above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

}  // namespace arcplan::benchmarks
