#include <fmt/format.h>

#include "gpfd/rl/ars.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

// The built-in learners: one line each.
void addBuiltIns(LearnerRegistry& registry) {
  registry.add(policyGradientLearner());
  registry.add(lambdaPolicyIterationLearner());
  registry.add(arsLearner());
}

}  // namespace

LearnerRegistry& LearnerRegistry::global() { return instance<LearnerRegistry>(addBuiltIns); }

void LearnerRegistry::add(LearnerInfo info) {
  if (!info.make || !info.unsuitable || info.budgetParam.empty()) {
    throw InputError("a learner needs a factory, a suitability check and a budget parameter",
                     "learner registry");
  }
  NamedRegistry::add(std::move(info));
}

std::unique_ptr<Learner> LearnerRegistry::make(const std::string& name,
                                               const Params& params) const {
  const LearnerInfo& entry = info(name);
  checkParamNames(name, paramNames(entry.params), params);
  return entry.make(params);
}

void LearnerRegistry::checkSuitable(const std::string& name, env::Environment& env) const {
  const std::string why = info(name).unsuitable(env);
  if (!why.empty()) {
    throw InputError(fmt::format("learner {} cannot learn on {}: {} (it needs {})", name,
                                 env.name(), why, info(name).needs),
                     "learner " + name);
  }
}

}  // namespace gpfd::rl
