#include "gpfd/run/discovery.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/thread_evaluator.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace fs = std::filesystem;

struct Discovery::State {
  ExperimentConfig config;
  DiscoveryOptions options;
  std::string configText;
  LearningTask task;
  std::atomic<long> done{0};
  int threads = 0;  // As recorded in run.json: the resolved count, or the option given to MPI.
  std::unique_ptr<gp::Evaluator> evaluator;
  gp::CachingEvaluator cache;
  gp::Evolution evolution;
  std::vector<GenerationRecord> history;

  State(const ExperimentConfig& c, const DiscoveryOptions& o)
      : config(c),
        options(o),
        configText(formatExperimentConfig(c)),
        task(c, LearningTask::Budget::Trial),
        evaluator(makeEvaluator()),
        cache(*evaluator),
        evolution(gpConfig(c), searchSpace(c, static_cast<int>(task.stateDim())), cache) {}

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

  std::string path(const std::string& name) const { return options.outDir + "/" + name; }

  expr::FeaturesFile featuresFile(const gp::Individual& best) const {
    expr::FeaturesFile file;
    file.env = config.env;
    file.variables = task.stateNames();
    file.genome = expr::simplify(best.genome);
    file.meta["fitness"] = fmt::format("{}", best.fitness);
    file.meta["experiment"] = config.name;
    file.meta["seed"] = std::to_string(config.seed);
    return file;
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
                            cache.lastHits(),
                            stats.seconds,
                            stats.bestIndividual.genome};
    history.push_back(record);
    auto best = featuresFile(stats.bestIndividual);
    best.meta["generation"] = std::to_string(stats.generation);
    writeFeaturesFile(path(fmt::format("best/generation-{:04d}.features", stats.generation)), best);
    writeFeaturesFile(path("best.features"), featuresFile(evolution.best()));
    writeFileAtomically(path("generations.csv"), formatGenerationsCsv(history));
    Checkpoint checkpoint{options.version, configText, evolution.state(), cache.entries(), history};
    writeFileAtomically(path("checkpoint.json"), formatCheckpoint(checkpoint));
  }
};

Discovery::Discovery(std::unique_ptr<State> state) : s_(std::move(state)) {}
Discovery::~Discovery() = default;

std::unique_ptr<Discovery> Discovery::start(const ExperimentConfig& config,
                                            const DiscoveryOptions& options) {
  validate(config);
  if (fs::exists(options.outDir + "/checkpoint.json")) {
    throw InputError(
        "the directory already holds a run: resume it with --resume, or choose "
        "another --out",
        options.outDir);
  }
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
    writeFileAtomically(state->path("run.json"), run.dump(1) + "\n");
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
    const std::string text = readFile(configPath);
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
  ExperimentConfig config = parseExperimentConfig(checkpoint.config, checkpointPath + " (config)");
  if (expected && formatExperimentConfig(*expected) != checkpoint.config) {
    throw InputError("the config differs from the one the run was started with (see " +
                         options.outDir + "/config.toml)",
                     options.outDir);
  }
  if (generations) config.gp.generations = *generations;
  auto state = std::make_unique<State>(config, options);
  state->configText = checkpoint.config;  // The run keeps its identity when extended.
  state->evolution.restore(checkpoint.state);
  state->cache.setEntries(std::move(checkpoint.cache));
  state->history = std::move(checkpoint.history);
  return std::unique_ptr<Discovery>(new Discovery(std::move(state)));
}

void Discovery::run(const std::function<void(const GenerationRecord&)>& onGeneration,
                    const std::atomic<bool>& stop) {
  auto& evolution = s_->evolution;
  while (!finished() && !stop.load()) {
    s_->done.store(0);
    const auto stats = evolution.generation() < 0 ? evolution.initialize() : evolution.step();
    s_->persist(stats);
    onGeneration(s_->history.back());
  }
}

const ExperimentConfig& Discovery::config() const { return s_->config; }
const std::vector<GenerationRecord>& Discovery::history() const { return s_->history; }
bool Discovery::finished() const {
  return s_->evolution.generation() + 1 >= s_->config.gp.generations;
}
long Discovery::progress() const { return s_->done.load(std::memory_order_relaxed); }
int Discovery::populationSize() const { return s_->config.gp.population; }

}  // namespace gpfd::run
