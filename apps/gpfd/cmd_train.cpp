// `gpfd train ENV [--features FILE | --raw] [--learner pg|lpi] [--param k=v]... [--seed S]
// [--out DIR]`: trains one linear learner once, prints the curve as it goes and writes
// DIR/curve.csv and DIR/weights.json (atomically, after training; nothing on bad input).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "command.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/service/params.hpp"
#include "gpfd/service/results_directory.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "listings.hpp"

namespace gpfd::app {
namespace {

struct TrainArgs {
  std::string env;
  std::string features;
  bool raw = false;
  bool addRaw = false;
  std::string learner;
  std::vector<std::string> params;
  std::uint64_t seed = 1;
  std::optional<std::string> out;
  bool force = false;
  int eval = 0;
  bool quiet = false;
};

std::string curveCsv(const rl::LearningCurve& curve) {
  std::string csv = "update,episodes,steps,mean_return\n";
  for (const auto& p : curve.points) {
    csv += fmt::format("{},{},{},{}\n", p.update, p.episodes, p.steps, p.meanReturn);
  }
  return csv;
}

int runTrain(const TrainArgs& args) {
  const auto& registry = env::Registry::global();
  const auto& learners = rl::LearnerRegistry::global();
  const env::EnvInfo& info = registry.info(args.env);
  const std::string learner = args.learner.empty() ? info.defaultLearner : args.learner;
  const auto& learnerInfo = service::reportedAt(
      "--learner", [&]() -> const auto& { return learners.info(learner); });
  if (!args.features.empty() && args.raw) {
    throw InputError("give either --features or --raw, not both", "--raw");
  }

  // Each k=v goes to the environment (its own parameter names) or to the learner.
  const service::RoutedParams params = service::routeParams(args.params, info, "--param");
  const auto learnerParamNames = paramNames(learnerInfo.params);
  for (const auto& [key, value] : params.learner) {
    if (std::find(learnerParamNames.begin(), learnerParamNames.end(), key) ==
        learnerParamNames.end()) {
      throw InputError(fmt::format("unknown parameter '{}' (the {} learner's: {}; {}'s: {})", key,
                                   learner, fmt::join(learnerParamNames, ", "), args.env,
                                   fmt::join(paramNames(info.params), ", ")),
                       "--param");
    }
  }
  const std::unique_ptr<env::Environment> environment = registry.make(args.env, params.env);
  service::reportedAt("--learner", [&] { learners.checkSuitable(learner, *environment); });
  const std::unique_ptr<rl::Learner> trainer = learners.make(learner, params.learner);

  // The feature map: raw state variables, a features file, or both side by side.
  const std::size_t stateDim = environment->stateDim();
  const auto& stateNames = environment->stateNames();
  std::vector<std::string> featureNames;
  std::shared_ptr<const features::FeatureMap> map;
  std::string featuresDescription = "raw";
  if (!args.features.empty()) {
    const expr::FeaturesFile file = expr::readFeaturesFile(args.features, stateNames, args.env);
    try {
      map = std::make_shared<jit::CompiledFeatureMap>(file.genome, stateDim);
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what(), args.features);
    }
    for (std::size_t k = 0; k < file.genome.featureCount(); ++k) {
      featureNames.push_back(expr::toInfix(file.genome.feature(k), stateNames));
    }
    featuresDescription = args.features;
    if (args.addRaw) {
      map = std::make_shared<features::ConcatFeatureMap>(
          std::vector<std::shared_ptr<const features::FeatureMap>>{
              map, std::make_shared<features::RawFeatureMap>(stateDim)});
      featureNames.insert(featureNames.end(), stateNames.begin(), stateNames.end());
      featuresDescription += " + raw";
    }
  } else {
    map = std::make_shared<features::RawFeatureMap>(stateDim);
    featureNames = stateNames;
  }

  // Check the output directory before spending time on training.
  // A fresh results/train-ENV-SEED (-2, ... when taken) unless --out says otherwise; locked.
  const DirectoryLock lock = service::claimResultsDirectory(
      {args.out, args.force, "--out"}, fmt::format("train-{}-{}", args.env, args.seed), {},
      "output directory");
  const std::string& outDir = lock.directory();

  auto progress = [&](const rl::CurvePoint& p) {
    if (!args.quiet) {
      fmt::print("{:>6} {:>9} {:>12} {:>14.6g}\n", p.update, p.episodes, p.steps, p.meanReturn);
      std::fflush(stdout);
    }
  };
  if (!args.quiet) {
    fmt::print("# gpfd train {} --learner {} --seed {} (features: {})\n", args.env, learner,
               args.seed, featuresDescription);
    fmt::print("{:>6} {:>9} {:>12} {:>14}\n", "update", "episodes", "steps", "mean_return");
  }
  Rng rng(args.seed);
  const rl::LearningCurve curve = trainer->train(*environment, *map, rng, progress);
  rl::Evaluation evaluation;
  if (args.eval > 0 && !curve.diverged) {
    Rng evalRng(deriveSeed(args.seed, 1));
    evaluation = trainer->evaluate(*environment, *map, curve.weights, args.eval, evalRng);
  }
  if (curve.weights.bias) featureNames.push_back("bias");

  nlohmann::json weights;
  weights["env"] = args.env;
  weights["env_params"] = environment->params();
  weights["learner"] = learner;
  weights["features"] = featuresDescription;
  weights["feature_names"] = featureNames;
  weights["seed"] = args.seed;
  weights["param_overrides"] = args.params;
  weights["rows"] = curve.weights.rows;
  weights["cols"] = curve.weights.cols;
  weights["values"] = curve.weights.values;
  weights["bias"] = curve.weights.bias;
  if (!curve.weights.shift.empty()) {
    weights["shift"] = curve.weights.shift;
    weights["scale"] = curve.weights.scale;
  }
  weights["episodes"] = curve.episodes;
  weights["steps"] = curve.steps;
  weights["wall_seconds"] = curve.wallSeconds;
  weights["diverged"] = curve.diverged;
  if (curve.diverged) weights["diverged_reason"] = curve.divergedReason;
  if (evaluation.episodes > 0) {
    weights["greedy_evaluation"] = {{"episodes", evaluation.episodes},
                                    {"mean_return", evaluation.meanReturn}};
  }
  writeFileAtomically(outDir + "/curve.csv", curveCsv(curve));
  writeFileAtomically(outDir + "/weights.json", weights.dump(2) + "\n");

  if (!args.quiet) {
    fmt::print("# {} episodes, {} steps, {:.3f} s{}\n", curve.episodes, curve.steps,
               curve.wallSeconds, curve.diverged ? ", DIVERGED: " + curve.divergedReason : "");
    if (evaluation.episodes > 0) {
      fmt::print("# greedy evaluation: {:.6g} over {}\n", evaluation.meanReturn,
                 evaluation.episodes);
    }
    fmt::print("# wrote {}/curve.csv and {}/weights.json\n", outDir, outDir);
  }
  if (curve.diverged) {
    throw NumericalError(fmt::format("training diverged after {} curve rows: {}",
                                     curve.points.size(), curve.divergedReason),
                         outDir + "/weights.json");
  }
  return 0;
}

const CommandRegistration registration{
    "train", [](CLI::App& app) {
      auto args = std::make_shared<TrainArgs>();
      auto* cmd = app.add_subcommand("train", "Train a linear learner once and write its curve");
      cmd->add_option("env", args->env, "environment name (see `gpfd envs`)")
          ->required()
          ->check(environmentName());
      cmd->add_option("--features", args->features, "features file (default: the raw state)");
      cmd->add_flag("--raw", args->raw, "the raw state variables as features (the default)");
      cmd->add_flag("--add-raw", args->addRaw, "with --features: append the raw state variables");
      cmd->add_option("--learner", args->learner,
                      "learner (gpfd learners); default: the environment's (gpfd envs)");
      cmd->add_option("--param", args->params,
                      "k=v for the environment or the learner (repeatable)");
      cmd->footer(
          "Learner parameters (defaults, ranges and meanings: gpfd learners; the "
          "environments': gpfd envs):\n" +
          learnerParamSummary());
      cmd->add_option("--seed", args->seed, "seed of the run (default 1)")->check(seedValue());
      cmd->add_option("--out", args->out,
                      "output directory (default results/train-ENV-SEED, or -2, -3, ... when "
                      "taken); one that already holds files needs --force");
      cmd->add_flag("--force", args->force, "write into an --out that already holds files");
      cmd->add_option("--eval", args->eval, "greedy evaluation episodes after training")
          ->check(bounded(0, 100000));
      cmd->add_flag("--quiet", args->quiet, "print nothing");
      return [args] { return runTrain(*args); };
    }};

}  // namespace
}  // namespace gpfd::app
