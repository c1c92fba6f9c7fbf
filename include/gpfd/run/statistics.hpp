// run: the statistics of `gpfd assess`: means with 95% confidence intervals, Welch's t-test and
// the Mann-Whitney U test, with effect sizes.
#pragma once

#include <vector>

namespace gpfd::run {

struct Summary {
  int n = 0;
  double mean = 0.0;
  double stddev = 0.0;     // Sample standard deviation (n - 1).
  double halfWidth = 0.0;  // Of the 95% confidence interval of the mean (Student's t).
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

}  // namespace gpfd::run
