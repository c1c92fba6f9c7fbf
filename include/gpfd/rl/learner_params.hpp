// rl: the learners' settings as text `k=v` pairs (command line, configs), so that every field of
// PolicyGradientConfig and LambdaPolicyIterationConfig can be overridden by name.
#pragma once

#include <string>
#include <vector>

#include "gpfd/rl/lambda_policy_iteration.hpp"
#include "gpfd/rl/policy_gradient.hpp"

namespace gpfd::rl {

struct LearnerParamSpec {
  std::string name;
  std::string meaning;
};

// Applies one setting. Returns false when `key` is not a setting of this learner; throws
// InputError (where = "--param <key>") for a value it cannot take.
//   pg:  updates, episodes, max_episode_steps, max_total_steps, discount, baseline (optimal|none),
//        rprop (large|small), delta_min, delta_ini, delta_max, std, learn_std, min_std, max_std,
//        lockstep, bias, normalise
//   lpi: iterations, games, lambda, ridge, step, max_moves, weights (v1,v2,...), bias, normalise
bool applyPolicyGradientParam(PolicyGradientConfig& config, const std::string& key,
                              const std::string& value);
bool applyLambdaPolicyIterationParam(LambdaPolicyIterationConfig& config, const std::string& key,
                                     const std::string& value);

std::vector<LearnerParamSpec> policyGradientParamSpecs();
std::vector<LearnerParamSpec> lambdaPolicyIterationParamSpecs();

}  // namespace gpfd::rl
