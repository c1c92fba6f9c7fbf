// run: typical ranges of the state variables of the control benchmarks, for the Fourier basis
// (which scales states to [0, 1]). Exact where the dynamics bound a variable (angles, Acrobot's
// clipped velocities, cart-pole's failure limits); otherwise ranges seen in episodes under random
// actions (gpfd simulate ENV --policy random), documented in docs/experiments.md.
#pragma once

#include <string>
#include <vector>

#include "gpfd/rl/fourier_basis.hpp"

namespace gpfd::run {

// One range per state variable of `env` (with the given variable names, e.g. for a swimmer of any
// number of segments). Throws InputError for an environment without known ranges.
std::vector<rl::StateRange> typicalStateRanges(const std::string& env,
                                               const std::vector<std::string>& variables);

}  // namespace gpfd::run
