// run: the paper's test protocol (`gpfd assess`): every feature set is trained with the long
// budget over N independent runs; learning curves with 95% intervals, final performance, and
// significance tests of each set against the original state variables.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/rl/fourier_basis.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/run/trial_runner.hpp"

namespace gpfd::run {

struct FeatureSet {
  std::string name;
  TrialFeatures features;
};

// The Fourier basis of `order` over the task's state (typical state ranges; full coupling up to
// 1024 terms, else independent). InputError when the environment knows no typical ranges.
std::shared_ptr<const rl::FourierBasis> fourierBasis(const LearningTask& task, int order);
// That basis as a set, named "fourier-ORDER" or "fourier-ORDER-independent".
FeatureSet fourierFeatureSet(const LearningTask& task, int order);

struct AssessmentResult {
  std::vector<std::string> names;
  std::vector<std::vector<rl::LearningCurve>> curves;  // [set][run]

  // The last row's mean return of every run of a set.
  std::vector<double> finals(std::size_t set) const;
  // The mean over all rows of every run of a set: the area under the learning curve, which
  // separates sets that learn at different speeds but end at the same ceiling.
  std::vector<double> areas(std::size_t set) const;
};

// Run r of set s is seeded deriveSeed(seed, s, r): independent runs, identical whatever the
// runner (threads, worker processes). `progress` (optional) counts finished runs.
AssessmentResult runAssessment(const LearningTask& task, const std::vector<FeatureSet>& sets,
                               int runs, std::uint64_t seed, TrialRunner& runner,
                               std::atomic<long>* progress = nullptr);

// One row per set: its final performance and its comparison with set `baseline`.
struct SetSummary {
  std::string name;
  Summary final;
  Comparison vsBaseline;
  Summary area;
  Comparison areaVsBaseline;
  int diverged = 0;
};
std::vector<SetSummary> summarizeAssessment(const AssessmentResult& result, std::size_t baseline);

// Writes DIR/curves.csv (set,update,episodes,runs,mean,ci_low,ci_high), DIR/finals.csv
// (set,run,final,area), DIR/summary.csv and DIR/summary.md (the statistics table), and the plot
// DIR/curves.{png,svg} (with its .dat and .gp). `title` heads the plot.
void writeAssessment(const std::string& dir, const AssessmentResult& result,
                     const std::vector<SetSummary>& summary, const std::string& title,
                     const std::string& xlabel);

// DIR/finals.csv (written by writeAssessment) read back: per set, in file order, its runs' final
// performances and areas.
struct SetFinals {
  std::string name;
  std::vector<double> finals, areas;
};
std::vector<SetFinals> readFinals(const std::string& dir);

// The statistics table of DIR/summary.md (written by writeAssessment): the header row, then one
// row per feature set, each a list of cells as formatted there.
std::vector<std::vector<std::string>> readSummaryTable(const std::string& dir);

}  // namespace gpfd::run
