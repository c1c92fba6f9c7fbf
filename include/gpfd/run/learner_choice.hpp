// run: the learner's settings chosen on the task before a run (`learner.choose`: values per
// parameter, { rprop = ["large", "small"] }, or alternatives, user-env's [{ step = "natural", ...
// }, { rprop = "large" }, { rprop = "small" }]). The original variables are trained with each
// candidate (a combination of the values, or an alternative) on the same fresh seeds, with the
// confirmation's budget and measure (the validation's without a confirmation); the combination with
// the best mean score (or, with learner.choose_random_sets, the best quarter of random feature
// sets as GP's generation 0 draws them where that is higher) becomes the learner's settings for the
// whole run, GP's trials included. So the original variables, the reference every verdict is
// against, are judged with the best of the candidate settings rather than one that harms them on
// this task, and with random sets a learner that makes nothing of any feature (one that stops
// exploring) is not chosen for what it does with the raw variables alone (docs/discovery.md, "The
// learner's settings chosen on the task"). The choice is a pure function of the config and its
// seed; where no candidate makes the original variables or the random sets score other than the
// no-learning reference (trained beside them on the same seeds), the run stops before GP with
// what to change (nothingLearnsText), unless learner.choose_fallback lists candidates to try then
// (user-env's ARS): the choice is made among those, and stops only where none of them learns
// either; the resolved config stores the values chosen and no choice, so a resume, or that config
// run again, gives the same run.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/trial_runner.hpp"

namespace gpfd::run {

// The most combinations `learner.choose` may list (each costs choose_seeds trainings).
inline constexpr std::size_t kMaxLearnerChoices = 16;

// The key of an alternative that names another learner: [{ rprop = "large" }, { learner = "ars",
// n_delta = 8 }]. Such a candidate is that learner with its own parameters (over its defaults,
// never the config's learner.params) at equal episodes: every training it makes (GP's trials,
// validation, confirmation, assessment, fitness.rung_params) is given the most iterations of its
// budget parameter that play no more episodes than the config's learner plays in that training
// (LearnerInfo::rowEpisodes), so that the choice compares the learners on the same seeds, the
// same measure and the same experience; the candidate gives no budget of its own.
inline constexpr const char* kCandidateLearnerKey = "learner";

// The learner a candidate trains: the one it names, or the config's own.
std::string candidateLearner(const ExperimentConfig& config,
                             const std::map<std::string, std::string>& candidate);

// The episodes one training of the config's learner plays with `params` (its learner.params with
// a budget's overrides): (budget parameter + 1) x LearnerInfo::rowEpisodes; 0 where the learner
// does not say.
std::int64_t trainingEpisodes(const std::string& learner,
                              const std::map<std::string, std::string>& params);

// `config` trained with `candidate`: its values over learner.params, or, where it names another
// learner (kCandidateLearnerKey), that learner with the candidate's parameters and each
// training's budget matched to the config's learner's episodes; no choice left. InputError where
// a learner cannot say its episodes.
ExperimentConfig withCandidate(ExperimentConfig config,
                               const std::map<std::string, std::string>& candidate);

// Whether the config has a learner.choose (values per parameter or alternatives).
bool choosesLearner(const ExperimentConfig& config);

// The alternatives of learner.choose as listed, or every combination of its values as learner
// settings, in order: keys alphabetically, the last key's values varying fastest, each key's
// values as listed.
std::vector<std::map<std::string, std::string>> learnerCandidates(const ExperimentConfig& config);

struct LearnerChoice {
  // learnerCandidates(config), then the fallbacks where tried (from fallbacksFrom on).
  std::vector<std::map<std::string, std::string>> candidates;
  std::vector<double> means;  // The original variables' mean score with each (-inf: diverged).
  std::vector<std::vector<double>> scores;  // Each one's score per seed.
  // With learner.choose_random_sets: each one's mean of its best quarter of the random sets.
  std::vector<double> randomSetsBest;
  std::vector<double> merits;  // What the choice compares: the mean, or the random sets' if higher.
  std::vector<double> noLearningMeans;  // The no-learning reference's, with each, on the seeds.
  // With every candidate, the original variables' mean and the random sets' equal the
  // no-learning mean (to 1e-6 of their scale): the learner learns nothing here
  // (nothingLearnsText).
  bool nothingLearns = false;
  // Above 0 where no listed candidate learns and learner.choose_fallback's were tried: the index
  // of the first, and the choice is made among them.
  std::size_t fallbacksFrom = 0;
  // No listed candidate learns, and the fallbacks were not tried: they would pass the allowance.
  bool fallbacksCut = false;
  int randomSets = 0;
  // The best mean, the first listed of equal ones; with learner.choose_significance, the first
  // listed that the best does not beat significantly.
  std::size_t chosen = 0;
  int seeds = 0;
  bool confirmation = true;  // Trained as the confirmation trains (else as the validation).
  double seconds = 0.0;      // Wall time of the trainings.
  // Where the allowance cut it: the random sets left out, every candidate but the first, or all
  // but the first candidate's first training (no no-learning reference then: its mean -inf).
  enum class Cut { None, RandomSets, Candidates, All } cut = Cut::None;
  // Per candidate tried: its learner, and the episodes of one of its trainings (trainingEpisodes
  // under the choice's budget; 0 where its learner does not say).
  std::vector<std::string> learners;
  std::vector<std::int64_t> episodes;
  // Whether a candidate names another learner than the config's: the text and JSON then name
  // each one's learner and episodes.
  bool otherLearners = false;
  double firstSeconds = 0.0;  // The first training (the original variables, first seed).
  // Under an allowance, the first training's seconds were predicted from one of a single unit of
  // the learner's budget, and it was not played: alone it would pass the allowance (cut All).
  bool firstPredicted = false;
  double predictedSeconds = 0.0;  // The whole choice's, predicted from it.
};

// Trains the original variables with each candidate on config.choiceSeeds seeds of a stream of
// their own (never the run's), on `runner`, and picks the best. Needs learner.choose.
// `allowance`: wall seconds the choice may take (a time budget's share). Its first training is
// timed, and where the rest, spread over `workers`, would pass the allowance the random sets are
// left out, or where that is not enough the first candidate is kept without trying the others, or
// where even its trainings do not fit, without more trainings (said, and recorded:
// LearnerChoice::cut). The choice then depends on the clock; config.toml records what it chose.
// Under an allowance the first training is predicted from one of a single unit first, and
// `predicted` is called with its wall seconds before any whole training is played: a caller that
// can tell the call will not fit refuses it there (by throwing).
LearnerChoice chooseLearnerSettings(
    const ExperimentConfig& config, TrialRunner& runner,
    double allowance = std::numeric_limits<double>::infinity(), int workers = 1,
    const std::function<void(double firstTrainingSeconds)>& predicted = {});

// `config` with the chosen candidate (withCandidate) and no choice left.
ExperimentConfig withLearnerChoice(ExperimentConfig config, const LearnerChoice& choice);

// What was tried and chosen: one line of text (with the seconds it took), and JSON (run.json's
// "learner_choice": no timing, so that a run's files are the same bytes on any machine; only
// where a budget cut it, the predicted first training's seconds, as run.json's "time_budget"
// holds the measured costs).
std::string learnerChoiceText(const LearnerChoice& choice);
std::string learnerChoiceJson(const LearnerChoice& choice);
// Why a choice where nothing learns stops the run, and what to change.
std::string nothingLearnsText(const LearnerChoice& choice);

}  // namespace gpfd::run
