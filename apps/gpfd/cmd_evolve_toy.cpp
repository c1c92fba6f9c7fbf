// `gpfd evolve-toy`: the built-in supervised task that proves the GP loop end to end.
#include <fmt/format.h>

#include <filesystem>

#include "command.hpp"
#include "gpfd/experiments/toy_task.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/run/thread_evaluator.hpp"
#include "gpfd/service/resources.hpp"
#include "gpfd/service/results_directory.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {
namespace {

struct ToyOptions {
  std::uint64_t seed = 1;
  std::string out = "results/evolve-toy";
  int threads = 0;
  int population = 0;
  int generations = 0;
  int samples = 200;
  bool quiet = false;
};

int runToy(const ToyOptions& o) {
  auto config = experiments::toyGpConfig(o.seed);
  if (o.population > 0) config.population = o.population;
  if (o.generations > 0) config.generations = o.generations;
  const DirectoryLock lock = service::lockDirectory(o.out, "output directory");

  const experiments::ToyTask task(o.samples, deriveSeed(o.seed, 7));
  run::ThreadEvaluator evaluator([&task](const expr::Genome& g, Rng&) { return task.rSquared(g); },
                                 service::usableThreads(o.threads));
  gp::Evolution evolution(config, experiments::toySearchSpace(), evaluator);
  evolution.run([&](const gp::GenerationStats& s) {
    if (!o.quiet) {
      fmt::print("gen {:3d}  best {:.6f}  mean {:.4f}  features {:.2f}  size {:.1f}  {:.2f}s\n",
                 s.generation, s.best, s.mean, s.meanFeatures, s.meanSize, s.seconds);
      std::fflush(stdout);
    }
    return true;
  });

  const auto& best = evolution.best();
  const auto& names = experiments::ToyTask::variableNames();
  const double r2 = task.rSquared(best.genome);
  expr::FeaturesFile file;
  file.env = "toy";
  file.variables = names;
  file.genome = expr::simplify(best.genome);
  file.meta["fitness"] = fmt::format("{}", best.fitness);
  file.meta["r2"] = fmt::format("{}", r2);
  file.meta["seed"] = std::to_string(o.seed);
  expr::writeFeaturesFile(o.out + "/best.features", file);

  fmt::print("target: y = 3 x0 x1 - 2 sin(x2) + 0.5\nbest features ({}):\n",
             file.genome.featureCount());
  for (std::size_t k = 0; k < file.genome.featureCount(); ++k) {
    fmt::print("  f{} = {}\n", k + 1, expr::toInfix(file.genome.feature(k), names));
  }
  fmt::print("written to {}/best.features\nR2 {:.8f}\n", o.out, r2);
  return 0;
}

const CommandRegistration registration{
    "evolve-toy", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "evolve-toy",
          "Evolve features for the built-in toy regression y = 3 x0 x1 - 2 sin(x2) + 0.5 (fitness: "
          "R^2 of least squares on the features)");
      auto o = std::make_shared<ToyOptions>();
      cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str()->check(seedValue());
      cmd->add_option("--out", o->out, "Output directory")->capture_default_str();
      cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")
          ->check(threadCount());
      cmd->add_option("--population", o->population, "Population size (default 200)")
          ->check(bounded(2, kMaxPopulation));
      cmd->add_option("--generations", o->generations, "Generations (default 40)")
          ->check(bounded(1, kMaxGenerations));
      cmd->add_option("--samples", o->samples, "Sampled states")->check(bounded(10, 1000000));
      cmd->add_flag("--quiet", o->quiet, "No per-generation lines");
      return [o] { return runToy(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
