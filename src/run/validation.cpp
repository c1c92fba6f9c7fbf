#include "gpfd/run/validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "gpfd/expr/print.hpp"
#include "gpfd/run/redundancy.hpp"

namespace gpfd::run {
namespace {

expr::Genome identityGenome(std::size_t stateDim) {
  expr::Genome genome;
  for (std::size_t i = 0; i < stateDim; ++i) {
    const expr::Node variable = expr::Node::variable(static_cast<int>(i));
    genome.addFeature(expr::TreeView(&variable, 1));
  }
  return genome;
}

// The no-learning row's description in the tables.
const char* const kNoLearningText =
    "no learning: one feature, always 0 (a policy that ignores the state)";

std::string featuresText(const ValidatedSet& set, const std::vector<std::string>& names) {
  if (set.isOriginal()) return "original variables";
  std::string text;
  for (std::size_t k = 0; k < set.genome.featureCount(); ++k) {
    text += (k > 0 ? " ; " : "") + expr::toInfix(set.genome.feature(k), names);
  }
  return text;
}

// CSV field: quoted, with quotes doubled.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Indices of `sets`, best mean first (ties: smaller, then original, then key order).
std::vector<std::size_t> ranking(const std::vector<ValidatedSet>& sets, std::size_t stateDim) {
  std::vector<double> means;
  for (const auto& s : sets) means.push_back(s.summary().mean);
  std::vector<std::size_t> order(sets.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (means[a] != means[b]) return means[a] > means[b];
    if (sets[a].size(stateDim) != sets[b].size(stateDim))
      return sets[a].size(stateDim) < sets[b].size(stateDim);
    return sets[a].isOriginal() && !sets[b].isOriginal();
  });
  return order;
}

}  // namespace

std::size_t ValidatedSet::size(std::size_t stateDim) const {
  return isOriginal() ? stateDim : genome.size();
}

std::vector<HallOfFameEntry> hallOfFame(const std::map<std::string, gp::FitnessRecord>& cache,
                                        int size, double sizePenalty) {
  std::vector<HallOfFameEntry> all;
  for (const auto& [key, record] : cache) {
    if (!std::isfinite(record.mean)) continue;
    expr::Genome genome = gp::genomeFromKey(key);
    // Placeholders alone show the learner nothing beside the original variables, which are
    // always a candidate, or nothing at all without them.
    if (onlyPlaceholders(genome)) continue;
    const double fitness = record.mean - sizePenalty * static_cast<double>(genome.size());
    all.push_back({key, std::move(genome), fitness, record.trials});
  }
  std::stable_sort(all.begin(), all.end(), [](const HallOfFameEntry& a, const HallOfFameEntry& b) {
    return a.fitness > b.fitness;
  });
  if (all.size() > static_cast<std::size_t>(size)) all.resize(static_cast<std::size_t>(size));
  return all;
}

bool Confirmation::held() const {
  return !key.empty() && comparePaired(winner, original).meanDifference > 0.0;
}

namespace {

// Whether `scores` are significantly better than `noLearning` on the same seeds at `level`; true
// when no-learning was not scored.
bool beats(const std::vector<double>& scores, const std::vector<double>& noLearning, double level) {
  if (noLearning.empty()) return true;
  const auto paired = comparePaired(scores, noLearning);
  return paired.meanDifference > 0.0 && paired.p < level;
}

}  // namespace

bool Confirmation::beatsNoLearning() const { return beats(winner, noLearning, noLearningLevel); }

Validator::Validator(const ExperimentConfig& config, TrialRunner& runner, std::uint64_t stream)
    : Validator(config, runner, LearningTask::Budget::Validation, config.validation.seeds, stream) {
}

Validator::Validator(const ExperimentConfig& config, TrialRunner& runner,
                     LearningTask::Budget budget, int seeds, std::uint64_t stream)
    : task_(config, budget), runner_(&runner), seeds_(seeds), stream_(stream) {}

Validator Validator::confirmation(const ExperimentConfig& config, TrialRunner& runner) {
  return {config, runner, LearningTask::Budget::Confirmation, config.validation.confirmSeeds,
          kConfirmationStream};
}

std::vector<std::vector<double>> Validator::score(const std::vector<TrialFeatures>& sets) const {
  return score(sets, 0, seeds_);
}

std::vector<std::vector<double>> Validator::score(const std::vector<TrialFeatures>& sets, int from,
                                                  int to) const {
  TrialBatch batch{sets, {}};
  for (std::size_t s = 0; s < sets.size(); ++s) {
    auto& seeds = batch.seeds.emplace_back();
    for (int m = from; m < to; ++m) {
      seeds.push_back(deriveSeed(task_.config().seed, stream_, static_cast<std::uint64_t>(m)));
    }
  }
  const auto curves = runner_->run(task_, batch, {});
  std::vector<std::vector<double>> scores(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s) {
    scores[s] = task_.scores(curves[s]);
  }
  return scores;
}

std::vector<TrialFeatures> Validator::features(
    const std::vector<const expr::Genome*>& genomes) const {
  std::vector<TrialFeatures> sets;
  for (const auto* genome : genomes) {
    // As task_.featureMap(*genome) compiles it.
    sets.push_back(genome != nullptr ? TrialFeatures::ofGenome(task_.prepared(*genome),
                                                               task_.config().withOriginal)
                                     : TrialFeatures::original());
  }
  return sets;
}

std::vector<std::vector<double>> Validator::score(
    const std::vector<const expr::Genome*>& sets) const {
  return score(features(sets));
}

std::size_t originalIndex(const std::vector<ValidatedSet>& sets) {
  for (std::size_t i = 0; i < sets.size(); ++i) {
    if (sets[i].isOriginal()) return i;
  }
  throw std::logic_error("validation without the original variables");
}

namespace {

// The canonical keys of a genome's features, one feature at a time (so that equal features
// compare equal whatever genome they are in; operands are not reordered: `x * y` is not `y * x`).
std::set<std::string> featureKeys(const expr::Genome& genome) {
  std::set<std::string> keys;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    expr::Genome feature;
    feature.addFeature(genome.feature(k));
    keys.insert(gp::canonicalKey(feature));
  }
  return keys;
}

// Whether discovered set `part` is made of some, not all, of the features `whole` (featureKeys).
bool isProperPart(const ValidatedSet& part, const std::set<std::string>& whole) {
  const auto features = featureKeys(part.genome);
  return features.size() < whole.size() &&
         std::includes(whole.begin(), whole.end(), features.begin(), features.end());
}

// Whether `a` is simpler than `b`: fewer features, then fewer nodes, then the better mean.
bool simpler(const ValidatedSet& a, const ValidatedSet& b) {
  if (a.genome.featureCount() != b.genome.featureCount()) {
    return a.genome.featureCount() < b.genome.featureCount();
  }
  if (a.genome.size() != b.genome.size()) return a.genome.size() < b.genome.size();
  return a.summary().mean > b.summary().mean;
}

}  // namespace

std::size_t chooseWinner(const std::vector<ValidatedSet>& sets, std::size_t stateDim,
                         double parsimonySe) {
  const std::size_t best = ranking(sets, stateDim).front();
  if (parsimonySe <= 0.0 || sets[best].isOriginal()) return best;
  const Summary summary = sets[best].summary();
  const double floor = summary.mean - parsimonySe * summary.standardError();
  const auto bestFeatures = featureKeys(sets[best].genome);
  std::size_t chosen = best;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const auto& set = sets[i];
    if (set.isOriginal() || !(set.summary().mean >= floor)) continue;
    if (isProperPart(set, bestFeatures) && simpler(set, sets[chosen])) chosen = i;
  }
  return chosen;
}

std::size_t chooseWinner(const ValidationState& state, std::size_t stateDim) {
  return chooseWinner(state.sets, stateDim, state.parsimonySe);
}

namespace {

// Whether the state's confirmation is of its current validation winner (a run extended after it
// finished validates more sets, and its old confirmation no longer applies until redone).
bool confirmsWinner(const ValidationState& state, std::size_t stateDim) {
  return state.confirmation.done() &&
         state.confirmation.key == state.sets[chooseWinner(state, stateDim)].key;
}

}  // namespace

std::size_t returnedIndex(const ValidationState& state, std::size_t stateDim) {
  const std::size_t winner = chooseWinner(state, stateDim);
  if (state.sets[winner].isOriginal()) return winner;
  const auto& confirmation = state.confirmation;
  const bool holds = confirmsWinner(state, stateDim)
                         ? confirmation.held() && confirmation.beatsNoLearning()
                         : beats(state.sets[winner].scores, state.noLearning, 0.05);
  return holds ? winner : originalIndex(state.sets);
}

ReportedScores reportedScores(const ValidationState& state, std::size_t stateDim) {
  const auto& confirmation = state.confirmation;
  const std::size_t returned = returnedIndex(state, stateDim);
  if (!confirmsWinner(state, stateDim)) {
    return {&state.sets[returned].scores, &state.sets[originalIndex(state.sets)].scores, false,
            &state.noLearning};
  }
  return {state.sets[returned].isOriginal() ? &confirmation.original : &confirmation.winner,
          &confirmation.original, true, &confirmation.noLearning};
}

NoLearningVerdict noLearningVerdict(const ValidationState& state, std::size_t stateDim) {
  NoLearningVerdict v;
  const auto reported = reportedScores(state, stateDim);
  if (reported.noLearning->empty()) return v;
  v.scored = true;
  v.noLearning = summarize(*reported.noLearning);
  v.original = comparePaired(*reported.original, *reported.noLearning);
  v.learnerHarms = v.original.p < 0.05 && v.original.meanDifference < 0.0;
  const auto& winner = state.sets[chooseWinner(state, stateDim)];
  if (winner.isOriginal()) return v;
  const auto& confirmation = state.confirmation;
  const bool confirmed = confirmsWinner(state, stateDim);
  v.winner = confirmed ? comparePaired(confirmation.winner, confirmation.noLearning)
                       : comparePaired(winner.scores, state.noLearning);
  // Turned back by no learning alone: it held against the original variables (or was not
  // confirmed) and was not returned.
  v.winnerNoBetter = (!confirmed || confirmation.held()) &&
                     state.sets[returnedIndex(state, stateDim)].isOriginal();
  return v;
}

std::string formatValidationCsv(const std::vector<ValidatedSet>& sets, std::size_t returned,
                                const std::vector<std::string>& stateNames,
                                const std::vector<double>& noLearning) {
  const std::size_t dim = stateNames.size();
  const auto& original = sets[originalIndex(sets)];
  std::string csv =
      "rank,set,generation,size,features,gp_fitness,gp_trials,mean,se,sd,seeds,"
      "difference_vs_original,p_vs_original,selected,expressions\n";
  int rank = 0;
  for (const std::size_t i : ranking(sets, dim)) {
    const auto& s = sets[i];
    const Summary summary = s.summary();
    const auto paired = comparePaired(s.scores, original.scores);
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", ++rank,
                       s.isOriginal() ? "original" : "hall-of-fame", s.generation, s.size(dim),
                       s.isOriginal() ? dim : s.genome.featureCount(), s.gpFitness, s.gpTrials,
                       summary.mean, summary.standardError(), summary.stddev, summary.n,
                       paired.meanDifference, s.isOriginal() ? 1.0 : paired.p,
                       i == returned ? 1 : 0, quoted(featuresText(s, stateNames)));
  }
  if (!noLearning.empty()) {
    const Summary summary = summarize(noLearning);
    const auto paired = comparePaired(noLearning, original.scores);
    csv += fmt::format(",no-learning,-1,1,1,nan,0,{},{},{},{},{},{},0,{}\n", summary.mean,
                       summary.standardError(), summary.stddev, summary.n, paired.meanDifference,
                       paired.p, quoted(kNoLearningText));
  }
  return csv;
}

std::string formatConfirmationCsv(const ValidationState& state,
                                  const std::vector<std::string>& stateNames) {
  const auto& confirmation = state.confirmation;
  std::string csv =
      "set,mean,se,sd,seeds,difference_vs_original,p_vs_original,returned,expressions\n";
  if (!confirmation.done()) return csv;
  const bool held = confirmation.held() && confirmation.beatsNoLearning();
  const auto row = [&](const char* name, const std::vector<double>& scores, bool original,
                       bool returned, const std::string& text) {
    const Summary summary = summarize(scores);
    const auto paired = comparePaired(scores, confirmation.original);
    csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", name, summary.mean, summary.standardError(),
                       summary.stddev, summary.n, paired.meanDifference, original ? 1.0 : paired.p,
                       returned ? 1 : 0, quoted(text));
  };
  if (!confirmation.key.empty()) {
    for (const auto& set : state.sets) {
      if (set.key == confirmation.key) {
        row("validation-winner", confirmation.winner, false, held, featuresText(set, stateNames));
      }
    }
  }
  const auto& original = state.sets[originalIndex(state.sets)];
  row("original", confirmation.original, true, !held, featuresText(original, stateNames));
  if (!confirmation.noLearning.empty()) {
    row("no-learning", confirmation.noLearning, false, false, kNoLearningText);
  }
  return csv;
}

std::vector<std::size_t> frontIndices(const std::vector<ValidatedSet>& sets, std::size_t dim) {
  const auto ranked = ranking(sets, dim);
  std::vector<std::size_t> position(sets.size());
  for (std::size_t r = 0; r < ranked.size(); ++r) position[ranked[r]] = r;
  std::vector<std::size_t> order(sets.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (sets[a].size(dim) != sets[b].size(dim)) return sets[a].size(dim) < sets[b].size(dim);
    return position[a] < position[b];
  });
  std::vector<std::size_t> front;
  for (const std::size_t i : order) {
    if (front.empty() || sets[i].summary().mean > sets[front.back()].summary().mean) {
      front.push_back(i);
    }
  }
  return front;
}

std::string formatFrontCsv(const std::vector<ValidatedSet>& sets,
                           const std::vector<std::string>& stateNames) {
  const std::size_t dim = stateNames.size();
  const auto& original = sets[originalIndex(sets)];
  std::string csv = "size,features,selection,selection_se,seeds,p_vs_original,set,expressions\n";
  for (const std::size_t i : frontIndices(sets, dim)) {
    const auto& s = sets[i];
    const Summary summary = s.summary();
    csv += fmt::format(
        "{},{},{},{},{},{},{},{}\n", s.size(dim), s.isOriginal() ? dim : s.genome.featureCount(),
        summary.mean, summary.standardError(), summary.n,
        s.isOriginal() ? 1.0 : comparePaired(s.scores, original.scores).p,
        s.isOriginal() ? "original" : "hall-of-fame", quoted(featuresText(s, stateNames)));
  }
  return csv;
}

std::string formatFrontTable(const std::vector<ValidatedSet>& sets,
                             const std::vector<std::string>& stateNames) {
  const std::size_t dim = stateNames.size();
  const auto& original = sets[originalIndex(sets)];
  std::string text = fmt::format("{:>5}  {:>8}  {:<22}  {:>9}  {}\n", "nodes", "features",
                                 "selection (mean +- SE)", "p vs orig", "features");
  for (const std::size_t i : frontIndices(sets, dim)) {
    const auto& s = sets[i];
    const Summary summary = s.summary();
    text += fmt::format("{:>5}  {:>8}  {:<22}  {:>9}  {}\n", s.size(dim),
                        s.isOriginal() ? dim : s.genome.featureCount(),
                        fmt::format("{:.5g} +- {:.3g}", summary.mean, summary.standardError()),
                        s.isOriginal()
                            ? std::string("-")
                            : fmt::format("{:.3g}", comparePaired(s.scores, original.scores).p),
                        featuresText(s, stateNames));
  }
  return text;
}

std::string comparisonVerdict(const PairedComparison& paired, const std::string& other,
                              const std::string& seeds) {
  if (paired.p < 0.05 && paired.meanDifference != 0.0) {
    return fmt::format("{} than {} on {} by {:.4g} (paired t-test p = {:.3g})",
                       paired.meanDifference > 0.0 ? "better" : "worse", other, seeds,
                       std::fabs(paired.meanDifference), paired.p);
  }
  return fmt::format(
      "not significantly different from {} on {} (difference {:.4g}, paired t-test p = {:.3g})",
      other, seeds, paired.meanDifference, paired.p);
}

std::string formatMeanSe(const Summary& summary) {
  return fmt::format("{:.6g} +- {:.3g} ({} trials)", summary.mean, summary.standardError(),
                     summary.n);
}

expr::FeaturesFile returnedFeaturesFile(const ValidationState& state, const expr::Genome& prepared,
                                        const LearningTask& task) {
  const auto& config = task.config();
  const std::size_t dim = task.stateDim();
  const auto& set = state.sets[returnedIndex(state, dim)];
  const auto reported = reportedScores(state, dim);
  expr::FeaturesFile file;
  file.env = config.env;
  file.variables = task.stateNames();
  file.genome = set.isOriginal() ? identityGenome(dim) : prepared;
  file.meta["experiment"] = config.name;
  file.meta["seed"] = std::to_string(config.seed);
  const auto confirmed = reported.returned->size();
  const bool endedEarly = confirmed < static_cast<std::size_t>(config.validation.confirmSeeds);
  if (reported.confirmed) {
    file.meta["confirmed"] = formatMeanSe(summarize(*reported.returned));
    file.meta["confirmed_by"] = fmt::format(
        "{} fresh seeds (validation.confirm_params, measure {}{})", confirmed,
        measureName(config.validation.confirmMeasure),
        endedEarly ? fmt::format("; a clear difference ended it before the {} seeds planned",
                                 config.validation.confirmSeeds)
                   : std::string());
  }
  file.meta["selection"] = formatMeanSe(set.summary());
  file.meta["selection_by"] = fmt::format(
      "{} validation seeds (the mean that chooses among the candidates: biased upwards for the "
      "winner)",
      set.scores.size());
  file.meta["original"] = formatMeanSe(summarize(*reported.original));
  const std::string seeds = reported.confirmed ? "the confirmation seeds" : "the validation seeds";
  const auto reference = noLearningVerdict(state, dim);
  if (reference.scored) file.meta["no_learning"] = formatMeanSe(reference.noLearning);
  if (reference.learnerHarms) {
    file.meta["warning"] = fmt::format(
        "the learner harms: on the original variables it does worse than no learning (a policy "
        "that ignores the state) on {} by {:.4g} (paired t-test p = {:.3g}); its step sizes or "
        "budget need changing",
        seeds, -reference.original.meanDifference, reference.original.p);
  }
  if (set.isOriginal()) {
    const bool confirmationFailed = state.confirmation.done() && !state.confirmation.key.empty();
    if (reference.winnerNoBetter) {
      file.meta["verdict"] = fmt::format(
          "the validation winner is not significantly better than no learning on {} "
          "(difference {:.4g}, paired t-test p = {:.3g}): not a discovery; these are the "
          "original variables",
          seeds, reference.winner.meanDifference, reference.winner.p);
    } else {
      file.meta["verdict"] =
          confirmationFailed
              ? fmt::format(
                    "the validation winner did not beat the original variables on the "
                    "confirmation seeds (difference {:.4g}); these are the original variables",
                    comparePaired(state.confirmation.winner, state.confirmation.original)
                        .meanDifference)
              : "no discovered feature set beat the original variables on the validation seeds; "
                "these are the original variables";
    }
    return file;
  }
  file.meta["gp_fitness"] = fmt::format("{}", set.gpFitness);
  file.meta["gp_trials"] = std::to_string(set.gpTrials);
  file.meta["verdict"] = comparisonVerdict(comparePaired(*reported.returned, *reported.original),
                                           "the original variables", seeds);
  if (reference.scored) {
    file.meta["verdict"] += "; " + comparisonVerdict(reference.winner, "no learning", seeds);
  }
  if (config.normalise) file.meta["normalised"] = "each feature scaled on sampled states";
  return file;
}

}  // namespace gpfd::run
