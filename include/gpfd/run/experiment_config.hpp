// run: the configuration of a feature-discovery experiment (what `gpfd evolve` and
// `gpfd assess` read from TOML), as a plain struct with named, defaulted fields.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/gp/evolution.hpp"
#include "gpfd/gp/search_space.hpp"

namespace gpfd::run {

// How one short learning trial is scored from its learning curve (the mean returns of its rows).
enum class TrialMeasure {
  Mean,          // Mean over all rows: rewards learning fast (the area under the curve).
  Final,         // The last row.
  LastFraction,  // Mean over the last `lastFraction` of the rows.
};

struct ExperimentConfig {
  std::string name = "cartpole";
  std::uint64_t seed = 1;
  // Plug-ins to load before anything else is checked (run/plugin.hpp); a relative path is taken
  // from the config file's directory, and stored absolute.
  std::vector<std::string> plugins;

  // Seconds the whole `gpfd evolve` may take (`time_budget`: seconds, or text such as "10m");
  // 0: none. When set, a fresh run measures what an evaluation costs, sizes the population and the
  // validation, and ends its generations when the next one and validation would pass the budget
  // (run/time_budget.hpp); the resolved config stores the sizes chosen (the generations made) and
  // no budget, so that a resume, or the resolved config run again, gives the same run.
  double timeBudget = 0.0;

  // Seconds one task of an environment stepped in Python (a lockstep group's fitness
  // evaluations, or learning runs) may take on a worker process (`task_timeout`: seconds, or text
  // such as "10m"); 0: none. Past it the worker ends and its task runs again as a lost worker's
  // (gpfd._deadline). Read by the Python workers only; it never changes a result.
  double taskTimeout = 0.0;

  std::string env = "cartpole";
  std::map<std::string, std::string> envParams;

  std::string learner = "pg";  // A registered learner (gpfd learners).
  // The short-trial budget and settings of the learner (its declared parameters).
  std::map<std::string, std::string> learnerParams;
  // Candidate values of learner parameters (`learner.choose`, e.g. { rprop = ["large", "small"] }),
  // of which the best for the original variables on this task is chosen before a run, on
  // choiceSeeds fresh seeds (run/learner_choice.hpp), and stored in learnerParams; the resolved
  // config keeps no choice. Empty: learnerParams as given.
  std::map<std::string, std::vector<std::string>> learnerChoices;
  // Or alternatives, each a set of learner parameters over learnerParams (`learner.choose` as an
  // array of tables, e.g. [{ step = "natural", updates = 30 }, { rprop = "large" }]), chosen the
  // same way. At most one of the two is given.
  std::vector<std::map<std::string, std::string>> learnerAlternatives;
  // Alternatives tried only where every candidate of learner.choose learns nothing (the original
  // variables and the random sets score as no learning does: MountainCar-v0 under policy
  // gradient), chosen among themselves the same way (`learner.choose_fallback`, user-env's ARS).
  // Needs learner.choose; resolved configs keep none.
  std::vector<std::map<std::string, std::string>> learnerFallbacks;
  int choiceSeeds = 10;
  // 0: the candidate with the best mean is chosen. Above 0: an earlier-listed candidate is kept
  // unless the best trains the original variables significantly better on the same seeds (the
  // paired t-test, one-sided p below this), so that cheaper settings listed first are kept where
  // the dearer ones gain nothing measurable (`learner.choose_significance`).
  double choiceSignificance = 0.0;
  // Above 0: each candidate also trains this many random feature sets, drawn as GP's generation 0
  // draws them (the same for every candidate), on a few seeds each, and scores the better of the
  // original variables' mean and the mean of its best quarter of those sets: the learner that
  // makes the most of the features GP starts from (`learner.choose_random_sets`).
  int choiceRandomSets = 0;

  int trials = 5;  // K short learning trials per fitness evaluation (the paper: 4-10).
  // Cap on the trials a genome accumulates: one met again gets K fresh trials until it has this
  // many, its fitness the mean over all of them. 0: no re-evaluation (the first K decide).
  int maxTrials = 0;
  // At most this share of the population is re-evaluated per generation, best fitness first.
  double reevaluationShare = 0.05;
  TrialMeasure measure = TrialMeasure::Mean;
  double lastFraction = 0.25;
  bool withOriginal = false;  // The learner sees discovered + original variables.
  // Each feature scaled to zero mean and unit standard deviation on sampled states, as part of
  // the feature (so best.features carries the scaling).
  bool normalise = false;
  // Visited states sampled (random actions) for redundancy and normalisation.
  int stateSample = 512;
  // Successive halving (fitness.promote, as gp.promote: gp/evolution.hpp): the rungs after the
  // short trials are this middle one, the learner's settings overridden by rungParams, when it is
  // not empty, and then the confirmation's training (validation.confirm_params, scored by
  // validation.confirm_measure); each rung evaluation is `trials` trainings (fitnessRungs).
  std::map<std::string, std::string> rungParams;

  std::string primitives = "control";
  std::vector<double> constants{1.0, 2.0};
  bool ephemeral = true;
  expr::GenomeLimits limits;
  // Features linearly dependent on the earlier ones, the bias (and the original variables with
  // withOriginal) on sampled states are dropped from every new genome before it is evaluated.
  bool dropRedundant = true;
  // With drop_redundant: a feature is also dropped when the bias and the features kept before it
  // explain at least this share of its variance on the sample (run/redundancy.hpp); 1: exact
  // linear dependence only.
  double redundantR2 = 1.0;
  // With gp.distinct_offspring: a genome none of whose features varies on sampled states (the
  // learner with it learns nothing: validation's no-learning reference) never joins the
  // population; another is bred in its place. Moot beside the original variables.
  bool rejectConstant = false;
  int initMinDepth = 2;
  int initMaxDepth = 4;
  int initMaxFeatures = 4;
  int mutationDepth = 3;

  gp::GpConfig gp;  // gp.seed is ignored: `seed` above is the run's seed.

  // The validation stage that picks what a run returns: the best distinct genomes (a hall of
  // fame of `candidates`) and the original variables are each scored on the same `seeds` fresh
  // trials, with the learner settings of the short trial overridden by `params`.
  struct Validation {
    int candidates = 10;  // 0: no validation; the GP's best is returned.
    int seeds = 30;
    int every = 0;  // Also validate the hall of fame every this many generations; 0: at the end.
    std::map<std::string, std::string> params;
    // How a validation trial is scored; none: as the GP scores a trial (fitness.measure).
    std::optional<TrialMeasure> measure;
    // Confirmation (docs/discovery.md): the validation winner and the original variables are
    // trained once more on confirmSeeds fresh seeds with learner.params overridden by
    // confirmParams, scored by confirmMeasure; the winner is returned only when it beats the
    // original variables there, and that score is what best.features reports. 0: no confirmation
    // (the validation score is reported, biased by the choice among the candidates).
    int confirmSeeds = 30;
    // Looks at the confirmation (a group-sequential test): after each k/confirmLooks of the
    // seeds, a paired difference past the O'Brien-Fleming boundary ends it early, decided by its
    // sign (run/sequential_test.hpp). 1: every seed is trained.
    int confirmLooks = 3;
    std::map<std::string, std::string> confirmParams;
    TrialMeasure confirmMeasure = TrialMeasure::Final;
    // The one-standard-error rule (chooseWinner, run/validation.hpp): a discovered winner gives
    // way to the smallest validated set made of some of its features whose validation mean is
    // within parsimonySe standard errors of the winner's. 0: the best mean wins.
    double parsimonySe = 0.0;

    // Whether a run validates and then confirms its winner.
    bool confirms() const { return candidates > 0 && confirmSeeds > 0; }
  } validation;

  int assessRuns = 20;  // Independent long trainings per feature set in `gpfd assess`.
  // The long budget: learner settings that override learnerParams for assessment.
  std::map<std::string, std::string> assessParams;
};

// The measure's name as configs spell it: "mean", "final" or "last_fraction".
std::string measureName(TrialMeasure measure);

// Reads a config from TOML text; `source` names it in errors. Unknown keys (with a suggestion),
// type errors and out-of-range values throw InputError at file:line:column. `overrides` are
// `key=value` assignments (`gp.population=50`) applied before reading.
ExperimentConfig parseExperimentConfig(const std::string& text, const std::string& source,
                                       const std::vector<std::string>& overrides = {});
ExperimentConfig loadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides = {});
// The learner's choice where values are given (an override's learner.params.KEY, an assessment's
// --param): a given key's choice is dropped, and so are the alternatives that set it to another
// value; a single alternative left (of several) goes into learnerParams, except its given keys.
void keepChoicesWith(ExperimentConfig& config, const std::map<std::string, std::string>& given);
// The fully resolved config as TOML (every field, defaults included); parsing it gives the same
// config back.
std::string formatExperimentConfig(const ExperimentConfig& config);

// Checks what the TOML types cannot: the environment and its parameters exist, the learner
// takes its parameters, the primitive set is known, the limits are consistent. InputError
// otherwise.
void validate(const ExperimentConfig& config);

// Whether `name` may name a results directory: letters, digits, '.', '_' and '-', not starting
// with '.' (so never "", "..", a path or a hidden directory).
bool isRunName(const std::string& name);

gp::SearchSpace searchSpace(const ExperimentConfig& config, int variableCount);
gp::GpConfig gpConfig(const ExperimentConfig& config);

}  // namespace gpfd::run
