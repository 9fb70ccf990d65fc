// bench compare's statistical tests against independent computations: hypergeometric terms by hand,
// all rank arrangements enumerated, the rank-sum variance, a textbook Holm example.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/benchmarks/comparison_statistics.h"
#include "support/error_message.h"

namespace arcplan::testing {
namespace {

double choose(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

// Fisher's two-sided p straight from the definition: hypergeometric terms C(r, k) C(N - r, n - k) / C(N, n).
double fisherByHand(int a, int b, int c, int d) {
  const int n = a + b, r = a + c, total = a + b + c + d;
  const auto term = [&](int k) { return choose(r, k) * choose(total - r, n - k) / choose(total, n); };
  double p = 0.0;
  for (int k = std::max(0, n + r - total); k <= std::min(r, n); ++k) {
    if (term(k) <= term(a) * (1 + 1e-9)) p += term(k);
  }
  return p;
}

TEST(ComparisonStatistics, FisherExactTestEqualsTheHypergeometricSumByHand) {
  // Fisher's tea-tasting table: tables 0..4 have 1, 16, 36, 16, 1 (of 70) arrangements; those no
  // more likely than 3 right are 0, 1, 3 and 4: 34/70.
  EXPECT_NEAR(benchmarks::fisherExactTwoSided(3, 1, 1, 3), 34.0 / 70.0, 1e-12);
  EXPECT_NEAR(benchmarks::fisherExactTwoSided(1, 9, 11, 3), fisherByHand(1, 9, 11, 3), 1e-12);
  EXPECT_NEAR(benchmarks::fisherExactTwoSided(10, 0, 4, 6), fisherByHand(10, 0, 4, 6), 1e-12);
  EXPECT_NEAR(benchmarks::fisherExactTwoSided(1, 9, 11, 3), 0.002759456,
              1e-8);  // R: fisher.test(matrix(c(1,11,9,3),2))
  EXPECT_DOUBLE_EQ(benchmarks::fisherExactTwoSided(5, 5, 5, 5), 1.0);
  EXPECT_DOUBLE_EQ(benchmarks::fisherExactTwoSided(10, 0, 10, 0), 1.0);
}

// Every way of choosing which of the pooled values form the first sample: the exact two-sided p of
// U by enumeration.
double mannWhitneyByEnumeration(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> pooled(a);
  pooled.insert(pooled.end(), b.begin(), b.end());
  const auto u = [](const std::vector<double>& x, const std::vector<double>& y) {
    double sum = 0.0;
    for (double p : x)
      for (double q : y) sum += p > q ? 1.0 : (p == q ? 0.5 : 0.0);
    return sum;
  };
  const double observed = u(a, b);
  const std::size_t n = pooled.size();
  int lower = 0, upper = 0, total = 0;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    if (static_cast<std::size_t>(__builtin_popcount(mask)) != a.size()) continue;
    std::vector<double> x, y;
    for (std::size_t i = 0; i < n; ++i) ((mask >> i) & 1u ? x : y).push_back(pooled[i]);
    const double value = u(x, y);
    ++total;
    lower += value <= observed;
    upper += value >= observed;
  }
  return std::min(1.0, 2.0 * std::min(lower, upper) / total);
}

TEST(ComparisonStatistics, MannWhitneyOnTheHollanderWolfeExampleIsExact) {
  // Hollander & Wolfe (1973), p. 69, the example of R's wilcox.test: W = 35, one-sided p = 0.1272.
  const std::vector<double> x{0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
  const std::vector<double> y{1.15, 0.88, 0.90, 0.74, 1.21};
  const auto result = benchmarks::mannWhitneyU(x, y);
  EXPECT_TRUE(result.exact);
  EXPECT_DOUBLE_EQ(result.u, 35.0);
  EXPECT_NEAR(result.pValue, 2 * 0.1272, 5e-4);
  EXPECT_NEAR(result.pValue, mannWhitneyByEnumeration(x, y), 1e-12);
  EXPECT_NEAR(result.rankBiserial, 2.0 * 35.0 / 50.0 - 1.0, 1e-12);
  // Swapping the samples: U' = n1 n2 - U, same two-sided p.
  const auto swapped = benchmarks::mannWhitneyU(y, x);
  EXPECT_DOUBLE_EQ(swapped.u, 15.0);
  EXPECT_NEAR(swapped.pValue, result.pValue, 1e-12);
}

TEST(ComparisonStatistics, MannWhitneyExactDistributionMatchesEnumerationOnSmallSamples) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> a(3 + trial % 6), b(4 + trial % 5);
    for (auto& v : a) v = normal(random) + 0.3 * (trial % 3);
    for (auto& v : b) v = normal(random);
    EXPECT_NEAR(benchmarks::mannWhitneyU(a, b).pValue, mannWhitneyByEnumeration(a, b), 1e-12) << trial;
  }
}

// The normal approximation with ties, computed the other way round: the rank sum of midranks and its
// variance from the ranks themselves, n1 n2 / (N (N-1)) sum r^2 - n1 n2 (N+1)^2 / (4 (N-1)).
double rankSumNormalP(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> pooled(a);
  pooled.insert(pooled.end(), b.begin(), b.end());
  const auto midrank = [&](double v) {
    double below = 0, equal = 0;
    for (double p : pooled) {
      below += p < v;
      equal += p == v;
    }
    return below + (equal + 1) / 2;
  };
  const double n1 = a.size(), n2 = b.size(), n = n1 + n2;
  double rankSum = 0, squares = 0;
  for (double v : a) rankSum += midrank(v);
  for (double v : pooled) squares += midrank(v) * midrank(v);
  const double variance = n1 * n2 / (n * (n - 1)) * squares - n1 * n2 * (n + 1) * (n + 1) / (4 * (n - 1));
  const double z = (std::abs(rankSum - n1 * (n + 1) / 2) - 0.5) / std::sqrt(variance);
  return std::erfc(z / std::sqrt(2.0));
}

TEST(ComparisonStatistics, MannWhitneyWithTiesUsesTheCorrectedNormalApproximation) {
  const std::vector<double> a{1, 2, 2, 3, 3, 3, 4, 5, 5, 6, 7, 7};
  const std::vector<double> b{3, 4, 4, 5, 6, 6, 6, 7, 8, 8, 9, 9, 10};
  const auto result = benchmarks::mannWhitneyU(a, b);
  EXPECT_FALSE(result.exact);
  EXPECT_NEAR(result.pValue, rankSumNormalP(a, b), 1e-12);
  EXPECT_DOUBLE_EQ(benchmarks::mannWhitneyU({1, 1, 1}, {1, 1}).pValue, 1.0);  // all tied: no evidence
  EXPECT_NE(errorMessageOf([] { benchmarks::mannWhitneyU({}, {1.0}); }), "(no error)");
}

TEST(ComparisonStatistics, HolmAdjustmentOfATextbookExample) {
  // sorted 0.005, 0.01, 0.03, 0.04 times 4, 3, 2, 1: 0.02, 0.03, 0.06, 0.04 -> running max 0.06.
  const auto adjusted = benchmarks::holmAdjusted({0.01, 0.04, 0.03, 0.005});
  ASSERT_EQ(adjusted.size(), 4u);
  EXPECT_NEAR(adjusted[0], 0.03, 1e-15);
  EXPECT_NEAR(adjusted[1], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[2], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[3], 0.02, 1e-15);
  EXPECT_DOUBLE_EQ(benchmarks::holmAdjusted({0.6, 0.7})[1], 1.0);
}

}  // namespace
}  // namespace arcplan::testing
