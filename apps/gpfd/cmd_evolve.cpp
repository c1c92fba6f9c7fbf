// `gpfd evolve`: feature discovery with GP, fitness from short learning trials.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

#include "command.hpp"
#include "config_loading.hpp"
#include "gpfd/run/discovery.hpp"
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

// The default results directory: results/<name>, or results/<name>-2, -3, ... when taken, so
// that running the same command again never collides with an earlier run.
std::string freshResultsDir(const std::string& base) {
  std::string dir = base;
  for (int n = 2; std::filesystem::exists(dir); ++n) dir = base + "-" + std::to_string(n);
  return dir;
}

int evolve(const EvolveOptions& o) {
  run::DiscoveryOptions options;
  options.outDir = o.resume.empty() ? o.out : o.resume;
  options.threads = o.threads;
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
  std::unique_ptr<run::Discovery> discovery;
  if (!o.resume.empty()) {
    if (!o.env.empty() || o.seed || o.population || !o.sets.empty()) {
      throw InputError(
          "--resume continues with the stored config; only --generations, "
          "--threads and --quiet may be given",
          "--resume " + o.resume);
    }
    std::optional<run::ExperimentConfig> expected;
    if (!o.config.empty()) expected = loadConfig(o.config, {});
    discovery = run::Discovery::resume(options, expected, o.generations);
  } else {
    const auto config = loadConfig(o.config, overrides(o));
    if (options.outDir.empty()) options.outDir = freshResultsDir("results/" + config.name);
    discovery = run::Discovery::start(config, options);
  }

  const bool terminal = ::isatty(STDOUT_FILENO) != 0;
  const auto& config = discovery->config();
  if (!o.quiet) {
    fmt::print(
        "gpfd evolve: {} ({} on {}), population {}, generations {}, seed {}, results in {}\n",
        config.name, config.learner, config.env, config.gp.population, config.gp.generations,
        config.seed, options.outDir);
    std::fflush(stdout);
  }
  const std::atomic<bool>& interrupted = stopOnInterrupt();

  // On a terminal, a status line shows the evaluations of the running generation.
  std::atomic<bool> running{true};
  std::jthread status;
  if (terminal && !o.quiet) {
    status = std::jthread([&] {
      const auto start = std::chrono::steady_clock::now();
      while (running.load()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print("\r\033[K  generation {}: {}/{} evaluated, {}", discovery->history().size(),
                   discovery->progress(), discovery->populationSize(), duration(elapsed));
        std::fflush(stdout);
      }
    });
  }
  double total = 0.0;
  // An error during the run (a worker's, a full disk) leaves the last generation's checkpoint.
  const auto stoppedByError = [&] {
    running.store(false);
    if (status.joinable()) status.join();
    if (terminal && !o.quiet) fmt::print("\r\033[K");
    if (discovery->history().empty()) return;
    fmt::print(stderr,
               "gpfd evolve stopped in generation {}; the checkpoint of generation {} is "
               "written. Continue with: gpfd evolve --resume {}\n",
               discovery->history().back().generation + 1, discovery->history().back().generation,
               options.outDir);
  };
  try {
    discovery->run(
        [&](const run::GenerationRecord& r) {
          total += r.seconds;
          if (o.quiet) return;
          const int remaining = config.gp.generations - 1 - r.generation;
          const double perGeneration = total / static_cast<double>(r.generation + 1);
          fmt::print(
              "{}gen {:3d}  best {:.6g}  mean {:.6g}  features {:.2f}  size {:.1f}  "
              "evals {} (+{} cached)  {}  ETA {}\n",
              terminal ? "\r\033[K" : "", r.generation, r.best, r.mean, r.meanFeatures, r.meanSize,
              r.evaluations, r.cacheHits, duration(r.seconds), duration(perGeneration * remaining));
          std::fflush(stdout);
        },
        interrupted);
  } catch (...) {
    stoppedByError();
    throw;
  }
  running.store(false);
  if (status.joinable()) status.join();
  if (terminal && !o.quiet) fmt::print("\r\033[K");

  if (!discovery->finished()) {
    fmt::print(stderr,
               "interrupted after generation {}; the checkpoint is written. Continue with: "
               "gpfd evolve --resume {}\n",
               discovery->history().back().generation, options.outDir);
    return 130;
  }
  if (!o.quiet) {
    fmt::print("best fitness {}; features in {}/best.features\n", discovery->history().back().best,
               options.outDir);
  }
  return 0;
}

const CommandRegistration registration{
    "evolve", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "evolve", "Discover features with GP; fitness = learning performance in short trials");
      auto o = std::make_shared<EvolveOptions>();
      cmd->add_option("config", o->config,
                      "Experiment config: a TOML file or a shipped config name "
                      "(configs/NAME.toml); default: cartpole-quick");
      cmd->add_option("--env", o->env, "Environment (overrides env.name)");
      cmd->add_option("--seed", o->seed, "Random seed (overrides seed)");
      cmd->add_option("--threads", o->threads,
                      "Worker threads (0: all cores); never changes results")
          ->check(threadCount());
      cmd->add_option("--population", o->population, "Population size (overrides gp.population)");
      cmd->add_option("--generations", o->generations,
                      "Generations (overrides gp.generations; may extend a resumed run)");
      cmd->add_option("--out", o->out,
                      "Results directory (default results/<name>, or results/<name>-N when taken)");
      cmd->add_option("--resume", o->resume, "Continue the run in this results directory");
      cmd->add_option("--set", o->sets, "Override any config key: --set gp.elitism=0.2")
          ->allow_extra_args(false);
      cmd->add_flag("--quiet", o->quiet, "No progress output");
      return [o] { return evolve(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
