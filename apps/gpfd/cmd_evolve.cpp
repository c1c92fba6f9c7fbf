// `gpfd evolve`: feature discovery with GP, fitness from short learning trials. The command only
// turns its flags into a service::EvolveRequest (gpfd/service/evolve.hpp does the rest).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "command.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/evolve_text.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"
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
  std::optional<std::string> out;
  bool force = false;
  std::string resume;
  std::string replay;
  std::vector<std::string> sets;
  std::optional<int> runs;
  std::optional<std::string> timeBudget;
  bool quiet = false;
  double mpiTimeout = 60.0;  // Seconds (mpi::kDefaultWorkerTimeout).
};

// The flags that override config keys, applied like --set so that they are checked in one place.
std::vector<std::string> overrides(const EvolveOptions& o) {
  std::vector<std::string> all;
  if (!o.env.empty()) all.push_back("env.name=\"" + o.env + "\"");
  if (o.seed) all.push_back("seed=" + std::to_string(*o.seed));
  if (o.population) all.push_back("gp.population=" + std::to_string(*o.population));
  if (o.timeBudget) {
    if (o.population || o.generations) {
      throw InputError(
          "a time budget chooses the population and the generations: give either "
          "it or them",
          "--time-budget");
    }
    all.push_back("time_budget=" + numberText(parseDuration(*o.timeBudget, "--time-budget")));
  }
  all.insert(all.end(), o.sets.begin(), o.sets.end());
  return all;
}

void writeTo(std::FILE* stream, const std::string& text) {
  std::fputs(text.c_str(), stream);
  std::fflush(stream);
}

int evolve(const EvolveOptions& o) {
  service::EvolveRequest request;
  request.config = o.config;
  request.overrides = overrides(o);
  request.out = {o.out, o.force, "--out"};
  request.resume = o.resume;
  request.replay = o.replay;
  request.generations = o.generations;
  request.runs = o.runs;
  request.threads = o.threads;
#ifdef GPFD_HAVE_MPI
  // Under mpiexec with several processes: rank 0 runs the request with an MpiEvaluator, the other
  // ranks only evaluate (docs/mpi.md).
  std::optional<mpi::WorkerRelease> release;
  if (auto* session = mpi::Session::current(); session && session->size() > 1) {
    if (!session->isMaster()) return mpi::serveAsWorker(*session, o.threads, kVersion);
    const auto timeout = std::chrono::milliseconds(std::llround(o.mpiTimeout * 1000));
    release.emplace(*session, timeout);
    request.processes = session->size();
    request.makeEvaluator = [session, timeout](const run::EvaluatorSetup& setup) {
      // The workers hold one config at a time (mpi/protocol.hpp): no second evaluator beside
      // the first.
      if (setup.rung > 0) {
        throw InputError(
            "fitness.promote (successive halving) is not available under MPI yet: run it on "
            "threads, or from Python with an executor",
            "fitness.promote");
      }
      return std::make_unique<mpi::MpiEvaluator>(
          *session, setup.configText, kVersion,
          mpi::MpiEvaluatorOptions{
              .workerTimeout = timeout,
              .onEvaluated = setup.onEvaluated,
              .onWorkerLost = [](const std::string& s) { writeTo(stderr, "gpfd: " + s + "\n"); }});
    };
  }
#endif
  service::EvolveText text({.out = [](const std::string& s) { writeTo(stdout, s); },
                            .err = [](const std::string& s) { writeTo(stderr, s); },
                            .terminal = ::isatty(STDOUT_FILENO) != 0,
                            .quiet = o.quiet});
  const auto result = service::evolve(
      request, text,
      stopOnInterrupt("\ngpfd evolve: stopping once the running generation's checkpoint is "
                      "written; press Ctrl-C again to stop at once (the run then resumes from "
                      "the previous checkpoint)\n"));
  return result.finished ? 0 : 130;
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
                      "Results directory (default results/<name>, or results/<name>-N when "
                      "taken); one that already holds files needs --force");
      cmd->add_flag("--force", o->force,
                    "Write into an --out that already holds files (never over a run: resume it)");
      cmd->add_option("--resume", o->resume, "Continue the run in this results directory");
      cmd->add_option("--replay", o->replay,
                      "Rerun the finished run in this results directory with the sizes and "
                      "learner settings it used (those a time budget chose), into a fresh "
                      "directory (--out; default results/<its name>-replay): the same files but "
                      "timings, on any number of threads");
      cmd->add_option("--set", o->sets, "Override any config key: --set gp.elitism=0.2")
          ->allow_extra_args(false);
      cmd->add_option("--runs", o->runs,
                      "Independent GP runs (1-1000): run r in OUT/run-NN with a seed derived "
                      "from --seed (run 1 uses it as is); runs.csv sums them up")
          ->check(bounded(1, 1000));
      cmd->add_option("--time-budget", o->timeBudget,
                      "Wall time for the whole command (90s, 10m, 1h30m, or seconds): the cost "
                      "of an evaluation is measured, and the population, generations and "
                      "validation sized to end within it (written to config.toml)");
      cmd->add_flag("--quiet", o->quiet, "No progress output");
      cmd->add_option("--mpi-timeout", o->mpiTimeout,
                      "Under mpiexec: seconds without a message after which a worker is lost "
                      "and its evaluations go to the others (default 60)")
          ->check(CLI::Range(0.1, 86400.0));
      return [o] { return evolve(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
