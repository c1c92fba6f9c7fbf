// The registry entry of policy gradient with Rprop: its parameters and how it trains.
#include "config_learner.hpp"
#include "gpfd/rl/policy_gradient.hpp"

namespace gpfd::rl {

const ParamTable<PolicyGradientConfig>& policyGradientParams() {
  static const auto table = [] {
    ParamTable<PolicyGradientConfig> t("pg");
    t.integer(
         "updates", [](auto& c) -> auto& { return c.updates; }, 0, 1000000,
         "policy updates; the curve has updates + 1 rows")
        .integer(
            "episodes", [](auto& c) -> auto& { return c.episodesPerUpdate; }, 1, 1000000,
            "episodes per update (the paper's: 10)")
        .integer(
            "max_episode_steps", [](auto& c) -> auto& { return c.maxEpisodeSteps; }, 1, 1000000000,
            "safety cap on an episode's steps")
        .integer(
            "max_total_steps", [](auto& c) -> auto& { return c.maxTotalSteps; }, 0,
            1000000000000000, "stop once this many steps were played (0: no cap)")
        .real(
            "discount", [](auto& c) -> auto& { return c.discount; }, 0.0, 1.0,
            "discount of the return in the gradient")
        .choice(
            "baseline", [](auto& c) -> auto& { return c.optimalBaseline; },
            std::vector<std::pair<std::string, bool>>{{"optimal", true}, {"none", false}},
            "optimal: Peters & Schaal's per-parameter baseline; none")
        .choice(
            "step", [](auto& c) -> auto& { return c.step; },
            std::vector<std::pair<std::string, StepRule>>{{"rprop", StepRule::Rprop},
                                                          {"natural", StepRule::Natural}},
            "rprop: Rprop on the gradient's signs (the paper's); natural: the episodic natural "
            "actor-critic's step, sized by kl (Peters & Schaal 2008)")
        .real(
            "kl", [](auto& c) -> auto& { return c.naturalKl; }, 1e-12, 100.0,
            "step natural: the mean KL divergence per time step between the policies before and "
            "after an update")
        .custom(
            "rprop", "large | small",
            "Rprop step sizes (min, initial, max): large = (0.01, 0.1, 0.5), small = (0.002, "
            "0.02, 0.1), the paper's two",
            [](PolicyGradientConfig& c, const std::string& text, const std::string& where) {
              if (text != "large" && text != "small") {
                throw InputError("rprop must be one of large | small, got '" + text + "'", where);
              }
              c.rprop = text == "large" ? RpropConfig::paperLarge() : RpropConfig::paperSmall();
            },
            [](const PolicyGradientConfig& c) {
              const auto same = [&](const RpropConfig& r) {
                return c.rprop.deltaMin == r.deltaMin && c.rprop.deltaInitial == r.deltaInitial &&
                       c.rprop.deltaMax == r.deltaMax;
              };
              return std::string(same(RpropConfig::paperLarge())   ? "large"
                                 : same(RpropConfig::paperSmall()) ? "small"
                                                                   : "custom");
            })
        .real(
            "delta_min", [](auto& c) -> auto& { return c.rprop.deltaMin; }, 0.0, 1e6,
            "Rprop minimum step")
        .real(
            "delta_ini", [](auto& c) -> auto& { return c.rprop.deltaInitial; }, 0.0, 1e6,
            "Rprop initial step")
        .real(
            "delta_max", [](auto& c) -> auto& { return c.rprop.deltaMax; }, 0.0, 1e6,
            "Rprop maximum step")
        .real(
            "std", [](auto& c) -> auto& { return c.policy.initialStd; }, 1e-12, 1e6,
            "Gaussian standard deviation in normalised action units")
        .flag(
            "learn_std", [](auto& c) -> auto& { return c.policy.learnStd; },
            "learn the log standard deviation per action dimension")
        .real(
            "min_std", [](auto& c) -> auto& { return c.policy.minStd; }, 1e-12, 1e6,
            "lower bound of a learned standard deviation")
        .real(
            "max_std", [](auto& c) -> auto& { return c.policy.maxStd; }, 1e-12, 1e6,
            "upper bound of a learned standard deviation")
        .flag(
            "greedy_last", [](auto& c) -> auto& { return c.greedyLastRow; },
            "the curve's last row plays the final weights without exploration (the mean action, "
            "the most likely choice)")
        .flag(
            "lockstep", [](auto& c) -> auto& { return c.lockstep; },
            "play an update's episodes side by side (false: one after another, the reference; "
            "the results are the same)");
    declareFeatureParams(
        t, [](auto& c) -> auto& { return c.features; });
    return t;
  }();
  return table;
}

namespace {

// With lockstep, the runs' episodes of each update are played side by side
// (trainPolicyGradientRuns) through the environment's batched form, or lane by lane through copies
// of it (Environment::freshCopy) where it has none, or one after another on this one environment
// where it cannot be copied. Every way gives the same curves.
class PolicyGradientLearner final
    : public ConfigLearner<PolicyGradientConfig, trainPolicyGradient, trainPolicyGradientRuns> {
 public:
  using ConfigLearner::ConfigLearner;

  Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                      const LinearWeights& weights, int episodes, Rng& rng) const override {
    const auto e = evaluatePolicy(env, map, weights, config(), episodes, true, rng);
    return {e.episodes, e.meanReturn, e.steps, e.diverged};
  }
};

}  // namespace

LearnerInfo policyGradientLearner() {
  return {
      "pg",
      "policy gradient with Rprop and the optimal baseline (Girgin & Preux, section 4), or with "
      "natural steps",
      policyGradientParams().specs(),
      [](const Params& p) {
        return std::make_unique<PolicyGradientLearner>(policyGradientParams().read(p));
      },
      "actions that are a box of continuous values or one discrete choice",
      [](env::Environment& env) {
        const env::ActionSpace space = env.actionSpace();
        const bool ok = space.continuous() || (space.components == 1 && space.choices.front() >= 2);
        return std::string(ok ? "" : "its actions are neither a box nor one discrete choice");
      },
      "updates",
      "policy update",
      [](const Params& p) {
        return static_cast<std::int64_t>(policyGradientParams().read(p).episodesPerUpdate);
      }};
}

}  // namespace gpfd::rl
