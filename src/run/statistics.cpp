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

Comparison compare(const std::vector<double>& a, const std::vector<double>& b) {
  Comparison c;
  const Summary sa = summarize(a), sb = summarize(b);
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

}  // namespace gpfd::run
