#include "gpfd/rl/learner_params.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

std::string where(const std::string& key) { return "--param " + key; }

double number(const std::string& key, const std::string& text, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
    throw InputError("'" + text + "' is not a finite number", where(key));
  }
  if (v < lo || v > hi) {
    throw InputError(
        "'" + text + "' is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
        where(key));
  }
  return v;
}

long long integer(const std::string& key, const std::string& text, long long lo, long long hi) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < lo || v > hi) {
    throw InputError("'" + text + "' is not an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]",
                     where(key));
  }
  return v;
}

bool boolean(const std::string& key, const std::string& text) {
  if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
  if (text == "false" || text == "0" || text == "off" || text == "no") return false;
  throw InputError("'" + text + "' is not a boolean (true|false)", where(key));
}

constexpr int kIntMax = std::numeric_limits<int>::max();
constexpr double kHuge = std::numeric_limits<double>::max();

bool applyFeatureParam(FeatureOptions& options, const std::string& key, const std::string& value) {
  if (key == "bias") {
    options.bias = boolean(key, value);
  } else if (key == "normalise") {
    options.normalise = boolean(key, value);
  } else {
    return false;
  }
  return true;
}

}  // namespace

bool applyPolicyGradientParam(PolicyGradientConfig& c, const std::string& key,
                              const std::string& value) {
  if (key == "updates") {
    c.updates = static_cast<int>(integer(key, value, 0, kIntMax - 1));
  } else if (key == "episodes") {
    c.episodesPerUpdate = static_cast<int>(integer(key, value, 1, kIntMax));
  } else if (key == "max_episode_steps") {
    c.maxEpisodeSteps = static_cast<int>(integer(key, value, 1, kIntMax));
  } else if (key == "max_total_steps") {
    c.maxTotalSteps = integer(key, value, 0, std::numeric_limits<long long>::max());
  } else if (key == "discount") {
    c.discount = number(key, value, 0.0, 1.0);
  } else if (key == "baseline") {
    if (value != "optimal" && value != "none") {
      throw InputError("'" + value + "' is not a baseline (optimal|none)", where(key));
    }
    c.optimalBaseline = value == "optimal";
  } else if (key == "rprop") {
    if (value == "large") {
      c.rprop = RpropConfig::paperLarge();
    } else if (value == "small") {
      c.rprop = RpropConfig::paperSmall();
    } else {
      throw InputError("'" + value + "' is not an Rprop preset (large|small)", where(key));
    }
  } else if (key == "delta_min") {
    c.rprop.deltaMin = number(key, value, 0.0, kHuge);
  } else if (key == "delta_ini") {
    c.rprop.deltaInitial = number(key, value, 0.0, kHuge);
  } else if (key == "delta_max") {
    c.rprop.deltaMax = number(key, value, 0.0, kHuge);
  } else if (key == "std") {
    c.policy.initialStd = number(key, value, 1e-12, kHuge);
  } else if (key == "learn_std") {
    c.policy.learnStd = boolean(key, value);
  } else if (key == "min_std") {
    c.policy.minStd = number(key, value, 1e-12, kHuge);
  } else if (key == "max_std") {
    c.policy.maxStd = number(key, value, 1e-12, kHuge);
  } else if (key == "lockstep") {
    c.lockstep = boolean(key, value);
  } else {
    return applyFeatureParam(c.features, key, value);
  }
  return true;
}

bool applyLambdaPolicyIterationParam(LambdaPolicyIterationConfig& c, const std::string& key,
                                     const std::string& value) {
  if (key == "iterations") {
    c.iterations = static_cast<int>(integer(key, value, 0, kIntMax - 1));
  } else if (key == "games") {
    c.gamesPerIteration = static_cast<int>(integer(key, value, 1, kIntMax));
  } else if (key == "lambda") {
    c.lambda = number(key, value, 0.0, 1.0);
  } else if (key == "ridge") {
    c.ridge = number(key, value, 0.0, kHuge);
  } else if (key == "step") {
    c.stepSize = number(key, value, 1e-12, 1.0);
  } else if (key == "max_moves") {
    c.maxMovesPerGame = integer(key, value, 1, std::numeric_limits<long long>::max());
  } else if (key == "game_over") {
    if (value != "avoid" && value != "zero") {
      throw InputError("'" + value + "' is not a game-over choice (avoid|zero)", where(key));
    }
    c.gameOver = value == "avoid" ? LambdaPolicyIterationConfig::GameOverChoice::Avoid
                                  : LambdaPolicyIterationConfig::GameOverChoice::Zero;
  } else if (key == "weights") {
    c.initialWeights.clear();
    std::size_t start = 0;
    while (start <= value.size()) {
      const std::size_t comma = value.find(',', start);
      const std::size_t stop = comma == std::string::npos ? value.size() : comma;
      c.initialWeights.push_back(number(key, value.substr(start, stop - start), -kHuge, kHuge));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  } else {
    return applyFeatureParam(c.features, key, value);
  }
  return true;
}

std::vector<LearnerParamSpec> policyGradientParamSpecs() {
  return {{"updates", "policy updates (default 100); the curve has updates + 1 rows"},
          {"episodes", "episodes per update (default 10, the paper's)"},
          {"max_episode_steps", "safety cap on an episode's steps (default 100000)"},
          {"max_total_steps", "stop once this many steps were played (default 0: no cap)"},
          {"discount", "discount of the return in the gradient (default 1)"},
          {"baseline", "optimal (Peters & Schaal, default) | none"},
          {"rprop", "large (0.01, 0.1, 0.5; default) | small (0.002, 0.02, 0.1)"},
          {"delta_min", "Rprop minimum step"},
          {"delta_ini", "Rprop initial step"},
          {"delta_max", "Rprop maximum step"},
          {"std", "Gaussian std in normalised action units (default 0.5)"},
          {"learn_std", "learn log std per action dimension (default false)"},
          {"min_std", "lower bound of a learned std (default 0.01)"},
          {"max_std", "upper bound of a learned std (default 2)"},
          {"lockstep",
           "play an update's episodes side by side (default true; false: one after another, the "
           "reference; the results are the same)"},
          {"bias", "append a constant feature (default true)"},
          {"normalise", "running mean/std feature normalisation (default false)"}};
}

std::vector<LearnerParamSpec> lambdaPolicyIterationParamSpecs() {
  return {{"iterations", "policy improvements (default 30, the paper's)"},
          {"games", "games per iteration (default 100, the paper's)"},
          {"lambda", "lambda (default 0.6, the paper's)"},
          {"ridge", "ridge term per sample of the least-squares fit (default 1e-6)"},
          {"step", "step size: r <- (1 - step) r + step r_fit (default 1)"},
          {"max_moves", "cap on a game's moves (default 100000)"},
          {"game_over",
           "zero (score a game-ending move as reward + 0; default) | avoid (only when all moves "
           "end the game)"},
          {"weights", "starting weights v1,v2,... over the features (bias last)"},
          {"bias", "append a constant feature (default true)"},
          {"normalise", "running mean/std feature normalisation (default false)"}};
}

}  // namespace gpfd::rl
