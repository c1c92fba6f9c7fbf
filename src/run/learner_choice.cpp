#include "gpfd/run/learner_choice.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::run {
namespace {

// The choice's seeds: a stream of their own, which no run draws from.
constexpr std::uint64_t kChoiceStream = 0x4c4348;

std::string settingsText(const std::map<std::string, std::string>& settings) {
  std::vector<std::string> parts;
  for (const auto& [key, value] : settings) parts.push_back(key + " = " + value);
  return fmt::format("{}", fmt::join(parts, ", "));
}

// The first candidate listed before the best whose scores the best's do not beat significantly
// (the paired t-test over the same seeds, one-sided p >= choose_significance); the best if none.
std::size_t earliestNotWorse(const LearnerChoice& choice, const ExperimentConfig& config) {
  const std::vector<double>& best = choice.scores[choice.chosen];
  for (std::size_t c = 0; c < choice.chosen; ++c) {
    if (!std::isfinite(choice.means[c])) continue;
    const PairedComparison paired = comparePaired(best, choice.scores[c]);
    const double oneSided = paired.meanDifference > 0.0 ? paired.p / 2.0 : 1.0 - paired.p / 2.0;
    if (oneSided >= config.choiceSignificance) return c;
  }
  return choice.chosen;
}

}  // namespace

bool choosesLearner(const ExperimentConfig& config) {
  return !config.learnerChoices.empty() || !config.learnerAlternatives.empty();
}

std::vector<std::map<std::string, std::string>> learnerCandidates(const ExperimentConfig& config) {
  if (!config.learnerAlternatives.empty()) return config.learnerAlternatives;
  std::vector<std::map<std::string, std::string>> combinations{{}};
  for (const auto& [key, values] : config.learnerChoices) {
    std::vector<std::map<std::string, std::string>> longer;
    for (const auto& partial : combinations) {
      for (const auto& value : values) {
        auto next = partial;
        next[key] = value;
        longer.push_back(std::move(next));
      }
    }
    combinations = std::move(longer);
  }
  return combinations;
}

LearnerChoice chooseLearnerSettings(const ExperimentConfig& config, TrialRunner& runner) {
  const auto start = std::chrono::steady_clock::now();
  LearnerChoice choice;
  choice.candidates = learnerCandidates(config);
  choice.seeds = config.choiceSeeds;
  TrialBatch batch{{TrialFeatures::original()}, {{}}};
  for (int i = 0; i < config.choiceSeeds; ++i) {
    batch.seeds[0].push_back(deriveSeed(config.seed, kChoiceStream, static_cast<std::uint64_t>(i)));
  }
  choice.confirmation = config.validation.confirms();
  const auto budget =
      choice.confirmation ? LearningTask::Budget::Confirmation : LearningTask::Budget::Validation;
  for (const auto& candidate : choice.candidates) {
    ExperimentConfig trained = config;
    trained.learnerChoices.clear();
    trained.learnerAlternatives.clear();
    for (const auto& [key, value] : candidate) trained.learnerParams[key] = value;
    const LearningTask task(trained, budget);
    double sum = 0.0;
    const auto curves = runner.run(task, batch, {});
    std::vector<double>& scores = choice.scores.emplace_back();
    for (const auto& curve : curves[0]) scores.push_back(task.score(curve));
    for (const double score : scores) sum += score;
    choice.means.push_back(std::isnan(sum) ? -std::numeric_limits<double>::infinity()
                                           : sum / config.choiceSeeds);
  }
  for (std::size_t c = 1; c < choice.means.size(); ++c) {
    if (choice.means[c] > choice.means[choice.chosen]) choice.chosen = c;
  }
  if (config.choiceSignificance > 0.0) choice.chosen = earliestNotWorse(choice, config);
  choice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return choice;
}

ExperimentConfig withLearnerChoice(ExperimentConfig config, const LearnerChoice& choice) {
  for (const auto& [key, value] : choice.candidates.at(choice.chosen)) {
    config.learnerParams[key] = value;
  }
  config.learnerChoices.clear();
  config.learnerAlternatives.clear();
  return config;
}

std::string learnerChoiceText(const LearnerChoice& choice) {
  std::vector<std::string> tried;
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    tried.push_back(
        fmt::format("{:.4g} with {}", choice.means[c], settingsText(choice.candidates[c])));
  }
  return fmt::format(
      "learner settings chosen on this task: {} (the original variables' mean score on {} fresh "
      "seeds, trained as the {} trains: {}; {:.2g} s); written to config.toml\n",
      settingsText(choice.candidates.at(choice.chosen)), choice.seeds,
      choice.confirmation ? "confirmation" : "validation", fmt::join(tried, "; "), choice.seconds);
}

std::string learnerChoiceJson(const LearnerChoice& choice) {
  nlohmann::ordered_json tried = nlohmann::ordered_json::array();
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    const double mean = choice.means[c];
    tried.push_back({{"settings", choice.candidates[c]},
                     {"mean", std::isfinite(mean) ? nlohmann::ordered_json(mean) : nullptr}});
  }
  return nlohmann::ordered_json{{"seeds", choice.seeds},
                                {"training", choice.confirmation ? "confirmation" : "validation"},
                                {"tried", tried},
                                {"chosen", choice.candidates.at(choice.chosen)}}
      .dump();
}

}  // namespace gpfd::run
