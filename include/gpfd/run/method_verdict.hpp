// run: what several independent GP runs say about the method on one benchmark. Each run's
// returned features are assessed (long training, N runs) against the original variables; the
// verdict is the distribution of the runs' improvements, how many are significant, and Wilcoxon's
// signed-rank test over the runs' mean differences (one GP run alone cannot tell method from
// luck).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/run/statistics.hpp"

namespace gpfd::run {

// One GP run of a benchmark, as measured after the fact.
struct RunAssessment {
  int run = 0;
  std::uint64_t seed = 0;
  std::string returned;  // "discovered", "original" (validation kept them) or "gp-best".
  std::size_t features = 0, size = 0;
  double gpFitness = 0.0;  // The GP's own best fitness: a biased number, shown for contrast.
  Summary reported;        // The score the run reports for the returned set: confirmed, or
                           // selection without confirmation (n = 0 without validation).
  Summary remeasured;      // Trial scores of the returned set on fresh seeds.
  Summary final, area;     // Long assessment.
  Comparison finalVsOriginal, areaVsOriginal;
};

// The no-learning reference of the long test: the same learner and budget seeing one feature
// that is always 0 (run::TrialFeatures::noLearning).
struct NoLearningRow {
  Summary final, area;
};

struct MethodVerdict {
  int runs = 0;
  int betterFinal = 0, worseFinal = 0;  // Runs significantly better / worse (Welch p < 0.05).
  int betterArea = 0, worseArea = 0;
  std::vector<double> finalDifferences, areaDifferences;  // Run mean - original mean.
  SignedRankTest final, area;                             // Over those differences.
  // Against the no-learning reference, where it was assessed (final performance, Welch's test
  // from the summaries): whether the original variables end significantly worse (the learner
  // harms), and the runs that returned a discovered set not significantly better than it.
  bool noLearningAssessed = false;
  bool learnerHarms = false;
  Comparison originalVsNoLearning;
  int discoveredNoBetter = 0;
};
MethodVerdict methodVerdict(const std::vector<RunAssessment>& runs, const Summary& originalFinal,
                            const Summary& originalArea,
                            const std::optional<NoLearningRow>& noLearning = std::nullopt);
// The verdict's no-learning findings in a sentence or two; empty when it was not assessed.
std::string noLearningSentence(const MethodVerdict& verdict);

// method-NAME.csv: one row per run, then a row "original" with the original variables' summary,
// and a row "no-learning" with the reference's (its p columns: Welch's test against the original
// variables, final then area; Mann-Whitney's, which needs the runs' values, nan) when given.
std::string formatMethodCsv(const std::vector<RunAssessment>& runs, const Summary& originalFinal,
                            const Summary& originalArea,
                            const std::optional<NoLearningRow>& noLearning = std::nullopt);
// Reads formatMethodCsv's output back (the runs; the original row into the two summaries; the
// no-learning row, where there is one and `noLearning` is given, into it). InputError naming
// `source` on anything else.
std::vector<RunAssessment> parseMethodCsv(const std::string& text, const std::string& source,
                                          Summary& originalFinal, Summary& originalArea,
                                          std::optional<NoLearningRow>* noLearning = nullptr);

// Report tables: one row per run; the verdict (with the baseline's, when given, and the
// Mann-Whitney test of this method's improvements against the baseline's).
std::vector<std::vector<std::string>> runTable(const std::vector<RunAssessment>& runs,
                                               const Summary& originalFinal);
std::vector<std::vector<std::string>> verdictTable(const MethodVerdict& verdict,
                                                   const MethodVerdict* baseline);

}  // namespace gpfd::run
