// `gpfd evolve`: feature discovery with GP, fitness from short learning trials.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "command.hpp"
#include "config_loading.hpp"
#include "gpfd/expr/genome.hpp"
#include "gpfd/run/discovery.hpp"
#include "gpfd/run/run_set.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/directory_lock.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"
#include "interrupt.hpp"

#ifdef GPFD_HAVE_MPI
#include "gpfd/mpi/mpi_evaluator.hpp"
#include "gpfd/mpi/worker.hpp"
#endif

namespace gpfd::app {
namespace {

struct EvolveOptions {
  std::string config;
  std::string env;
  std::optional<std::uint64_t> seed;
  int threads = 0;
  std::optional<int> population;
  std::optional<int> generations;
  std::string out;
  std::string resume;
  std::vector<std::string> sets;
  std::optional<int> runs;
  bool quiet = false;
};

std::string duration(double seconds) {
  if (seconds < 90) return fmt::format("{:.0f}s", seconds);
  if (seconds < 5400)
    return fmt::format("{:.0f}m{:02.0f}s", std::floor(seconds / 60), std::fmod(seconds, 60));
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(seconds / 3600), std::fmod(seconds / 60, 60));
}

// Overrides from the flags, applied like --set so that they are validated in one place.
std::vector<std::string> overrides(const EvolveOptions& o) {
  std::vector<std::string> all;
  if (!o.env.empty()) all.push_back("env.name=\"" + o.env + "\"");
  if (o.seed) all.push_back("seed=" + std::to_string(*o.seed));
  if (o.population) all.push_back("gp.population=" + std::to_string(*o.population));
  if (o.generations) all.push_back("gp.generations=" + std::to_string(*o.generations));
  all.insert(all.end(), o.sets.begin(), o.sets.end());
  return all;
}

std::string meanSe(const run::Summary& s) {
  return fmt::format("{:.6g} +- {:.3g}", s.mean, s.standardError());
}

// What a finished run returned, in words.
void printOutcome(const run::RunOutcome& o, const std::string& dir, const std::string& label) {
  if (!o.validated) {
    fmt::print(
        "{}best fitness {} (GP's own estimate, not validated); features in {}/best.features\n",
        label, o.gpBest, dir);
  } else if (o.originalWon) {
    fmt::print(
        "{}no discovered feature set beat the original variables on {} (original {}); "
        "{}/best.features holds the original variables\n",
        label, o.confirmed ? "validation and confirmation" : "validation", meanSe(o.original), dir);
  } else {
    fmt::print(
        "{}{}: {} vs original {} on {} paired fresh trials (difference {:.4g}, p = {:.3g}); "
        "features in {}/best.features\n",
        label, o.confirmed ? "confirmed" : "validated", meanSe(o.winner), meanSe(o.original),
        o.winner.n, o.vsOriginal.meanDifference, o.vsOriginal.p, dir);
  }
}

// A set of runs in a few lines: what each returned, and how often discovery beat the original.
void printSetSummary(const std::vector<run::RunOutcome>& outcomes, const std::string& dir) {
  int discovered = 0, significant = 0;
  bool confirmed = false;
  std::vector<double> differences;
  for (const auto& o : outcomes) {
    if (!o.validated) continue;
    confirmed = confirmed || o.confirmed;
    differences.push_back(o.vsOriginal.meanDifference);
    if (o.originalWon) continue;
    ++discovered;
    if (o.vsOriginal.p < 0.05) ++significant;
  }
  if (differences.empty()) {
    fmt::print("{} runs done (not validated); per-run results in {}/runs.csv\n", outcomes.size(),
               dir);
    return;
  }
  const auto test = run::wilcoxonSignedRank(differences);
  fmt::print(
      "{} runs: a discovered set beat the original variables on {} in {} ({} with "
      "p < 0.05); median difference {:.4g} (Wilcoxon signed-rank over runs p = {:.3g}); per-run "
      "results in {}/runs.csv\n",
      outcomes.size(), confirmed ? "confirmation" : "validation", discovered, significant,
      test.median, test.p, dir);
}

// Runs (or continues) one discovery run with progress output; 0 when finished, 130 when
// interrupted. `label` prefixes its lines in a set of runs; `resumeDir` is what to resume.
int runDiscovery(run::Discovery& discovery, const std::string& outDir, const std::string& label,
                 const std::string& resumeDir, bool quiet) {
  const bool terminal = ::isatty(STDOUT_FILENO) != 0;
  const auto& config = discovery.config();
  if (!quiet) {
    fmt::print(
        "{}gpfd evolve: {} ({} on {}), population {}, generations {}, seed {}, results in {}\n",
        label, config.name, config.learner, config.env, config.gp.population, config.gp.generations,
        config.seed, outDir);
    std::fflush(stdout);
  }
  // On a terminal, a status line shows the evaluations of the running generation.
  std::atomic<bool> running{true};
  std::jthread status;
  if (terminal && !quiet) {
    status = std::jthread([&] {
      const auto start = std::chrono::steady_clock::now();
      while (running.load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print("\r\033[K  {}generation {}: {}/{} evaluated, {}", label,
                   discovery.history().size(), discovery.progress(), discovery.populationSize(),
                   duration(elapsed));
        std::fflush(stdout);
      }
    });
  }
  double total = 0.0;
  const auto stopStatus = [&] {
    running.store(false);
    if (status.joinable()) status.join();
    if (terminal && !quiet) fmt::print("\r\033[K");
  };
  // An error during the run (a worker's, a full disk) leaves the last generation's checkpoint.
  try {
    discovery.run(
        [&](const run::GenerationRecord& r) {
          total += r.seconds;
          if (quiet) return;
          const int remaining = config.gp.generations - 1 - r.generation;
          const double perGeneration = total / static_cast<double>(r.generation + 1);
          fmt::print(
              "{}{}gen {:3d}  best {:.6g}  mean {:.6g}  features {:.2f}  size {:.1f}  "
              "evals {} (+{} cached, {} re-evaluated)  {}  ETA {}\n",
              terminal ? "\r\033[K" : "", label, r.generation, r.best, r.mean, r.meanFeatures,
              r.meanSize, r.evaluations - r.reevaluations, r.cacheHits, r.reevaluations,
              duration(r.seconds), duration(perGeneration * remaining));
          std::fflush(stdout);
        },
        stopOnInterrupt());
  } catch (...) {
    stopStatus();
    if (!discovery.history().empty()) {
      fmt::print(stderr,
                 "gpfd evolve stopped after generation {}; its checkpoint is written. Continue "
                 "with: gpfd evolve --resume {}\n",
                 discovery.history().back().generation, resumeDir);
    }
    throw;
  }
  stopStatus();
  if (!discovery.finished()) {
    fmt::print(stderr,
               "interrupted after generation {}; the checkpoint is written. Continue with: "
               "gpfd evolve --resume {}\n",
               discovery.history().empty() ? -1 : discovery.history().back().generation, resumeDir);
    return 130;
  }
  if (!quiet) printOutcome(run::outcomeOf(discovery, 1), outDir, label);
  return 0;
}

// Runs (or continues) runs 1..runs of `base` in `dir`, then prints the set's summary.
int runSet(const run::ExperimentConfig& base, int runs, const run::DiscoveryOptions& options,
           std::optional<int> generations, bool quiet) {
  std::vector<run::RunOutcome> outcomes;
  for (int r = 1; r <= runs; ++r) {
    run::ExperimentConfig config = base;
    config.seed = run::runSeed(base.seed, r);
    run::DiscoveryOptions one = options;
    one.outDir = options.outDir + "/" + run::runDirName(r, runs);
    const DirectoryLock lock(one.outDir, "results directory");  // Also against --resume of it.
    std::unique_ptr<run::Discovery> discovery;
    if (std::filesystem::exists(one.outDir + "/config.toml")) {
      discovery = run::Discovery::resume(one, config, generations);
    } else {
      if (generations) config.gp.generations = *generations;
      discovery = run::Discovery::start(config, one);
    }
    const std::string label = fmt::format("[run {}/{}] ", r, runs);
    if (const int code = runDiscovery(*discovery, one.outDir, label, options.outDir, quiet)) {
      return code;
    }
    outcomes.push_back(run::outcomeOf(*discovery, r));
    writeFileAtomically(options.outDir + "/runs.csv", run::formatRunsCsv(outcomes));
  }
  if (!quiet) printSetSummary(outcomes, options.outDir);
  return 0;
}

int evolve(const EvolveOptions& o) {
  run::DiscoveryOptions options;
  options.outDir = o.resume.empty() ? o.out : o.resume;
  options.threads = threads(o.threads);
  options.version = kVersion;
  options.revision = kRevision;
#ifdef GPFD_HAVE_MPI
  // Under mpiexec with several processes: rank 0 runs everything below with an MpiEvaluator,
  // the other ranks only evaluate (docs/mpi.md).
  std::optional<mpi::WorkerRelease> release;
  if (auto* session = mpi::Session::current(); session && session->size() > 1) {
    if (!session->isMaster()) return mpi::serveAsWorker(*session, o.threads, kVersion);
    release.emplace(*session);
    options.processes = session->size();
    options.makeEvaluator = [session](const run::EvaluatorSetup& setup) {
      return std::make_unique<mpi::MpiEvaluator>(*session, setup.configText, kVersion,
                                                 setup.onEvaluated);
    };
  }
#endif
  stopOnInterrupt();
  // One writer per results directory, held until the process ends (by an MPI run's master).
  std::optional<DirectoryLock> lock;
  if (!o.resume.empty()) {
    if (!o.env.empty() || o.seed || o.population || !o.sets.empty() || o.runs) {
      throw InputError(
          "--resume continues with the stored config; only --generations, "
          "--threads and --quiet may be given",
          "--resume " + o.resume);
    }
    std::optional<run::ExperimentConfig> expected;
    if (!o.config.empty()) expected = loadConfig(o.config, {});
    if (!std::filesystem::is_directory(o.resume)) {
      throw InputError("no such results directory", "--resume " + o.resume);
    }
    lock.emplace(o.resume, "results directory");
    const std::string runsJson = o.resume + "/runs.json";
    if (std::filesystem::exists(runsJson)) {
      std::uint64_t seed = 0;
      int runs = 0;
      run::parseRunsJson(readFile(runsJson), runsJson, seed, runs);
      const std::string configPath = o.resume + "/config.toml";
      const auto base = run::loadExperimentConfig(configPath);
      if (expected && run::formatExperimentConfig(*expected) != readFile(configPath)) {
        throw InputError(
            "the config differs from the one the runs were started with (see " + configPath + ")",
            o.resume);
      }
      return runSet(base, runs, options, o.generations, o.quiet);
    }
    auto discovery = run::Discovery::resume(options, expected, o.generations);
    if (discovery->finished()) {
      fmt::print(stderr,
                 "the run in {0} is already complete (generations: {1}); pass --generations N "
                 "(more than {1}) to extend it\n",
                 o.resume, discovery->config().gp.generations);
      return 0;
    }
    return runDiscovery(*discovery, options.outDir, "", options.outDir, o.quiet);
  }
  const auto config = loadConfig(o.config, overrides(o));
  // Parents and offspring with every genome at its size limits.
  requireMemory(2.0 * config.gp.population * config.limits.maxFeatures * config.limits.maxSize *
                    static_cast<double>(sizeof(expr::Node)),
                "the population at its genome size limits",
                "gp.population x genome.max_features x genome.max_size");
  // The default results/<name> (or -2, -3, ... when taken) never collides with an earlier run.
  lock.emplace(options.outDir.empty()
                   ? DirectoryLock::lockFresh("results/" + config.name, "results directory")
                   : DirectoryLock(options.outDir, "results directory"));
  options.outDir = lock->directory();
  const int runs = o.runs.value_or(1);
  if (runs == 1) {
    std::unique_ptr<run::Discovery> discovery;
    try {
      discovery = run::Discovery::start(config, options);
    } catch (...) {
      lock->removeCreatedDirectory();  // Nothing half-made is left behind.
      throw;
    }
    return runDiscovery(*discovery, options.outDir, "", options.outDir, o.quiet);
  }
  run::refuseExistingRuns(options.outDir);
  run::validate(config);
  createDirectories(options.outDir, "results directory");
  writeFileAtomically(options.outDir + "/config.toml", run::formatExperimentConfig(config));
  writeFileAtomically(options.outDir + "/runs.json", run::formatRunsJson(config.seed, runs));
  return runSet(config, runs, options, std::nullopt, o.quiet);
}

const CommandRegistration registration{
    "evolve", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "evolve", "Discover features with GP; fitness = learning performance in short trials");
      auto o = std::make_shared<EvolveOptions>();
      cmd->add_option("config", o->config,
                      "Experiment config: a TOML file or a shipped config name "
                      "(configs/NAME.toml); default: cartpole-quick");
      cmd->add_option("--env", o->env, "Environment (overrides env.name)")
          ->check(environmentName());
      cmd->add_option("--seed", o->seed, "Random seed (overrides seed)")->check(seedValue());
      cmd->add_option("--threads", o->threads,
                      "Worker threads (0: all cores); never changes results")
          ->check(threadCount());
      cmd->add_option("--population", o->population, "Population size (overrides gp.population)")
          ->check(bounded(2, kMaxPopulation));
      cmd->add_option("--generations", o->generations,
                      "Generations (overrides gp.generations; may extend a resumed run)")
          ->check(bounded(1, kMaxGenerations));
      cmd->add_option("--out", o->out,
                      "Results directory (default results/<name>, or results/<name>-N when taken)");
      cmd->add_option("--resume", o->resume, "Continue the run in this results directory");
      cmd->add_option("--set", o->sets, "Override any config key: --set gp.elitism=0.2")
          ->allow_extra_args(false);
      cmd->add_option("--runs", o->runs,
                      "Independent GP runs (1-1000): run r in OUT/run-NN with a seed derived "
                      "from --seed (run 1 uses it as is); runs.csv sums them up")
          ->check(bounded(1, 1000));
      cmd->add_flag("--quiet", o->quiet, "No progress output");
      return [o] { return evolve(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
