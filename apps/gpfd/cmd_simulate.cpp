// `gpfd simulate ENV ...`: runs one environment and writes its trajectory as CSV to stdout.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include "command.hpp"
#include "gpfd/env/simulate.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {
namespace {

struct SimulateArgs {
  std::string env;
  std::vector<std::string> params;
  std::string state;
  std::string actions;
  std::string policy;
  std::optional<long long> steps;
  std::uint64_t seed = 0;
  bool noStop = false;
};

int runSimulate(const SimulateArgs& args) {
  env::SimulationRequest request;
  request.env = args.env;
  for (const auto& kv : args.params) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(fmt::format("expected k=v, got '{}'", kv), "--param");
    }
    request.params[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  if (!args.state.empty()) request.initialState = env::parseNumberList(args.state, "--state");
  if (!args.actions.empty() && !args.policy.empty()) {
    throw InputError("give either --actions or --policy, not both", "--actions");
  }
  if (!args.actions.empty()) {
    if (args.actions == "-") {
      request.actions = env::readActionLines(std::cin, "stdin");
      request.actionsSource = "stdin";
    } else {
      std::ifstream file(args.actions);
      if (!file) throw InputError("cannot open the actions file", args.actions);
      request.actions = env::readActionLines(file, args.actions);
      request.actionsSource = args.actions;
    }
  } else if (args.policy == "random") {
    if (!args.steps) throw InputError("--policy random needs --steps N", "--policy");
    request.randomSteps = static_cast<std::size_t>(*args.steps);
  }
  if (args.steps && args.policy.empty()) {
    throw InputError(
        "--steps counts the steps of --policy random; without a policy or --actions only the "
        "initial state is printed",
        "--steps");
  }
  request.seed = args.seed;
  request.stopAtEpisodeEnd = !args.noStop;
  const std::string csv = env::simulateCsv(request);
  std::fwrite(csv.data(), 1, csv.size(), stdout);
  return 0;
}

const CommandRegistration registration{
    "simulate", [](CLI::App& app) {
      auto args = std::make_shared<SimulateArgs>();
      auto* cmd = app.add_subcommand(
          "simulate", "Run one environment on given or random actions and write CSV to stdout");
      cmd->add_option("env", args->env, "environment name (see `gpfd envs`)")
          ->required()
          ->check(environmentName());
      cmd->add_option("--param", args->params, "parameter k=v (repeatable)");
      cmd->add_option("--state", args->state, "initial state v1,v2,... (default: a reset)");
      cmd->add_option("--actions", args->actions,
                      "file of actions, one per line, components comma-separated; - for stdin");
      cmd->add_option("--policy", args->policy, "random: uniformly random legal actions")
          ->check(oneOf({"random"}));
      cmd->add_option("--steps", args->steps, "number of steps of the random policy")
          ->check(bounded(0, kMaxSteps));
      cmd->add_option("--seed", args->seed, "seed of the reset and of the random policy")
          ->check(seedValue());
      cmd->add_flag("--no-stop", args->noStop, "go on after a terminated or truncated step");
      return [args] { return runSimulate(*args); };
    }};

}  // namespace
}  // namespace gpfd::app
