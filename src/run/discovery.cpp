#include "gpfd/run/discovery.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/redundancy.hpp"
#include "gpfd/run/sequential_test.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/run/thread_evaluator.hpp"
#include "gpfd/run/validation.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace fs = std::filesystem;
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// run.json's "sizes" of a run sized by a time budget: what the clock chose, the generations as
// fitted to the deadline so far; a replay (run/replay.hpp) runs them again.
nlohmann::ordered_json sizesJson(const ExperimentConfig& config) {
  return {{"from_clock", true},
          {"population", config.gp.population},
          {"generations", config.gp.generations},
          {"candidates", config.validation.candidates},
          {"seeds", config.validation.seeds},
          {"confirm_seeds", config.validation.confirmSeeds}};
}

std::vector<gp::Evaluator*> pointers(const std::vector<std::unique_ptr<gp::Evaluator>>& owned) {
  std::vector<gp::Evaluator*> out;
  for (const auto& e : owned) out.push_back(e.get());
  return out;
}

}  // namespace

std::vector<std::unique_ptr<gp::Evaluator>> makeRungEvaluators(const ExperimentConfig& config,
                                                               const DiscoveryOptions& options) {
  std::vector<std::unique_ptr<gp::Evaluator>> evaluators;
  int r = 0;
  for (const auto& rung : fitnessRungs(config)) {
    ++r;
    if (options.makeEvaluator) {
      evaluators.push_back(options.makeEvaluator({rung, formatExperimentConfig(rung), {}, r}));
      continue;
    }
    auto task = std::make_shared<const LearningTask>(rung, LearningTask::Budget::Trial);
    evaluators.push_back(std::make_unique<ThreadEvaluator>(
        [task](const expr::Genome& g, Rng& rng) { return trialFitness(*task, g, rng); },
        options.threads));
  }
  return evaluators;
}

struct Discovery::State {
  ExperimentConfig config;
  DiscoveryOptions options;
  std::string configText;
  LearningTask task;
  std::atomic<long> done{0};
  std::atomic<int> stage{RunStage::Generations}, stageDone{0}, stageTotal{0};  // Discovery::stage
  std::atomic<int> generationsNow{0};  // config.gp.generations, for displays on other threads.
  int threads = 0;  // As recorded in run.json: the resolved count, or the option given to MPI.
  std::unique_ptr<gp::Evaluator> evaluator;
  // Successive halving's longer rungs (fitnessRungs), shortest first; none without it.
  std::vector<std::unique_ptr<gp::Evaluator>> rungEvaluators;
  std::shared_ptr<TrialRunner> trialRunner;  // Validation's and confirmation's trials.
  gp::CachingEvaluator cache;
  gp::Evolution evolution;
  std::vector<GenerationRecord> history;
  ValidationState validation;
  nlohmann::ordered_json runJson;        // run.json, as written at the start (not on a resume).
  std::unique_ptr<Validator> validator;  // Made when first needed.

  State(const ExperimentConfig& c, const DiscoveryOptions& o)
      : config(c),
        options(o),
        configText(formatExperimentConfig(c)),
        task(c, LearningTask::Budget::Trial),
        evaluator(makeEvaluator()),
        rungEvaluators(makeRungEvaluators(c, o)),
        trialRunner(o.trialRunner ? o.trialRunner : std::make_shared<ThreadTrialRunner>(threads)),
        cache(*evaluator, c.trials, c.maxTrials,
              static_cast<int>(std::lround(c.reevaluationShare * c.gp.population))),
        evolution(gpConfig(c), searchSpace(c, static_cast<int>(task.stateDim())), cache,
                  genomeReducer(c, task), genomeAdmissible(c, task), pointers(rungEvaluators)) {
    validation.parsimonySe = c.validation.parsimonySe;
    generationsNow.store(c.gp.generations);
  }

  std::unique_ptr<gp::Evaluator> makeEvaluator() {
    if (options.makeEvaluator) {
      threads = options.threads;
      return options.makeEvaluator({config, formatExperimentConfig(config),
                                    [this] { done.fetch_add(1, std::memory_order_relaxed); }});
    }
    auto local = std::make_unique<ThreadEvaluator>(
        [this](const expr::Genome& g, Rng& rng) {
          const double f = trialFitness(task, g, rng);
          done.fetch_add(1, std::memory_order_relaxed);
          return f;
        },
        options.threads);
    threads = local->threads();
    return local;
  }

  void enterStage(RunStage::Kind kind, int total) {
    stageDone.store(0);
    stageTotal.store(total);
    stage.store(kind);
  }

  std::string path(const std::string& name) const { return options.outDir + "/" + name; }

  // The GP's best genome as the learner saw it (normalised, placeholders out), marked as not
  // validated: what best.features holds until validation replaces it.
  expr::FeaturesFile unvalidatedFile(const gp::Individual& best, int generation) const {
    expr::FeaturesFile file;
    file.env = config.env;
    file.variables = task.stateNames();
    file.genome = expr::simplify(task.prepared(best.genome));
    file.meta["status"] = fmt::format(
        "not validated: the GP's best genome {}, scored by its own short trials (a biased, "
        "best-of-run estimate); finish or resume the run to validate it against the original "
        "variables",
        generation < 0 ? std::string("so far") : fmt::format("of generation {}", generation));
    file.meta["gp_fitness"] = fmt::format("{}", best.fitness);
    if (generation >= 0) file.meta["generation"] = std::to_string(generation);
    file.meta["experiment"] = config.name;
    file.meta["seed"] = std::to_string(config.seed);
    if (config.normalise) file.meta["normalised"] = "each feature scaled on sampled states";
    return file;
  }

  void writeCheckpoint() const {
    const Checkpoint checkpoint{options.version, configText, evolution.state(),
                                cache.entries(), history,    validation};
    writeFileAtomically(path("checkpoint.json"), formatCheckpoint(checkpoint));
  }

  // Writes the generation's files, then the checkpoint (all atomically).
  void persist(const gp::GenerationStats& stats) {
    GenerationRecord record{stats.generation,
                            stats.best,
                            stats.mean,
                            stats.median,
                            stats.meanSize,
                            stats.meanFeatures,
                            cache.lastEvaluated(),
                            cache.lastReevaluated(),
                            cache.lastHits(),
                            stats.seconds,
                            stats.bestIndividual.genome,
                            stats.promotions};
    history.push_back(record);
    writeFeaturesFile(path(fmt::format("best/generation-{:04d}.features", stats.generation)),
                      unvalidatedFile(stats.bestIndividual, stats.generation));
    writeFeaturesFile(path("best.features"), unvalidatedFile(evolution.best(), -1));
    writeFileAtomically(path("generations.csv"), formatGenerationsCsv(history));
    writeCheckpoint();
  }

  bool validating() const { return config.validation.candidates > 0; }
  bool generationsDone() const { return evolution.generation() + 1 >= config.gp.generations; }

  // A time budget's end (DiscoveryOptions::deadline): the generations become those made and
  // those that still fit before the deadline, validation and confirmation left out, each as long
  // as the longest of the last three, a last one counted where half of it fits (rounding, not
  // truncating: the run ends within half a generation of the deadline on either side, where
  // truncating ended it up to a whole one early), validation and confirmation kept free as
  // DiscoveryOptions::finishTrainings says; written into config.toml and the checkpoint when they
  // change.
  void fitDeadline() {
    if (!options.deadline) return;
    double next = 0.0, perTraining = 0.0;
    for (std::size_t i = history.size() > 3 ? history.size() - 3 : 0; i < history.size(); ++i) {
      next = std::max(next, history[i].seconds);
      const int trainings = history[i].evaluations * config.trials;
      if (trainings > 0) perTraining = std::max(perTraining, history[i].seconds / trainings);
    }
    const double finish = std::max(options.finishSeconds, options.finishTrainings * perTraining);
    const double left =
        std::chrono::duration<double>(*options.deadline - std::chrono::steady_clock::now())
            .count() -
        finish;
    const double fit = next > 0.0 ? std::round(std::max(0.0, left) / next) : 0.0;
    const int generations = evolution.generation() + 1 + static_cast<int>(std::min(fit, 1e6));
    if (generations == config.gp.generations) return;
    config.gp.generations = generations;
    generationsNow.store(generations);
    configText = formatExperimentConfig(config);
    writeFileAtomically(path("config.toml"), configText);
    writeRunJson();
    writeCheckpoint();
  }

  // run.json, its "sizes" (a time budget's) as the config holds them now.
  void writeRunJson() {
    if (runJson.contains("sizes")) runJson["sizes"] = sizesJson(config);
    writeFileAtomically(path("run.json"), runJson.dump(1) + "\n");
  }

  // Scores the hall of fame members (and the original variables) not validated yet.
  void validateHallOfFame() {
    const auto start = std::chrono::steady_clock::now();
    enterStage(RunStage::Validation, 0);
    if (!validator) validator = std::make_unique<Validator>(config, *trialRunner);
    std::vector<ValidatedSet> fresh;
    const auto known = [&](const std::string& key) {
      for (const auto& s : validation.sets) {
        if (s.key == key) return true;
      }
      return false;
    };
    if (!known("")) fresh.push_back({});  // The original variables.
    for (auto& entry :
         hallOfFame(cache.entries(), config.validation.candidates, config.gp.sizePenalty)) {
      if (known(entry.key)) continue;
      fresh.push_back({entry.key,
                       std::move(entry.genome),
                       evolution.generation(),
                       entry.fitness,
                       entry.trials,
                       {}});
    }
    std::vector<const expr::Genome*> genomes;
    for (const auto& set : fresh) genomes.push_back(set.isOriginal() ? nullptr : &set.genome);
    auto sets = validator->features(genomes);
    // The no-learning reference, scored once, last: on the same seeds as every set, which
    // it leaves as they are (a curve depends on its features, budget and seed only).
    const bool reference = validation.noLearning.empty();
    if (reference) sets.push_back(TrialFeatures::noLearning());
    stageTotal.store(static_cast<int>(sets.size()) * validator->seeds());
    auto scores = validator->score(sets);
    stageDone.store(stageTotal.load());
    if (reference) validation.noLearning = std::move(scores.back());
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      fresh[i].scores = std::move(scores[i]);
      validation.sets.push_back(std::move(fresh[i]));
    }
    validation.seconds += secondsSince(start);
  }

  std::size_t dim() const { return task.stateDim(); }

  // validation.csv, marking the set at index `returned`.
  void writeValidationCsv(std::size_t returned) const {
    writeFileAtomically(
        path("validation.csv"),
        formatValidationCsv(validation.sets, returned, task.stateNames(), validation.noLearning));
  }

  // Trains the validation winner (unless it is the original variables), the original variables
  // and the no-learning reference on the confirmation seeds, a look at a time
  // (run/sequential_test.hpp): a clear decision ends the trials before the last seed.
  void confirmWinner() {
    validation.confirmation = {};
    if (!config.validation.confirms()) return;
    const auto start = std::chrono::steady_clock::now();
    const auto& winner = validation.sets[chooseWinner(validation, dim())];
    std::vector<const expr::Genome*> genomes{nullptr};  // The original variables first.
    if (!winner.isOriginal()) genomes.push_back(&winner.genome);
    auto& confirmation = validation.confirmation;
    confirmation.key = winner.key;  // Empty for the original variables.
    const Validator confirm = Validator::confirmation(config, *trialRunner);
    auto sets = confirm.features(genomes);
    sets.push_back(TrialFeatures::noLearning());  // Last, on the same seeds.
    enterStage(RunStage::Confirmation, static_cast<int>(sets.size()) * confirm.seeds());
    // The original variables alone are confirmed for their score only: nothing to decide.
    const int looks = winner.isOriginal() ? 1 : config.validation.confirmLooks;
    confirmation.noLearningLevel = nominalLevel(looks, looks);
    for (int look = 1, trained = 0; trained < confirm.seeds(); ++look) {
      const int until = seedsAtLook(confirm.seeds(), look, looks);
      auto scores = confirm.score(sets, trained, until);
      trained = until;
      stageDone.store(static_cast<int>(sets.size()) * trained);
      const auto append = [](std::vector<double>& to, const std::vector<double>& from) {
        to.insert(to.end(), from.begin(), from.end());
      };
      append(confirmation.original, scores[0]);
      append(confirmation.noLearning, scores.back());
      if (winner.isOriginal()) continue;
      append(confirmation.winner, scores[1]);
      const auto vsNoLearning = comparePaired(confirmation.winner, confirmation.noLearning);
      if (confirmationEndsAtLook(comparePaired(confirmation.winner, confirmation.original),
                                 &vsNoLearning, look, looks)) {
        break;
      }
    }
    validation.seconds += secondsSince(start);
    writeFileAtomically(path("confirmation.csv"),
                        formatConfirmationCsv(validation, task.stateNames()));
  }

  // The final choice: best.features becomes what validation and confirmation return; front.csv
  // the size front.
  void chooseValidated() {
    validateHallOfFame();
    confirmWinner();
    const std::size_t returned = returnedIndex(validation, dim());
    const auto& set = validation.sets[returned];
    writeValidationCsv(returned);
    writeFeaturesFile(
        path("best.features"),
        returnedFeaturesFile(validation, expr::simplify(task.prepared(set.genome)), task));
    writeFileAtomically(path("front.csv"), formatFrontCsv(validation.sets, task.stateNames()));
    validation.finalGeneration = evolution.generation();
    writeCheckpoint();
  }
};

void refuseExistingRuns(const std::string& dir) {
  if (fs::exists(dir + "/checkpoint.json") || fs::exists(dir + "/runs.json")) {
    throw InputError(
        "the directory already holds a run or a set of runs: resume it with --resume, or choose "
        "another --out",
        dir);
  }
}

Discovery::Discovery(std::unique_ptr<State> state) : s_(std::move(state)) {}
Discovery::~Discovery() = default;

std::unique_ptr<Discovery> Discovery::start(const ExperimentConfig& config,
                                            const DiscoveryOptions& options) {
  validate(config);
  refuseExistingRuns(options.outDir);
  auto state = std::make_unique<State>(config, options);  // Compiles nothing yet; checks env.
  const bool existed = fs::exists(options.outDir);
  try {
    createDirectories(options.outDir, "results directory");
    createDirectories(options.outDir + "/best", "results directory");
    writeFileAtomically(state->path("config.toml"), state->configText);
    nlohmann::ordered_json run{{"seed", config.seed},
                               {"version", options.version},
                               {"revision", options.revision},
                               {"threads", state->threads}};
    if (options.processes > 1) run["mpi_processes"] = options.processes;
    if (!options.learnerChoiceJson.empty()) {
      run["learner_choice"] = nlohmann::ordered_json::parse(options.learnerChoiceJson);
    }
    if (!options.timeBudgetJson.empty()) {
      run["time_budget"] = nlohmann::ordered_json::parse(options.timeBudgetJson);
    }
    if (!options.timeBudgetJson.empty()) run["sizes"] = sizesJson(config);
    if (!options.envJson.empty()) run["env"] = nlohmann::ordered_json::parse(options.envJson);
    if (!options.replayOf.empty()) run["replay_of"] = options.replayOf;
    state->runJson = std::move(run);
    state->writeRunJson();
  } catch (...) {
    // Leave nothing half-made behind.
    std::error_code ignored;
    if (!existed) fs::remove_all(options.outDir, ignored);
    throw;
  }
  return std::unique_ptr<Discovery>(new Discovery(std::move(state)));
}

std::unique_ptr<Discovery> Discovery::resume(const DiscoveryOptions& options,
                                             const std::optional<ExperimentConfig>& expected,
                                             std::optional<int> generations) {
  const std::string checkpointPath = options.outDir + "/checkpoint.json";
  if (!fs::exists(checkpointPath)) {
    // Killed before its first checkpoint: the run starts over with its stored config.
    const std::string configPath = options.outDir + "/config.toml";
    if (!fs::exists(configPath)) {
      throw InputError("no run to resume (neither checkpoint.json nor config.toml)",
                       options.outDir);
    }
    // In today's form: keys added since the run was written read as their defaults.
    const std::string text =
        formatExperimentConfig(parseStoredExperimentConfig(readFile(configPath), configPath));
    if (expected && formatExperimentConfig(*expected) != text) {
      throw InputError(
          "the config differs from the one the run was started with (see " + configPath + ")",
          options.outDir);
    }
    ExperimentConfig config = parseExperimentConfig(text, configPath);
    if (generations) config.gp.generations = *generations;
    auto state = std::make_unique<State>(config, options);
    state->configText = text;
    return std::unique_ptr<Discovery>(new Discovery(std::move(state)));
  }
  Checkpoint checkpoint = parseCheckpoint(readFile(checkpointPath), checkpointPath);
  if (checkpoint.version != options.version) {
    throw InputError(
        "the checkpoint was written by gpfd " + checkpoint.version + ", this is " + options.version,
        checkpointPath);
  }
  ExperimentConfig config =
      parseStoredExperimentConfig(checkpoint.config, checkpointPath + " (config)");
  // The stored config in today's form: keys added since the run was written read as their
  // defaults, so that a run of an earlier gpfd resumes (and its MPI workers read the text back).
  const std::string stored = formatExperimentConfig(config);
  if (expected && formatExperimentConfig(*expected) != stored) {
    throw InputError("the config differs from the one the run was started with (see " +
                         options.outDir + "/config.toml)",
                     options.outDir);
  }
  if (generations) config.gp.generations = *generations;
  auto state = std::make_unique<State>(config, options);
  state->configText = stored;  // The run keeps its identity when extended.
  state->evolution.restore(checkpoint.state);
  state->cache.setEntries(std::move(checkpoint.cache));
  state->history = std::move(checkpoint.history);
  state->validation = std::move(checkpoint.validation);
  state->validation.parsimonySe = config.validation.parsimonySe;
  return std::unique_ptr<Discovery>(new Discovery(std::move(state)));
}

void Discovery::run(const std::function<void(const GenerationRecord&)>& onGeneration,
                    const std::atomic<bool>& stop) {
  auto& evolution = s_->evolution;
  const int every = s_->config.validation.every;
  while (!s_->generationsDone() && !stop.load()) {
    s_->done.store(0);
    s_->enterStage(RunStage::Generations, s_->config.gp.population);
    const auto stats = evolution.generation() < 0 ? evolution.initialize() : evolution.step();
    s_->persist(stats);
    s_->fitDeadline();
    onGeneration(s_->history.back());
    if (s_->validating() && every > 0 && (stats.generation + 1) % every == 0 &&
        !s_->generationsDone()) {
      s_->validateHallOfFame();
      s_->writeValidationCsv(chooseWinner(s_->validation, s_->dim()));
      s_->writeCheckpoint();
    }
  }
  if (!finished() && s_->generationsDone() && !stop.load()) s_->chooseValidated();
}

const ExperimentConfig& Discovery::config() const { return s_->config; }
std::size_t Discovery::stateDim() const { return s_->task.stateDim(); }
const std::vector<GenerationRecord>& Discovery::history() const { return s_->history; }
bool Discovery::finished() const {
  return s_->generationsDone() &&
         (!s_->validating() || s_->validation.finalGeneration == s_->evolution.generation());
}
const ValidationState& Discovery::validation() const { return s_->validation; }
expr::Genome Discovery::asLearnerSees(const expr::Genome& genome) const {
  return expr::simplify(s_->task.prepared(genome));
}
long Discovery::progress() const { return s_->done.load(std::memory_order_relaxed); }
int Discovery::populationSize() const { return s_->config.gp.population; }
RunStage Discovery::stage() const {
  const auto kind = static_cast<RunStage::Kind>(s_->stage.load());
  // In the generations, `done` is the evaluations so far (progress()).
  const long done = kind == RunStage::Generations ? progress() : s_->stageDone.load();
  return {kind, static_cast<int>(done), s_->stageTotal.load(), s_->generationsNow.load()};
}

const char* stageName(RunStage::Kind kind) {
  switch (kind) {
    case RunStage::Generations:
      return "generations";
    case RunStage::Validation:
      return "validation";
    case RunStage::Confirmation:
      return "confirmation";
  }
  return "?";
}

}  // namespace gpfd::run
