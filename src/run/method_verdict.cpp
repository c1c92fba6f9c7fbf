#include "gpfd/run/method_verdict.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace {

std::string meanSe(const Summary& s) {
  if (s.n == 0) return "-";
  return fmt::format("{:.4g} ± {:.2g}", s.mean, s.standardError());
}

std::string percent(double difference, double base) {
  if (base == 0 || !std::isfinite(difference)) return fmt::format("{:+.4g}", difference);
  return fmt::format("{:+.1f}%", 100.0 * difference / std::fabs(base));
}

std::string summaryFields(const Summary& s) {
  return fmt::format("{},{},{}", s.n, s.mean, s.stddev);
}

Summary summaryFrom(const std::vector<std::string>& cells, std::size_t at) {
  Summary s;
  s.n = std::stoi(cells.at(at));
  s.mean = std::stod(cells.at(at + 1));
  s.stddev = std::stod(cells.at(at + 2));
  return s;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

const char* kHeader =
    "run,seed,returned,features,size,gp_fitness,reported_n,reported_mean,reported_sd,"
    "remeasured_n,remeasured_mean,remeasured_sd,final_n,final_mean,final_sd,area_n,area_mean,"
    "area_sd,final_welch_p,final_mann_whitney_p,area_welch_p,area_mann_whitney_p";
// The header before the reported score's columns were renamed (the same columns).
const char* kHeaderBefore =
    "run,seed,returned,features,size,gp_fitness,validated_n,validated_mean,validated_sd,"
    "remeasured_n,remeasured_mean,remeasured_sd,final_n,final_mean,final_sd,area_n,area_mean,"
    "area_sd,final_welch_p,final_mann_whitney_p,area_welch_p,area_mann_whitney_p";

}  // namespace

MethodVerdict methodVerdict(const std::vector<RunAssessment>& runs, const Summary& originalFinal,
                            const Summary& originalArea,
                            const std::optional<NoLearningRow>& noLearning) {
  MethodVerdict v;
  if (noLearning) {
    v.noLearningAssessed = true;
    v.originalVsNoLearning = welch(originalFinal, noLearning->final);
    v.learnerHarms =
        v.originalVsNoLearning.welchP < 0.05 && originalFinal.mean < noLearning->final.mean;
    for (const auto& r : runs) {
      if (r.returned != "discovered") continue;
      const auto c = welch(r.final, noLearning->final);
      if (!(c.welchP < 0.05 && r.final.mean > noLearning->final.mean)) ++v.discoveredNoBetter;
    }
  }
  v.runs = static_cast<int>(runs.size());
  for (const auto& r : runs) {
    const double finalDifference = r.final.mean - originalFinal.mean;
    const double areaDifference = r.area.mean - originalArea.mean;
    v.finalDifferences.push_back(finalDifference);
    v.areaDifferences.push_back(areaDifference);
    if (r.finalVsOriginal.welchP < 0.05) ++(finalDifference > 0 ? v.betterFinal : v.worseFinal);
    if (r.areaVsOriginal.welchP < 0.05) ++(areaDifference > 0 ? v.betterArea : v.worseArea);
  }
  v.final = wilcoxonSignedRank(v.finalDifferences);
  v.area = wilcoxonSignedRank(v.areaDifferences);
  return v;
}

std::string noLearningSentence(const MethodVerdict& v) {
  if (!v.noLearningAssessed) return {};
  std::string text =
      v.learnerHarms
          ? fmt::format(
                "The learner harms: on the original variables it ends worse than no learning (a "
                "policy that ignores the state; Welch p = {:.3g}); its step sizes or budget need "
                "changing, and a gain over the original variables says little.",
                v.originalVsNoLearning.welchP)
          : fmt::format(
                "The original variables end {} no learning (a policy that ignores the state; "
                "Welch p = {:.3g}).",
                v.originalVsNoLearning.welchT > 0 && v.originalVsNoLearning.welchP < 0.05
                    ? "better than"
                    : "not significantly different from",
                v.originalVsNoLearning.welchP);
  if (v.discoveredNoBetter > 0) {
    text += fmt::format(
        " {} of {} runs returned a discovered set that ends no better than no learning (Welch p "
        ">= 0.05 or a lower mean).",
        v.discoveredNoBetter, v.runs);
  }
  return text;
}

std::string formatMethodCsv(const std::vector<RunAssessment>& runs, const Summary& originalFinal,
                            const Summary& originalArea,
                            const std::optional<NoLearningRow>& noLearning) {
  std::string csv = std::string(kHeader) + "\n";
  for (const auto& r : runs) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.run, r.seed, r.returned,
                       r.features, r.size, r.gpFitness, summaryFields(r.reported),
                       summaryFields(r.remeasured), summaryFields(r.final), summaryFields(r.area),
                       r.finalVsOriginal.welchP, r.finalVsOriginal.mannWhitneyP,
                       r.areaVsOriginal.welchP, r.areaVsOriginal.mannWhitneyP);
  }
  csv += fmt::format("original,,,,,,0,0,0,0,0,0,{},{},1,1,1,1\n", summaryFields(originalFinal),
                     summaryFields(originalArea));
  if (noLearning) {
    csv += fmt::format("no-learning,,,,,,0,0,0,0,0,0,{},{},{},nan,{},nan\n",
                       summaryFields(noLearning->final), summaryFields(noLearning->area),
                       welch(noLearning->final, originalFinal).welchP,
                       welch(noLearning->area, originalArea).welchP);
  }
  return csv;
}

std::vector<RunAssessment> parseMethodCsv(const std::string& text, const std::string& source,
                                          Summary& originalFinal, Summary& originalArea,
                                          std::optional<NoLearningRow>* noLearning) {
  std::vector<RunAssessment> runs;
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line != kHeader && line != kHeaderBefore) {
    throw InputError("not a method-level results file", source);
  }
  try {
    while (std::getline(in, line)) {
      const auto cells = split(line);
      if (cells.size() != 22) throw InputError("expected 22 fields: " + line, source);
      if (cells[0] == "original") {
        originalFinal = summaryFrom(cells, 12);
        originalArea = summaryFrom(cells, 15);
        continue;
      }
      if (cells[0] == "no-learning") {
        if (noLearning) *noLearning = NoLearningRow{summaryFrom(cells, 12), summaryFrom(cells, 15)};
        continue;
      }
      RunAssessment r;
      r.run = std::stoi(cells[0]);
      r.seed = std::stoull(cells[1]);
      r.returned = cells[2];
      r.features = std::stoul(cells[3]);
      r.size = std::stoul(cells[4]);
      r.gpFitness = std::stod(cells[5]);
      r.reported = summaryFrom(cells, 6);
      r.remeasured = summaryFrom(cells, 9);
      r.final = summaryFrom(cells, 12);
      r.area = summaryFrom(cells, 15);
      r.finalVsOriginal.welchP = std::stod(cells[18]);
      r.finalVsOriginal.mannWhitneyP = std::stod(cells[19]);
      r.areaVsOriginal.welchP = std::stod(cells[20]);
      r.areaVsOriginal.mannWhitneyP = std::stod(cells[21]);
      runs.push_back(r);
    }
  } catch (const std::logic_error& e) {  // std::stoi and friends.
    throw InputError(std::string("unreadable number: ") + e.what(), source);
  }
  return runs;
}

std::vector<std::vector<std::string>> runTable(const std::vector<RunAssessment>& runs,
                                               const Summary& originalFinal) {
  std::vector<std::vector<std::string>> rows{
      {"run", "returned", "features (nodes)", "GP fitness (biased)", "reported",
       "re-measured (fresh seeds)", "final", "vs original", "Welch p", "area Welch p"}};
  for (const auto& r : runs) {
    rows.push_back({std::to_string(r.run), r.returned, fmt::format("{} ({})", r.features, r.size),
                    fmt::format("{:.4g}", r.gpFitness), meanSe(r.reported), meanSe(r.remeasured),
                    fmt::format("{:.4g}", r.final.mean),
                    percent(r.final.mean - originalFinal.mean, originalFinal.mean),
                    fmt::format("{:.3g}", r.finalVsOriginal.welchP),
                    fmt::format("{:.3g}", r.areaVsOriginal.welchP)});
  }
  return rows;
}

std::vector<std::vector<std::string>> verdictTable(const MethodVerdict& v,
                                                   const MethodVerdict* baseline) {
  std::vector<std::string> header{"measure", "median change", "runs better (p < 0.05)",
                                  "runs worse (p < 0.05)", "Wilcoxon signed-rank p"};
  if (baseline) {
    header.insert(header.end(), {"baseline: median change", "baseline: Wilcoxon p",
                                 "vs baseline: Mann-Whitney p"});
  }
  std::vector<std::vector<std::string>> rows{header};
  const auto row = [&](const char* name, const SignedRankTest& test, int better, int worse,
                       const std::vector<double>& differences, const SignedRankTest* base,
                       const std::vector<double>* baseDifferences) {
    std::vector<std::string> cells{
        name, fmt::format("{:+.4g}", test.median), fmt::format("{} of {}", better, v.runs),
        fmt::format("{} of {}", worse, v.runs), fmt::format("{:.3g}", test.p)};
    if (base) {
      cells.push_back(fmt::format("{:+.4g}", base->median));
      cells.push_back(fmt::format("{:.3g}", base->p));
      cells.push_back(
          differences.size() >= 2 && baseDifferences->size() >= 2
              ? fmt::format("{:.3g}", compare(differences, *baseDifferences).mannWhitneyP)
              : "-");
    }
    rows.push_back(cells);
  };
  row("final performance", v.final, v.betterFinal, v.worseFinal, v.finalDifferences,
      baseline ? &baseline->final : nullptr, baseline ? &baseline->finalDifferences : nullptr);
  row("area under the curve", v.area, v.betterArea, v.worseArea, v.areaDifferences,
      baseline ? &baseline->area : nullptr, baseline ? &baseline->areaDifferences : nullptr);
  return rows;
}

}  // namespace gpfd::run
