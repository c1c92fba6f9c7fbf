#include "gpfd/run/run_set.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gpfd/run/validation.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {

std::uint64_t runSeed(std::uint64_t seed, int run) {
  constexpr std::uint64_t kRunStream = 0x52554e;
  return run == 1 ? seed : deriveSeed(seed, kRunStream, run);
}

std::string runDirName(int run, int runs) {
  return fmt::format("run-{:0{}d}", run, runs >= 100 ? 3 : 2);
}

RunOutcome outcomeOf(const Discovery& discovery, int run) {
  RunOutcome o;
  o.run = run;
  o.seed = discovery.config().seed;
  o.gpBest = discovery.history().empty() ? 0.0 : discovery.history().back().best;
  const auto& sets = discovery.validation().sets;
  const std::size_t dim = discovery.stateDim();
  if (sets.empty()) {
    const auto& best = discovery.history().back().bestGenome;
    o.features = best.featureCount();
    o.size = best.size();
    return o;
  }
  o.validated = true;
  const std::size_t returned = returnedIndex(discovery.validation(), dim);
  const auto reported = reportedScores(discovery.validation(), dim);
  o.originalWon = sets[returned].isOriginal();
  o.confirmed = reported.confirmed;
  o.winner = summarize(*reported.returned);
  o.original = summarize(*reported.original);
  o.vsOriginal = comparePaired(*reported.returned, *reported.original);
  o.features = o.originalWon ? dim : sets[returned].genome.featureCount();
  o.size = sets[returned].size(dim);
  o.noLearning = noLearningVerdict(discovery.validation(), dim);
  return o;
}

std::string formatRunsCsv(const std::vector<RunOutcome>& outcomes) {
  std::string csv =
      "run,seed,gp_best,returned,features,size,reported_mean,reported_se,original_mean,"
      "original_se,difference,p_vs_original,scored_by,no_learning_mean,no_learning_se,"
      "original_vs_no_learning,p_original_vs_no_learning,learner_harms,no_better_than_no_learning"
      "\n";
  for (const auto& o : outcomes) {
    const auto& n = o.noLearning;
    // Empty where no-learning was not scored (no validation, or a run made before it existed).
    const std::string reference =
        n.scored ? fmt::format("{},{},{},{},{},{}", n.noLearning.mean, n.noLearning.standardError(),
                               n.original.meanDifference, n.original.p, n.learnerHarms ? 1 : 0,
                               n.winnerNoBetter ? 1 : 0)
                 : std::string(",,,,,");
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", o.run, o.seed, o.gpBest,
                       !o.validated    ? "gp-best"
                       : o.originalWon ? "original"
                                       : "discovered",
                       o.features, o.size, o.winner.mean, o.winner.standardError(), o.original.mean,
                       o.original.standardError(), o.vsOriginal.meanDifference, o.vsOriginal.p,
                       !o.validated  ? "gp"
                       : o.confirmed ? "confirmation"
                                     : "validation",
                       reference);
  }
  return csv;
}

std::string formatRunsJson(std::uint64_t seed, int runs) {
  return nlohmann::json{{"seed", seed}, {"runs", runs}}.dump(1) + "\n";
}

void parseRunsJson(const std::string& text, const std::string& source, std::uint64_t& seed,
                   int& runs) {
  try {
    const auto j = nlohmann::json::parse(text);
    seed = j.at("seed").get<std::uint64_t>();
    runs = j.at("runs").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("not a runs.json: ") + e.what(), source);
  }
  if (runs < 1) throw InputError("not a runs.json: runs must be at least 1", source);
}

}  // namespace gpfd::run
