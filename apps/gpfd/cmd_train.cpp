// `gpfd train ENV [--features FILE | --raw] [--learner pg|lpi] [--param k=v]... [--seed S]
// [--out DIR]`: trains one linear learner once, prints the curve as it goes and writes
// DIR/curve.csv and DIR/weights.json (atomically, after training; nothing on bad input).
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/learner_params.hpp"
#include "gpfd/rl/tetris_afterstates.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "param_routing.hpp"

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
  std::string out;
  int eval = 0;
  bool quiet = false;
};

std::string joinNames(const std::vector<rl::LearnerParamSpec>& specs) {
  std::string s;
  for (const auto& spec : specs) s += (s.empty() ? "" : ", ") + spec.name;
  return s;
}

std::string curveCsv(const rl::LearningCurve& curve) {
  std::string csv = "update,episodes,steps,mean_return\n";
  for (const auto& p : curve.points) {
    csv += fmt::format("{},{},{},{}\n", p.update, p.episodes, p.steps, p.meanReturn);
  }
  return csv;
}

int runTrain(const TrainArgs& args) {
  const auto& registry = env::Registry::global();
  const env::EnvInfo& info = registry.info(args.env);
  const std::string learner =
      args.learner.empty() ? (args.env == "tetris" ? "lpi" : "pg") : args.learner;
  if (learner != "pg" && learner != "lpi") {
    throw InputError(fmt::format("unknown learner '{}' (known: pg, lpi)", learner), "--learner");
  }
  if (!args.features.empty() && args.raw) {
    throw InputError("give either --features or --raw, not both", "--raw");
  }

  // Route each k=v to the environment (its own parameter names) or to the learner.
  env::Params envParams;
  rl::PolicyGradientConfig pg;
  rl::LambdaPolicyIterationConfig lpi;
  std::string start;
  bool biasGiven = false;
  for (const auto& kv : args.params) {
    const auto [key, value] = splitKeyValue(kv, "--param");
    if (isEnvParam(info, key)) {
      envParams[key] = value;
      continue;
    }
    if (learner == "lpi" && key == "start") {
      if (value != "zero" && value != "bertsekas") {
        throw InputError(fmt::format("'{}' is not a start (zero|bertsekas)", value),
                         "--param start");
      }
      start = value;
      continue;
    }
    biasGiven = biasGiven || key == "bias";
    const bool known = learner == "pg" ? rl::applyPolicyGradientParam(pg, key, value)
                                       : rl::applyLambdaPolicyIterationParam(lpi, key, value);
    if (!known) {
      std::string envNames;
      for (const auto& spec : info.params) envNames += (envNames.empty() ? "" : ", ") + spec.name;
      throw InputError(
          fmt::format("unknown parameter '{}' (the {} learner's: {}{}; {}'s: {})", key, learner,
                      joinNames(learner == "pg" ? rl::policyGradientParamSpecs()
                                                : rl::lambdaPolicyIterationParamSpecs()),
                      learner == "lpi" ? ", start" : "", args.env, envNames),
          "--param");
    }
  }
  const std::unique_ptr<env::Environment> environment = registry.make(args.env, envParams);
  auto* tetris = dynamic_cast<env::Tetris*>(environment.get());
  if (learner == "lpi" && tetris == nullptr) {
    throw InputError("lambda-policy iteration needs an afterstate game (tetris)", "--learner");
  }
  if (learner == "pg" && tetris != nullptr) {
    throw InputError("Tetris is learned with lambda-policy iteration (--learner lpi)", "--learner");
  }

  // The feature map: raw state variables, a features file, or both side by side.
  const std::size_t stateDim = environment->stateDim();
  const auto& stateNames = environment->stateNames();
  std::vector<std::string> featureNames;
  std::shared_ptr<const jit::FeatureMap> map;
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
      map = std::make_shared<jit::ConcatFeatureMap>(
          std::vector<std::shared_ptr<const jit::FeatureMap>>{
              map, std::make_shared<jit::RawFeatureMap>(stateDim)});
      featureNames.insert(featureNames.end(), stateNames.begin(), stateNames.end());
      featuresDescription += " + raw";
    }
  } else {
    map = std::make_shared<jit::RawFeatureMap>(stateDim);
    featureNames = stateNames;
  }

  const bool bertsekasState =
      tetris != nullptr && tetris->config().state == env::TetrisFeatures::Bertsekas;
  if (learner == "lpi") {
    // The Bertsekas layout ends with a constant already: no second bias unless asked for.
    if (bertsekasState && !biasGiven) lpi.features.bias = false;
    const bool rawOnly = args.features.empty();
    if (lpi.initialWeights.empty() && rawOnly &&
        (start == "bertsekas" || (start.empty() && bertsekasState))) {
      lpi.initialWeights =
          rl::bertsekasIoffeStartWeights(tetris->config().cols, lpi.features.bias ? 1 : 0);
    } else if (start == "bertsekas" && !rawOnly) {
      throw InputError("the Bertsekas-Ioffe start needs the raw Tetris state (no --features)",
                       "--param start");
    }
  }
  const bool bias = learner == "pg" ? pg.features.bias : lpi.features.bias;
  if (bias) featureNames.push_back("bias");

  // Check the output directory before spending time on training.
  const std::string outDir =
      args.out.empty() ? fmt::format("gpfd-train-{}-{}", args.env, args.seed) : args.out;
  createDirectories(outDir);

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
  rl::LearningCurve curve;
  double evalMean = 0.0;
  int evalCount = 0;
  if (learner == "pg") {
    pg.onPoint = progress;
    curve = rl::trainPolicyGradient(*environment, *map, pg, rng);
    if (args.eval > 0 && !curve.diverged) {
      Rng evalRng(deriveSeed(args.seed, 1));
      const auto e =
          rl::evaluatePolicy(*environment, *map, curve.weights, pg, args.eval, true, evalRng);
      evalMean = e.meanReturn;
      evalCount = e.episodes;
    }
  } else {
    lpi.onPoint = progress;
    rl::TetrisAfterstateProblem problem(*tetris);
    curve = rl::trainLambdaPolicyIteration(problem, *map, lpi, rng);
    if (args.eval > 0 && !curve.diverged) {
      Rng evalRng(deriveSeed(args.seed, 1));
      const auto e = rl::playGreedy(problem, *map, curve.weights, lpi, args.eval, evalRng);
      evalMean = e.meanReturn;
      evalCount = e.games;
    }
  }

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
  if (evalCount > 0)
    weights["greedy_evaluation"] = {{"episodes", evalCount}, {"mean_return", evalMean}};
  writeFileAtomically(outDir + "/curve.csv", curveCsv(curve));
  writeFileAtomically(outDir + "/weights.json", weights.dump(2) + "\n");

  if (!args.quiet) {
    fmt::print("# {} episodes, {} steps, {:.3f} s{}\n", curve.episodes, curve.steps,
               curve.wallSeconds, curve.diverged ? ", DIVERGED: " + curve.divergedReason : "");
    if (evalCount > 0) fmt::print("# greedy evaluation: {:.6g} over {}\n", evalMean, evalCount);
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
      cmd->add_option("--learner", args->learner, "pg | lpi (default: lpi for tetris, else pg)")
          ->check(oneOf({"pg", "lpi"}));
      cmd->add_option("--param", args->params,
                      "k=v for the environment or the learner (repeatable)");
      cmd->add_option("--seed", args->seed, "seed of the run (default 1)")->check(seedValue());
      cmd->add_option("--out", args->out, "output directory (default gpfd-train-ENV-SEED)");
      cmd->add_option("--eval", args->eval, "greedy evaluation episodes after training")
          ->check(bounded(0, 100000));
      cmd->add_flag("--quiet", args->quiet, "print nothing");
      return [args] { return runTrain(*args); };
    }};

}  // namespace
}  // namespace gpfd::app
