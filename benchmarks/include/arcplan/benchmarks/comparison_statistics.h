#pragma once
// The tests `bench compare` runs on stochastic planners' results (campaign_comparison.h). The
// distributions come from Boost.Math (Debian's libboost-dev); what is computed here is only which
// tail of which distribution a statistic falls in.
#include <vector>

namespace arcplan::benchmarks {

// Fisher's exact test of a 2x2 table (successes and failures of two samples), two-sided: the sum of
// the hypergeometric probabilities of every table with the same margins that is no more likely than
// the observed one. Throws arcplan::Error for negative counts.
double fisherExactTwoSided(int successesA, int failuresA, int successesB, int failuresB);

struct MannWhitneyResult {
  double u = 0.0;       // U of the first sample: pairs (a, b) with a > b, ties counting 1/2
  double pValue = 1.0;  // two-sided
  bool exact = false;   // exact null distribution (no ties, n1 + n2 <= 60), else normal approximation
  // Rank-biserial correlation 2U/(n1 n2) - 1 in [-1, 1]: positive when the first sample tends larger.
  double rankBiserial = 0.0;
};
// Mann-Whitney U (Wilcoxon rank-sum) test of two independent samples. Without ties and with at most
// 60 values in all, the p-value comes from the exact distribution of U (counted with the Gaussian
// binomial coefficients); otherwise from the normal approximation with tie and continuity
// correction. Throws arcplan::Error for an empty sample or a non-finite value.
MannWhitneyResult mannWhitneyU(const std::vector<double>& a, const std::vector<double>& b);

// Holm's step-down adjustment of p-values for multiple tests (controls the family-wise error rate):
// the i-th smallest of m becomes max over j <= i of min(1, (m - j + 1) p_(j)), in the input order.
std::vector<double> holmAdjusted(const std::vector<double>& pValues);

// Type-7 (linear interpolation) quantile of sorted values, p in [0, 1]. Throws for an empty sample.
double quantileOfSorted(const std::vector<double>& sorted, double p);

}  // namespace arcplan::benchmarks
