#include "gpfd/run/statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <numeric>

namespace gpfd::run {

Summary summarize(const std::vector<double>& values) {
  Summary s;
  s.n = static_cast<int>(values.size());
  if (s.n == 0) return s;
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / s.n;
  if (s.n < 2) return s;
  double sq = 0.0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(sq / (s.n - 1));
  const boost::math::students_t t(s.n - 1);
  s.halfWidth = boost::math::quantile(boost::math::complement(t, 0.025)) * s.stddev /
                std::sqrt(static_cast<double>(s.n));
  return s;
}

Comparison welch(const Summary& sa, const Summary& sb) {
  Comparison c;
  const double na = sa.n, nb = sb.n;
  if (sa.n < 2 || sb.n < 2) return c;
  // Welch (1947): t = (ma - mb) / sqrt(va/na + vb/nb), Welch-Satterthwaite degrees of freedom.
  const double va = sa.stddev * sa.stddev / na, vb = sb.stddev * sb.stddev / nb;
  if (va + vb > 0) {
    c.welchT = (sa.mean - sb.mean) / std::sqrt(va + vb);
    c.welchDf = (va + vb) * (va + vb) / (va * va / (na - 1) + vb * vb / (nb - 1));
    const boost::math::students_t t(c.welchDf);
    c.welchP = 2 * boost::math::cdf(boost::math::complement(t, std::fabs(c.welchT)));
  } else {
    c.welchP = sa.mean == sb.mean ? 1.0 : 0.0;
  }
  return c;
}

Comparison compare(const std::vector<double>& a, const std::vector<double>& b) {
  const Summary sa = summarize(a), sb = summarize(b);
  const double na = sa.n, nb = sb.n;
  if (sa.n < 2 || sb.n < 2) return {};
  Comparison c = welch(sa, sb);
  const double pooled = std::sqrt(
      ((na - 1) * sa.stddev * sa.stddev + (nb - 1) * sb.stddev * sb.stddev) / (na + nb - 2));
  c.cohenD = pooled > 0 ? (sa.mean - sb.mean) / pooled : 0.0;

  // Mann & Whitney (1947) with mid-ranks for ties; normal approximation with the tie-corrected
  // variance and a continuity correction of 0.5.
  std::vector<std::pair<double, int>> all;
  for (double v : a) all.emplace_back(v, 0);
  for (double v : b) all.emplace_back(v, 1);
  std::sort(all.begin(), all.end());
  const double n = na + nb;
  double rankSumA = 0.0, tieTerm = 0.0;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    const double midRank = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;
    const double ties = static_cast<double>(j - i);
    tieTerm += ties * ties * ties - ties;
    for (std::size_t k = i; k < j; ++k) {
      if (all[k].second == 0) rankSumA += midRank;
    }
    i = j;
  }
  c.mannWhitneyU = rankSumA - na * (na + 1) / 2;
  c.a12 = c.mannWhitneyU / (na * nb);
  const double mean = na * nb / 2;
  const double variance = na * nb / 12 * ((n + 1) - tieTerm / (n * (n - 1)));
  if (variance > 0) {
    const double z = std::max(0.0, std::fabs(c.mannWhitneyU - mean) - 0.5) / std::sqrt(variance);
    c.mannWhitneyP = 2 * boost::math::cdf(boost::math::complement(boost::math::normal(), z));
  }
  return c;
}

PairedComparison comparePaired(const std::vector<double>& a, const std::vector<double>& b) {
  PairedComparison c;
  std::vector<double> d;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d.push_back(a[i] - b[i]);
  const Summary s = summarize(d);
  c.n = s.n;
  c.meanDifference = s.mean;
  if (s.n < 2) return c;
  c.standardError = s.standardError();
  if (c.standardError > 0) {
    const boost::math::students_t t(s.n - 1);
    c.p = 2 * boost::math::cdf(boost::math::complement(t, std::fabs(s.mean / c.standardError)));
  } else {
    c.p = s.mean == 0 ? 1.0 : 0.0;
  }
  return c;
}

SignedRankTest wilcoxonSignedRank(const std::vector<double>& values) {
  SignedRankTest test;
  if (!values.empty()) {
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t m = sorted.size() / 2;
    test.median = sorted.size() % 2 ? sorted[m] : 0.5 * (sorted[m - 1] + sorted[m]);
  }
  std::vector<double> nonZero;
  for (const double v : values) {
    if (v != 0) nonZero.push_back(v);
  }
  test.n = static_cast<int>(nonZero.size());
  if (test.n == 0) return test;
  std::sort(nonZero.begin(), nonZero.end(),
            [](double x, double y) { return std::fabs(x) < std::fabs(y); });
  // Doubled mid-ranks are integers, which the exact distribution below counts over.
  std::vector<int> doubledRanks(nonZero.size());
  double tieTerm = 0.0;
  for (std::size_t i = 0; i < nonZero.size();) {
    std::size_t j = i;
    while (j < nonZero.size() && std::fabs(nonZero[j]) == std::fabs(nonZero[i])) ++j;
    const double ties = static_cast<double>(j - i);
    tieTerm += ties * ties * ties - ties;
    for (std::size_t k = i; k < j; ++k) doubledRanks[k] = static_cast<int>(i + 1 + j);
    i = j;
  }
  int doubledPlus = 0, doubledTotal = 0;
  for (std::size_t i = 0; i < nonZero.size(); ++i) {
    doubledTotal += doubledRanks[i];
    if (nonZero[i] > 0) doubledPlus += doubledRanks[i];
  }
  test.wPlus = doubledPlus / 2.0;
  const int extreme = std::min(doubledPlus, doubledTotal - doubledPlus);
  if (test.n <= 30) {
    // Under the null each rank is positive with probability 1/2: count the sign patterns whose
    // doubled positive rank sum is at most `extreme` (the distribution is symmetric).
    std::vector<double> ways(static_cast<std::size_t>(doubledTotal) + 1, 0.0);
    ways[0] = 1.0;
    for (const int r : doubledRanks) {
      for (int s = doubledTotal; s >= r; --s) ways[s] += ways[s - r];
    }
    double tail = 0.0;
    for (int s = 0; s <= extreme; ++s) tail += ways[s];
    test.p = std::min(1.0, 2.0 * tail / std::ldexp(1.0, test.n));
    return test;
  }
  const double n = test.n;
  const double mean = n * (n + 1) / 4;
  const double variance = n * (n + 1) * (2 * n + 1) / 24 - tieTerm / 48;
  const double z = std::max(0.0, std::fabs(test.wPlus - mean) - 0.5) / std::sqrt(variance);
  test.p = 2 * boost::math::cdf(boost::math::complement(boost::math::normal(), z));
  return test;
}

}  // namespace gpfd::run
