// env: the registry entries of the twins of Gymnasium's classic-control tasks, one per file.
#pragma once

#include "gpfd/env/environment.hpp"

namespace gpfd::env::twin {

EnvInfo cartPoleTwin();
EnvInfo acrobotTwin();
EnvInfo pendulumTwin();
EnvInfo mountainCarTwin();
EnvInfo mountainCarContinuousTwin();

}  // namespace gpfd::env::twin
