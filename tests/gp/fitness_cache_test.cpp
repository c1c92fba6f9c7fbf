#include "gpfd/gp/fitness_cache.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gpfd/expr/parse.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::gp {
namespace {

expr::Genome genome(const std::string& features) {
  expr::Genome g;
  std::size_t from = 0;
  for (;;) {
    const auto end = features.find(';', from);
    g.addFeature(expr::parseInfix(features.substr(from, end - from), {"a", "b"}));
    if (end == std::string::npos) return g;
    from = end + 1;
  }
}

// Scores a genome with its seed (a stand-in for the mean of K trials) and counts the calls.
class SeedScore final : public Evaluator {
 public:
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    calls += static_cast<int>(genomes.size());
    std::vector<double> out;
    for (const auto s : seeds) out.push_back(s == 666 ? NAN : static_cast<double>(s));
    return out;
  }
  int calls = 0;
};

TEST(FitnessCache, WithoutReevaluationTheFirstValueStays) {
  SeedScore inner;
  CachingEvaluator cache(inner, 5, 0);
  const auto g = genome("a + b");
  EXPECT_EQ(cache.evaluate({&g}, {10}), std::vector<double>{10.0});
  EXPECT_EQ(cache.evaluate({&g, &g}, {20, 30}), (std::vector<double>{10.0, 10.0}));
  EXPECT_EQ(inner.calls, 1);
  EXPECT_EQ(cache.lastHits(), 2);
  EXPECT_EQ(cache.entries().at(canonicalKey(g)).trials, 5);
}

TEST(FitnessCache, AGenomeMetAgainGetsFreshTrialsUpToTheCap) {
  SeedScore inner;
  CachingEvaluator cache(inner, 2, 6);
  const auto g = genome("a * b"), same = genome("a * b");
  EXPECT_EQ(cache.evaluate({&g}, {10}), std::vector<double>{10.0});
  // Met again: fresh trials on its new seed; the mean of 4 trials.
  EXPECT_EQ(cache.evaluate({&same}, {20}), std::vector<double>{15.0});
  EXPECT_EQ(cache.lastReevaluated(), 1);
  // Twice in one batch: one evaluation, shared.
  EXPECT_EQ(cache.evaluate({&g, &same}, {40, 50}),
            (std::vector<double>{(10 + 20 + 40) / 3.0, (10 + 20 + 40) / 3.0}));
  EXPECT_EQ(cache.entries().at(canonicalKey(g)).trials, 6);
  // At the cap: no more trials.
  EXPECT_EQ(cache.evaluate({&g}, {70}), std::vector<double>{(10 + 20 + 40) / 3.0});
  EXPECT_EQ(cache.lastHits(), 1);
  EXPECT_EQ(inner.calls, 3);
}

TEST(FitnessCache, AtMostTheLimitIsReevaluatedBestFirst) {
  SeedScore inner;
  CachingEvaluator cache(inner, 1, 10, 2);
  const auto a = genome("a"), b = genome("b"), c = genome("a * b"), d = genome("a + b");
  cache.evaluate({&a, &b, &c, &d}, {1, 4, 3, 2});
  EXPECT_EQ(inner.calls, 4);
  // All four met again: only the two best (b: 4, c: 3) get fresh trials.
  const auto out = cache.evaluate({&a, &b, &c, &d}, {100, 100, 100, 100});
  EXPECT_EQ(out, (std::vector<double>{1, 52, 51.5, 2}));
  EXPECT_EQ(cache.lastReevaluated(), 2);
  EXPECT_EQ(cache.lastHits(), 2);
  EXPECT_EQ(inner.calls, 6);
}

TEST(FitnessCache, ADivergedEvaluationIsFinal) {
  SeedScore inner;
  CachingEvaluator cache(inner, 1, 10);
  const auto g = genome("a");
  cache.evaluate({&g}, {5});
  EXPECT_EQ(cache.evaluate({&g}, {666}), std::vector<double>{-INFINITY});
  EXPECT_EQ(cache.evaluate({&g}, {7}), std::vector<double>{-INFINITY});
  EXPECT_EQ(inner.calls, 2);
}

TEST(FitnessCache, ACapBelowTheTrialsIsRefused) {
  SeedScore inner;
  EXPECT_THROW(CachingEvaluator(inner, 5, 4), InputError);
  EXPECT_NO_THROW(CachingEvaluator(inner, 5, 5));
  EXPECT_NO_THROW(CachingEvaluator(inner, 5, 0));
}

TEST(FitnessCache, KeysReadBackAsTheirGenomes) {
  const auto g = genome("sin(a) / 2;b - 0.1");
  const auto key = canonicalKey(g);
  EXPECT_EQ(canonicalKey(genomeFromKey(key)), key);
  EXPECT_EQ(genomeFromKey(key).featureCount(), 2u);
}

}  // namespace
}  // namespace gpfd::gp
