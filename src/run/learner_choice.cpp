#include "gpfd/run/learner_choice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>

#include "gpfd/gp/init.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/redundancy.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::run {
namespace {

// The choice's seeds: a stream of their own, which no run draws from; the random sets' draw and
// training seeds, two more.
constexpr std::uint64_t kChoiceStream = 0x4c4348;
constexpr std::uint64_t kRandomSetsStream = 0x4c4352;
constexpr std::uint64_t kRandomSetsSeedStream = 0x4c4353;
// The seeds each random set of learner.choose_random_sets is trained on.
constexpr int kRandomSetSeeds = 3;
constexpr double kWorst = -std::numeric_limits<double>::infinity();

std::string settingsText(const std::map<std::string, std::string>& settings) {
  std::vector<std::string> parts;
  for (const auto& [key, value] : settings) parts.push_back(key + " = " + value);
  return fmt::format("{}", fmt::join(parts, ", "));
}

// Candidate c as the text says it: its settings; where learners differ, its learner, settings
// and the episodes of a training.
std::string candidateText(const LearnerChoice& choice, std::size_t c) {
  if (!choice.otherLearners) return settingsText(choice.candidates[c]);
  auto settings = choice.candidates[c];
  settings.erase(kCandidateLearnerKey);
  return fmt::format("{}{}{} ({} episodes a training)", choice.learners[c],
                     settings.empty() ? "" : " with ", settingsText(settings), choice.episodes[c]);
}

// The first candidate listed before the best whose scores the best's do not beat significantly
// (the paired t-test over the same seeds, one-sided p >= choose_significance); the best if none.
std::size_t earliestNotWorse(const LearnerChoice& choice, const ExperimentConfig& config) {
  const std::vector<double>& best = choice.scores[choice.chosen];
  for (std::size_t c = choice.fallbacksFrom; c < choice.chosen; ++c) {
    if (!std::isfinite(choice.means[c])) continue;
    const PairedComparison paired = comparePaired(best, choice.scores[c]);
    const double oneSided = paired.meanDifference > 0.0 ? paired.p / 2.0 : 1.0 - paired.p / 2.0;
    if (oneSided >= config.choiceSignificance) return c;
  }
  return choice.chosen;
}

// learner.choose_random_sets random genomes as GP's generation 0 draws them (reduced, constant
// genomes drawn again, as the run's Evolution does), from the choice's own stream: the same for
// every candidate.
std::vector<expr::Genome> randomSets(const ExperimentConfig& config, const LearningTask& task) {
  Rng rng(deriveSeed(config.seed, kRandomSetsStream, 0));
  const auto space = searchSpace(config, static_cast<int>(task.stateDim()));
  const auto reduce = genomeReducer(config, task);
  const auto admissible = genomeAdmissible(config, task);
  constexpr int kDrawsPerSet = 100;  // Then a constant genome is kept rather than none.
  std::vector<expr::Genome> sets;
  for (int i = 0; i < config.choiceRandomSets; ++i) {
    expr::Genome genome;
    for (int draw = 0; draw < kDrawsPerSet; ++draw) {
      genome = gp::randomGenome(rng, space);
      if (reduce) genome = reduce(genome);
      if (!admissible || admissible(genome)) break;
    }
    sets.push_back(std::move(genome));
  }
  return sets;
}

// The mean of `scores`; -inf where a training diverged (a NaN score).
double meanOrWorst(const std::vector<double>& scores) {
  double sum = 0.0;
  for (const double score : scores) sum += score;
  return std::isnan(sum) ? kWorst : sum / static_cast<double>(scores.size());
}

// The mean of the best quarter (at least one) of the random sets' mean scores under `task`;
// -inf where a training diverged counts as the worst.
double bestQuarterOfRandomSets(const LearningTask& task, const std::vector<expr::Genome>& genomes,
                               TrialRunner& runner) {
  TrialBatch batch;
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < kRandomSetSeeds; ++i) {
    seeds.push_back(
        deriveSeed(task.config().seed, kRandomSetsSeedStream, static_cast<std::uint64_t>(i)));
  }
  for (const auto& genome : genomes) {
    batch.sets.push_back(
        TrialFeatures::ofGenome(task.prepared(genome), task.config().withOriginal));
    batch.seeds.push_back(seeds);
  }
  const auto curves = runner.run(task, batch, {});
  std::vector<double> means;
  for (const auto& runs : curves) means.push_back(meanOrWorst(task.scores(runs)));
  std::sort(means.begin(), means.end(), std::greater<>());
  const std::size_t quarter = std::max<std::size_t>(1, means.size() / 4);
  double sum = 0.0;
  for (std::size_t i = 0; i < quarter; ++i) sum += means[i];
  return sum / static_cast<double>(quarter);
}

// Whether, with every candidate, the original variables' mean and (where tried) the random
// sets' both equal the no-learning mean to 1e-6 of their scale: no feature set tried makes the
// learner score other than a policy that ignores the state (MountainCar-v0: -200 everywhere).
// Scores that only differ by less than their noise are not taken for it: a short training
// that learns little is not one that cannot learn.
bool noCandidateLearns(const LearnerChoice& choice) {
  const auto alike = [](double a, double b) {
    const double scale = std::max({1.0, std::abs(a), std::abs(b)});
    return std::isfinite(a) && std::isfinite(b) && std::abs(a - b) <= 1e-6 * scale;
  };
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    const double reference = choice.noLearningMeans[c];
    if (!alike(choice.means[c], reference)) return false;
    if (!choice.randomSetsBest.empty() && !alike(choice.randomSetsBest[c], reference)) {
      return false;
    }
  }
  return !choice.candidates.empty();
}

// `params` with `overrides` over them.
Params merged(Params params, const Params& overrides) {
  for (const auto& [key, value] : overrides) params[key] = value;
  return params;
}

// The value of the learner's budget parameter in `params`, else its default.
std::int64_t budgetValue(const rl::LearnerInfo& info, const Params& params) {
  std::string value;
  for (const auto& spec : info.params) {
    if (spec.name == info.budgetParam) value = spec.defaultValue;
  }
  if (const auto given = params.find(info.budgetParam); given != params.end()) {
    value = given->second;
  }
  return static_cast<std::int64_t>(parseNumber(value, info.name + "." + info.budgetParam));
}

// `config` trained under `budget` for one unit of its learner's budget (rl::LearnerInfo::
// budgetParam: pg's updates, ARS's iterations): the training that times a unit.
ExperimentConfig oneUnitTraining(ExperimentConfig config, LearningTask::Budget budget) {
  const auto& key = rl::LearnerRegistry::global().info(config.learner).budgetParam;
  auto& params = budget == LearningTask::Budget::Confirmation ? config.validation.confirmParams
                                                              : config.validation.params;
  params.insert_or_assign(key, std::string{"1"});
  return config;
}

// Wall seconds of `task`'s whole training on `seed`, predicted from a training of one unit of
// its learner's budget, timed (a training of B units plays B + 1 rows of episodes); 0 where the
// learner's budget has no more than one unit.
double predictedFromOneUnit(const ExperimentConfig& trained, const LearningTask& task,
                            LearningTask::Budget budget, TrialRunner& runner, std::uint64_t seed) {
  const auto& info = rl::LearnerRegistry::global().info(trained.learner);
  const auto units = info.budgetParam.empty() ? 0 : budgetValue(info, task.learnerParams());
  if (units <= 1) return 0.0;
  const auto start = std::chrono::steady_clock::now();
  runner.run(LearningTask(oneUnitTraining(trained, budget), budget),
             {{TrialFeatures::original()}, {{seed}}}, {});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return seconds * static_cast<double>(units + 1) / 2.0;
}

}  // namespace

std::string candidateLearner(const ExperimentConfig& config, const Params& candidate) {
  const auto named = candidate.find(kCandidateLearnerKey);
  return named == candidate.end() ? config.learner : named->second;
}

std::int64_t trainingEpisodes(const std::string& learner, const Params& params) {
  const auto& info = rl::LearnerRegistry::global().info(learner);
  if (!info.rowEpisodes) return 0;
  return (budgetValue(info, params) + 1) * info.rowEpisodes(params);
}

ExperimentConfig withCandidate(ExperimentConfig config, const Params& candidate) {
  config.learnerChoices.clear();
  config.learnerAlternatives.clear();
  config.learnerFallbacks.clear();
  const std::string learner = candidateLearner(config, candidate);
  Params own = candidate;
  own.erase(kCandidateLearnerKey);
  if (learner == config.learner) {
    config.learnerParams = merged(config.learnerParams, own);
    return config;
  }
  // Another learner: its own parameters, each training's budget matched to the episodes the
  // config's learner plays in it (the same experience; pg's 15 updates of 20 episodes, 320
  // episodes, become ARS's 19 iterations of 8 directions, 320).
  const auto& registry = rl::LearnerRegistry::global();
  const auto& from = registry.info(config.learner);
  const auto& to = registry.info(learner);
  for (const auto* info : {&from, &to}) {
    if (!info->rowEpisodes) {
      throw InputError(
          fmt::format("learner {} cannot be compared with learner {} at equal episodes: {} does "
                      "not say how many episodes a training plays",
                      config.learner, learner, info->name),
          "learner.choose");
    }
  }
  const auto names = paramNames(to.params);
  // The budget parameter's value for the training `base` (the config's learner's parameters)
  // with the new learner's `params`: the most iterations that play no more episodes.
  const auto matched = [&](const Params& base, const Params& params) {
    const std::int64_t episodes = trainingEpisodes(config.learner, base);
    const std::int64_t perRow = std::max<std::int64_t>(1, to.rowEpisodes(params));
    return std::to_string(std::max<std::int64_t>(0, episodes / perRow - 1));
  };
  Params params = own;
  params[to.budgetParam] = matched(config.learnerParams, params);
  // A budget's overrides: the keys the new learner takes, but its budget, which is matched.
  const auto translated = [&](const Params& overrides) {
    Params out;
    if (overrides.empty()) return out;  // The trials' budget, matched already.
    for (const auto& [key, value] : overrides) {
      if (key != from.budgetParam && key != to.budgetParam &&
          std::find(names.begin(), names.end(), key) != names.end()) {
        out[key] = value;
      }
    }
    out[to.budgetParam] = matched(merged(config.learnerParams, overrides), merged(params, out));
    return out;
  };
  config.validation.params = translated(config.validation.params);
  config.validation.confirmParams = translated(config.validation.confirmParams);
  config.assessParams = translated(config.assessParams);
  config.rungParams = translated(config.rungParams);
  config.learnerParams = std::move(params);
  config.learner = learner;
  return config;
}

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

LearnerChoice chooseLearnerSettings(const ExperimentConfig& config, TrialRunner& runner,
                                    double allowance, int workers,
                                    const std::function<void(double)>& predicted) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  LearnerChoice choice;
  choice.candidates = learnerCandidates(config);
  const auto namesOtherLearners = [&] {
    return std::any_of(choice.candidates.begin(), choice.candidates.end(), [&](const auto& c) {
      return candidateLearner(config, c) != config.learner;
    });
  };
  choice.otherLearners = namesOtherLearners();
  const std::size_t listed = choice.candidates.size();
  choice.seeds = config.choiceSeeds;
  choice.randomSets = config.choiceRandomSets;
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < config.choiceSeeds; ++i) {
    seeds.push_back(deriveSeed(config.seed, kChoiceStream, static_cast<std::uint64_t>(i)));
  }
  choice.confirmation = config.validation.confirms();
  const auto budget =
      choice.confirmation ? LearningTask::Budget::Confirmation : LearningTask::Budget::Validation;
  // The original variables on the seeds from `from` on and, on every seed, the no-learning
  // reference (a curve depends on its features, budget and seed only: batches split anyhow
  // train the same curves).
  const auto trainPairs = [&](const LearningTask& task, std::size_t from) {
    const TrialFeatures original = TrialFeatures::original(), none = TrialFeatures::noLearning();
    if (from == 0) return runner.run(task, {{original, none}, {seeds, seeds}}, {});
    // A batch's sets share their seeds' count: the two apart.
    const std::vector<std::uint64_t> rest(seeds.begin() + static_cast<std::ptrdiff_t>(from),
                                          seeds.end());
    auto curves = runner.run(task, {{original}, {rest}}, {});
    curves.push_back(runner.run(task, {{none}, {seeds}}, {})[0]);
    return curves;
  };
  std::vector<expr::Genome> genomes;
  bool withRandomSets = config.choiceRandomSets > 0;
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    const ExperimentConfig trained = withCandidate(config, choice.candidates[c]);
    const LearningTask task(trained, budget);
    choice.learners.push_back(trained.learner);
    choice.episodes.push_back(trainingEpisodes(trained.learner, task.learnerParams()));
    std::vector<double> scores;
    // The first candidate kept with the scores it has (none, or its first training's), no
    // no-learning reference and nothing else tried.
    const auto keepFirstOnly = [&] {
      choice.cut = LearnerChoice::Cut::All;
      choice.candidates.resize(1);
      choice.scores.push_back(scores);
      choice.means.push_back(scores.empty() ? kWorst : meanOrWorst(scores));
      choice.noLearningMeans.push_back(kWorst);
      choice.merits.push_back(choice.means.back());
    };
    // Under an allowance, a training of one unit first: where the whole first training alone
    // would pass it, none is played (Swimmer-v5 stepped in Python: one training 171-207 s, of a
    // 180-s budget, docs/results/budget-call/).
    const double first = c == 0 && std::isfinite(allowance)
                             ? predictedFromOneUnit(trained, task, budget, runner, seeds[0])
                             : 0.0;
    if (first > 0.0 && predicted) predicted(first);
    if (first > allowance) {
      choice.firstSeconds = choice.predictedSeconds = first;
      choice.firstPredicted = true;
      keepFirstOnly();
      break;
    }
    if (c == 0) {
      // One training, timed, sizes the rest: all of it where it fits the allowance, else
      // without the random sets, else the first candidate alone, else none but this one.
      const double before = elapsed();
      scores = task.scores(runner.run(task, {{TrialFeatures::original()}, {{seeds[0]}}}, {})[0]);
      choice.firstSeconds = elapsed() - before;
      const double each = choice.firstSeconds / std::max(1, workers);
      const double pairs = 2.0 * config.choiceSeeds;
      const double random = withRandomSets ? kRandomSetSeeds * config.choiceRandomSets : 0.0;
      const auto candidates = static_cast<double>(choice.candidates.size());
      choice.predictedSeconds = each * (pairs + random) * candidates;
      if (each * pairs > allowance && (candidates > 1 || withRandomSets || pairs > 2)) {
        keepFirstOnly();
        break;
      }
      if (choice.predictedSeconds > allowance && withRandomSets) {
        withRandomSets = false;
        choice.cut = LearnerChoice::Cut::RandomSets;
      }
      if (each * pairs * candidates > allowance && candidates > 1) {
        choice.cut = LearnerChoice::Cut::Candidates;
        choice.candidates.resize(1);
      }
    }
    const auto curves = trainPairs(task, scores.size());
    const auto more = task.scores(curves[0]);
    scores.insert(scores.end(), more.begin(), more.end());
    choice.scores.push_back(scores);
    choice.means.push_back(meanOrWorst(scores));
    choice.noLearningMeans.push_back(meanOrWorst(task.scores(curves[1])));
    choice.merits.push_back(choice.means.back());
    if (withRandomSets) {
      if (genomes.empty()) genomes = randomSets(config, task);
      choice.randomSetsBest.push_back(bestQuarterOfRandomSets(task, genomes, runner));
      choice.merits.back() = std::max(choice.merits.back(), choice.randomSetsBest.back());
    }
    // The first candidate's whole cost, measured, sizes the others again: the first training
    // alone misjudges it where no learning plays longer episodes (Acrobot-v1's 500 steps) or
    // the machine slows. The first candidate is kept where the others would pass the allowance.
    const auto candidates = static_cast<double>(choice.candidates.size());
    if (c == 0 && candidates > 1 && elapsed() * candidates > allowance) {
      choice.cut = LearnerChoice::Cut::Candidates;
      choice.predictedSeconds = elapsed() * candidates;
      choice.candidates.resize(1);
      break;
    }
    // Every listed candidate tried and none learns: the fallbacks, where they fit the allowance
    // at the listed ones' cost each (they train as many episodes).
    if (c + 1 == listed && !config.learnerFallbacks.empty() &&
        choice.cut == LearnerChoice::Cut::None && noCandidateLearns(choice)) {
      const auto fallbacks = static_cast<double>(config.learnerFallbacks.size());
      if (elapsed() * (1.0 + fallbacks / static_cast<double>(listed)) > allowance) {
        choice.fallbacksCut = true;
      } else {
        choice.fallbacksFrom = listed;
        choice.candidates.insert(choice.candidates.end(), config.learnerFallbacks.begin(),
                                 config.learnerFallbacks.end());
        choice.otherLearners = namesOtherLearners();
      }
    }
  }
  choice.chosen = choice.fallbacksFrom;
  for (std::size_t c = choice.chosen + 1; c < choice.merits.size(); ++c) {
    if (choice.merits[c] > choice.merits[choice.chosen]) choice.chosen = c;
  }
  if (config.choiceSignificance > 0.0) choice.chosen = earliestNotWorse(choice, config);
  // Only a whole choice tells that nothing learns: random sets not tried may learn.
  choice.nothingLearns = choice.cut == LearnerChoice::Cut::None && noCandidateLearns(choice);
  choice.seconds = elapsed();
  return choice;
}

ExperimentConfig withLearnerChoice(ExperimentConfig config, const LearnerChoice& choice) {
  return withCandidate(std::move(config), choice.candidates.at(choice.chosen));
}

std::string learnerChoiceText(const LearnerChoice& choice) {
  std::vector<std::string> tried;
  const bool random = !choice.randomSetsBest.empty();
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    tried.push_back(fmt::format(
        "{}{} with {}",
        choice.scores[c].empty() ? std::string("untrained")
                                 : fmt::format("{:.4g}", choice.means[c]),
        random ? fmt::format(" (random sets {:.4g})", choice.randomSetsBest[c]) : std::string(),
        candidateText(choice, c)));
  }
  std::string cut;
  if (choice.cut == LearnerChoice::Cut::RandomSets) {
    cut = fmt::format(
        "; without the random sets: trying them too would take about {:.0f} s, more than the "
        "time budget's share for the choice",
        choice.predictedSeconds);
  } else if (choice.firstPredicted) {
    cut = fmt::format(
        "; NOT chosen: the first alternative kept untrained, since one training of the original "
        "variables would take about {:.0f} s (timed on one of a single update), more than the "
        "time budget's share for the choice; give a longer budget, or shorter trainings "
        "(learner.params, validation.confirm_params)",
        choice.firstSeconds);
  } else if (choice.cut == LearnerChoice::Cut::All) {
    cut = fmt::format(
        "; NOT chosen: the first alternative kept after one training of the original variables "
        "({:.2g} s), since trying them would take about {:.0f} s, more than the time budget's "
        "share for the choice, and nothing learning not checked; give a longer budget, or the "
        "settings (learner.params)",
        choice.firstSeconds, choice.predictedSeconds);
  } else if (choice.cut == LearnerChoice::Cut::Candidates) {
    cut = fmt::format(
        "; NOT chosen: the first alternative kept, untried against the others, since trying them "
        "would take about {:.0f} s, more than the time budget's share for the choice (its first "
        "training took {:.2g} s); give a longer budget, or the settings (learner.params)",
        choice.predictedSeconds, choice.firstSeconds);
  }
  return fmt::format(
      "learner settings chosen on this task: {} (the original variables' mean score on {} fresh "
      "seeds{}, trained as the {} trains: {}; {:.2g} s{}); written to config.toml\n",
      candidateText(choice, choice.chosen), choice.seeds,
      random ? fmt::format(", or the best quarter of {} random feature sets' on {} seeds if higher",
                           choice.randomSets, kRandomSetSeeds)
             : std::string(),
      choice.confirmation ? "confirmation" : "validation", fmt::join(tried, "; "), choice.seconds,
      choice.fallbacksFrom > 0 ? std::string("; none of the listed settings learns here, so the "
                                             "choice is among learner.choose_fallback's") +
                                     cut
                               : cut);
}

std::string learnerChoiceJson(const LearnerChoice& choice) {
  nlohmann::ordered_json tried = nlohmann::ordered_json::array();
  for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
    const auto number = [](double value) {
      return std::isfinite(value) ? nlohmann::ordered_json(value) : nullptr;
    };
    tried.push_back({{"settings", choice.candidates[c]},
                     {"mean", number(choice.means[c])},
                     {"no_learning", number(choice.noLearningMeans[c])}});
    // Only with random sets, so that other choices keep run.json's bytes.
    if (!choice.randomSetsBest.empty()) {
      tried.back()["random_sets_best"] = number(choice.randomSetsBest[c]);
    }
    // Only where learners differ, likewise.
    if (choice.otherLearners) {
      tried.back()["learner"] = choice.learners[c];
      tried.back()["episodes"] = choice.episodes[c];
    }
  }
  nlohmann::ordered_json json{{"seeds", choice.seeds},
                              {"training", choice.confirmation ? "confirmation" : "validation"},
                              {"tried", tried},
                              {"chosen", choice.candidates.at(choice.chosen)},
                              {"nothing_learns", choice.nothingLearns}};
  if (choice.otherLearners) json["learner"] = choice.learners.at(choice.chosen);
  // Only where fallbacks were tried, likewise.
  if (choice.fallbacksFrom > 0) json["fallback_from"] = choice.fallbacksFrom;
  // Only where the time budget cut the choice, so that a whole choice keeps its bytes.
  if (choice.cut == LearnerChoice::Cut::RandomSets) json["cut"] = "random sets";
  if (choice.cut == LearnerChoice::Cut::Candidates) json["cut"] = "candidates";
  if (choice.cut == LearnerChoice::Cut::All) json["cut"] = "all";
  if (choice.firstPredicted) json["first_seconds_predicted"] = choice.firstSeconds;
  return json.dump();
}

std::string nothingLearnsText(const LearnerChoice& choice) {
  const std::size_t c = choice.chosen;
  return fmt::format(
      "nothing learns here: with every learner setting tried, the original variables ({:.4g}){} "
      "score as no learning does, a policy that ignores the state ({:.4g}), over the {} seeds, so "
      "GP would compare feature sets that all score alike. The learner does not learn this task "
      "at these settings: give it more to learn from (learner.params: more updates or episodes "
      "per update; other learner.choose alternatives), a longer episode or a reward that grades "
      "progress (a sparse reward such as MountainCar-v0's is reached only by exploring), or "
      "another learner (learner.name){}",
      choice.means[c],
      choice.randomSetsBest.empty()
          ? std::string()
          : fmt::format(" and the best quarter of {} random feature sets ({:.4g})",
                        choice.randomSets, choice.randomSetsBest[c]),
      choice.noLearningMeans[c], choice.seeds,
      choice.fallbacksCut ? "; learner.choose_fallback was not tried: it would pass the time "
                            "budget's share for the choice (give a longer budget)"
                          : "");
}

}  // namespace gpfd::run
