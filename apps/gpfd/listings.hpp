// The registries described for people: `gpfd envs`, `gpfd learners` and the --help of the
// commands that take `--param k=v`. Everything comes from the registries' declarations, plug-ins
// included.
#pragma once

#include <string>

namespace gpfd::app {

// Every environment: description, state variables, actions, default learner, whether typical
// state ranges are known, and its parameters (default, range, meaning).
std::string describeEnvironments();
// Every learner: description, what it needs from an environment, its budget parameter, and its
// parameters (default, range, meaning).
std::string describeLearners();
// One line per learner: "NAME: its parameter names" (for --help footers).
std::string learnerParamSummary();

}  // namespace gpfd::app
