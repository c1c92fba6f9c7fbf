#include "gpfd/env/simulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::env {
namespace {

void appendRow(std::string& out, std::size_t step, std::span<const double> action,
               std::size_t actionComponents, std::span<const double> state,
               const StepResult* result) {
  fmt::format_to(std::back_inserter(out), "{}", step);
  for (std::size_t i = 0; i < actionComponents; ++i) {
    out += ',';
    if (!action.empty()) fmt::format_to(std::back_inserter(out), "{}", action[i]);
  }
  for (double v : state) fmt::format_to(std::back_inserter(out), ",{}", v);
  if (result) {
    fmt::format_to(std::back_inserter(out), ",{},{:d},{:d}\n", result->reward,
                   static_cast<int>(result->terminated), static_cast<int>(result->truncated));
  } else {
    out += ",,,\n";
  }
}

// A state or reward that is no longer a finite number ends the simulation: what follows would be
// meaningless (NumericalError, exit code 3 in the CLI).
void requireFinite(const Environment& env, const StepResult& result, std::size_t step,
                   const std::string& name) {
  const auto state = env.state();
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!std::isfinite(state[i])) {
      throw NumericalError(
          fmt::format("non-finite state at step {}: {} = {}", step, env.stateNames()[i], state[i]),
          name);
    }
  }
  if (!std::isfinite(result.reward)) {
    throw NumericalError(fmt::format("non-finite reward at step {}: {}", step, result.reward),
                         name);
  }
}

}  // namespace

std::vector<double> parseNumberList(const std::string& text, const std::string& where) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string field =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    values.push_back(parseNumber(field, where));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return values;
}

std::vector<ActionLine> readActionLines(std::istream& in, const std::string& source) {
  std::vector<ActionLine> lines;
  std::string text;
  std::size_t number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.find_first_not_of(" \t") == std::string::npos) continue;
    lines.push_back({number, parseNumberList(text, fmt::format("{} line {}", source, number))});
  }
  return lines;
}

std::string simulateCsv(const SimulationRequest& request) {
  const auto env = Registry::global().make(request.env, request.params);
  const ActionSpace space = env->actionSpace();
  Rng rng(request.seed);
  env->reset(rng);
  if (request.initialState) {
    if (request.initialState->size() != env->stateDim()) {
      throw InputError(
          fmt::format("{} takes {} state variables ({}), got {}", request.env, env->stateDim(),
                      fmt::join(env->stateNames(), ","), request.initialState->size()),
          "--state");
    }
    env->setState(*request.initialState);
  }

  std::string out = "step";
  for (const auto& name : space.names) out += "," + name;
  for (const auto& name : env->stateNames()) out += "," + name;
  out += ",reward,terminated,truncated\n";
  appendRow(out, 0, {}, space.components, env->state(), nullptr);

  Rng policy(deriveSeed(request.seed, 1));
  const std::size_t steps = request.actions ? request.actions->size() : request.randomSteps;
  std::vector<double> action(space.components);
  for (std::size_t t = 0; t < steps; ++t) {
    std::string where = "random policy";
    if (request.actions) {
      const ActionLine& line = (*request.actions)[t];
      where = fmt::format("{} line {}", request.actionsSource, line.line);
      if (line.values.size() != space.components) {
        throw InputError(
            fmt::format("{} takes {} action components ({}), got {}", request.env, space.components,
                        fmt::join(space.names, ","), line.values.size()),
            where);
      }
      std::copy(line.values.begin(), line.values.end(), action.begin());
    } else {
      env->sampleAction(policy, action);
    }
    if (space.continuous()) {
      for (std::size_t i = 0; i < space.components; ++i) {
        action[i] = std::clamp(action[i], space.low[i], space.high[i]);
      }
    }
    StepResult result;
    try {
      result = env->step(action);
    } catch (const InputError& e) {
      throw InputError(e.what(), where);
    }
    requireFinite(*env, result, t + 1, request.env);
    appendRow(out, t + 1, action, space.components, env->state(), &result);
    if (request.stopAtEpisodeEnd && (result.terminated || result.truncated)) break;
  }
  return out;
}

}  // namespace gpfd::env
