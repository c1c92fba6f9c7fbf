// The registry entry of Augmented Random Search: its parameters and how it trains.
#include "config_learner.hpp"
#include "gpfd/rl/ars.hpp"
#include "gpfd/rl/policy_gradient.hpp"

namespace gpfd::rl {

const ParamTable<ArsConfig>& arsParams() {
  static const auto table = [] {
    ParamTable<ArsConfig> t("ars");
    t.integer(
         "updates", [](auto& c) -> auto& { return c.updates; }, 0, 1000000,
         "iterations (weight updates); the curve has updates + 1 rows")
        .integer(
            "n_delta", [](auto& c) -> auto& { return c.directions; }, 1, 100000,
            "N: random directions per iteration, each played + and - (2N episodes)")
        .integer(
            "n_top", [](auto& c) -> auto& { return c.topDirections; }, 0, 100000,
            "b <= n_delta: the directions with the best returns that the step uses (0: all)")
        .real(
            "learning_rate", [](auto& c) -> auto& { return c.learningRate; }, 0.0, 1e6,
            "alpha: the step is alpha / (b sigma_R) sum (r+ - r-) delta")
        .real(
            "delta_std", [](auto& c) -> auto& { return c.deltaStd; }, 1e-12, 1e6,
            "nu: the scale of the perturbations of the weights")
        .flag(
            "zero_policy", [](auto& c) -> auto& { return c.zeroPolicy; },
            "start from zero weights (false: uniform in +-1/sqrt(d), d the features without the "
            "bias)")
        .integer(
            "max_episode_steps", [](auto& c) -> auto& { return c.maxEpisodeSteps; }, 1, 1000000000,
            "safety cap on an episode's steps")
        .integer(
            "max_total_steps", [](auto& c) -> auto& { return c.maxTotalSteps; }, 0,
            1000000000000000, "stop once this many steps were played (0: no cap)")
        .flag(
            "greedy_last", [](auto& c) -> auto& { return c.greedyLastRow; },
            "the curve's last row plays the final weights unperturbed")
        .flag(
            "lockstep", [](auto& c) -> auto& { return c.lockstep; },
            "play an iteration's episodes side by side (false: one after another, the reference; "
            "the results are the same)")
        .rule(
            "n_top", [](const ArsConfig& c) { return c.topDirections <= c.directions; },
            "n_top must be at most n_delta");
    declareFeatureParams(
        t, [](auto& c) -> auto& { return c.features; });
    return t;
  }();
  return table;
}

namespace {

class ArsLearner final : public ConfigLearner<ArsConfig, trainArs, trainArsRuns> {
 public:
  using ConfigLearner::ConfigLearner;

  // The trained weights played as ARS plays them (policy gradient's greedy player: the arg-max,
  // or the mean action, which the environment clips).
  Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                      const LinearWeights& weights, int episodes, Rng& rng) const override {
    PolicyGradientConfig player;
    player.maxEpisodeSteps = config().maxEpisodeSteps;
    player.features = config().features;
    player.lockstep = config().lockstep;
    const auto e = evaluatePolicy(env, map, weights, player, episodes, true, rng);
    return {e.episodes, e.meanReturn, e.steps, e.diverged};
  }
};

}  // namespace

LearnerInfo arsLearner() {
  return {"ars",
          "Augmented Random Search (Mania, Guy & Recht 2018): a deterministic linear policy "
          "improved along random directions of its weights (V1; V2 with normalise)",
          arsParams().specs(),
          [](const Params& p) { return std::make_unique<ArsLearner>(arsParams().read(p)); },
          "actions that are a box of continuous values or one discrete choice",
          [](env::Environment& env) {
            const env::ActionSpace space = env.actionSpace();
            const bool ok =
                space.continuous() || (space.components == 1 && space.choices.front() >= 2);
            return std::string(ok ? "" : "its actions are neither a box nor one discrete choice");
          },
          "updates", "ARS iteration",
          // Each direction played + and - (the greedy last row as many episodes).
          [](const Params& p) {
            return 2 * static_cast<std::int64_t>(arsParams().read(p).directions);
          }};
}

}  // namespace gpfd::rl
