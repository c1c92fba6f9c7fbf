// env: running one environment on given or random actions and writing the trajectory as CSV
// (`gpfd simulate`).
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"

namespace gpfd::env {

// One action read from text, with the line it came from (for error messages).
struct ActionLine {
  std::size_t line = 0;
  std::vector<double> values;
};

struct SimulationRequest {
  std::string env;
  Params params;
  std::optional<std::vector<double>> initialState;  // Default: reset with the seed.
  std::optional<std::vector<ActionLine>> actions;   // Given actions, or else:
  std::size_t randomSteps = 0;                      // uniformly random actions for this many steps.
  std::uint64_t seed = 0;
  bool stopAtEpisodeEnd = true;             // Stop after a terminated or truncated step.
  std::string actionsSource = "--actions";  // Names the action source in errors.
};

// Runs the request and returns the whole CSV: a header `step,<action names>,<state names>,reward,
// terminated,truncated`, row 0 with the initial state (action, reward and flags empty), then one
// row per step with the action as applied (continuous components clipped to the bounds), the
// state after it, the reward and the flags as 0/1. Numbers in shortest round-trip form. Throws
// InputError, before any output exists, on an unknown environment or parameter, a wrong number of
// state or action components, or an illegal action; NumericalError when a step makes the state
// or the reward non-finite.
std::string simulateCsv(const SimulationRequest& request);

// "v1,v2,..." -> finite numbers; InputError(where) on an empty field or a non-number.
std::vector<double> parseNumberList(const std::string& text, const std::string& where);

// One action per line (blank lines skipped); InputError names `source` and the line.
std::vector<ActionLine> readActionLines(std::istream& in, const std::string& source);

}  // namespace gpfd::env
