// run: the statistics of `gpfd assess`: means with 95% confidence intervals, Welch's t-test and
// the Mann-Whitney U test, with effect sizes.
#pragma once

#include <cmath>
#include <vector>

namespace gpfd::run {

struct Summary {
  int n = 0;
  double mean = 0.0;
  double stddev = 0.0;     // Sample standard deviation (n - 1).
  double halfWidth = 0.0;  // Of the 95% confidence interval of the mean (Student's t).

  // Of the mean: sd / sqrt(n); 0 for fewer than 2 values.
  double standardError() const { return n > 1 ? stddev / std::sqrt(static_cast<double>(n)) : 0.0; }
};
Summary summarize(const std::vector<double>& values);

struct Comparison {
  double welchT = 0.0;
  double welchDf = 0.0;
  double welchP = 1.0;        // Two-sided.
  double mannWhitneyU = 0.0;  // U of the first sample.
  double mannWhitneyP = 1.0;  // Two-sided, normal approximation with tie and continuity correction.
  double cohenD = 0.0;        // (mean a - mean b) / pooled standard deviation.
  double a12 = 0.5;           // Vargha-Delaney A: P(a > b) + P(a = b) / 2.
};
// Compares sample a against sample b (each of size >= 2).
Comparison compare(const std::vector<double>& a, const std::vector<double>& b);
// Welch's t-test of a against b from their summaries alone (each n >= 2; else p = 1): the
// welchT, welchDf and welchP of compare(), the rest left at their defaults.
Comparison welch(const Summary& a, const Summary& b);

// Paired comparison of a[i] with b[i] (same seeds): the mean difference, its standard error and
// the two-sided p-value of Student's paired t-test. p = 1 for fewer than 2 pairs; with no spread
// in the differences, p = 0 unless they are all 0.
struct PairedComparison {
  int n = 0;
  double meanDifference = 0.0;
  double standardError = 0.0;
  double p = 1.0;
};
PairedComparison comparePaired(const std::vector<double>& a, const std::vector<double>& b);

// Wilcoxon's signed-rank test (1945) of whether the values are centred on 0 (two-sided): zeros
// dropped, mid-ranks for ties (Pratt's variant is not used). Exact null distribution up to 30
// non-zero values, else the normal approximation with tie correction and continuity correction.
struct SignedRankTest {
  int n = 0;            // Non-zero values.
  double wPlus = 0.0;   // Sum of the ranks of the positive values.
  double p = 1.0;       // Two-sided.
  double median = 0.0;  // Of all values (zeros included).
};
SignedRankTest wilcoxonSignedRank(const std::vector<double>& values);

}  // namespace gpfd::run
