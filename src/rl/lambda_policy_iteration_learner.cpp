// The registry entry of approximate lambda-policy iteration: its parameters and how it trains.
#include "gpfd/rl/game_afterstates.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"

namespace gpfd::rl {
namespace {

struct Settings {
  LambdaPolicyIterationConfig algorithm;
  // Start from the environment's known value weights (AfterstateGame::knownValueWeights) instead
  // of zero; only with the raw state as features.
  bool knownStart = false;
};

const ParamTable<Settings>& table() {
  using GameOver = LambdaPolicyIterationConfig::GameOverChoice;
  static const auto table = [] {
    ParamTable<Settings> t("lpi");
    t.integer(
         "iterations", [](auto& c) -> auto& { return c.algorithm.iterations; }, 0, 1000000,
         "policy improvements (the paper's: 30); the curve has iterations + 1 rows")
        .integer(
            "games", [](auto& c) -> auto& { return c.algorithm.gamesPerIteration; }, 1, 1000000,
            "games per iteration (the paper's: 100)")
        .real(
            "lambda", [](auto& c) -> auto& { return c.algorithm.lambda; }, 0.0, 1.0,
            "lambda of the lambda-returns (the paper's: 0.6)")
        .real(
            "ridge", [](auto& c) -> auto& { return c.algorithm.ridge; }, 0.0, 1e6,
            "ridge term per sample of the least-squares fit")
        .real(
            "step", [](auto& c) -> auto& { return c.algorithm.stepSize; }, 1e-12, 1.0,
            "step size: r <- (1 - step) r + step r_fit")
        .integer(
            "max_moves", [](auto& c) -> auto& { return c.algorithm.maxMovesPerGame; }, 1,
            1000000000, "cap on a game's moves (a capped game bootstraps its last afterstate)")
        .choice(
            "game_over", [](auto& c) -> auto& { return c.algorithm.gameOver; },
            std::vector<std::pair<std::string, GameOver>>{{"zero", GameOver::Zero},
                                                          {"avoid", GameOver::Avoid}},
            "zero: a game-ending move scores reward + 0; avoid: taken only when every move ends "
            "the game")
        .custom(
            "weights", "v1,v2,... or empty",
            "starting weights over the features (bias last); empty: zero",
            [](Settings& c, const std::string& text, const std::string& where) {
              c.algorithm.initialWeights.clear();
              for (std::size_t start = 0; !text.empty() && start <= text.size();) {
                const std::size_t comma = std::min(text.find(',', start), text.size());
                c.algorithm.initialWeights.push_back(
                    parseNumber(text.substr(start, comma - start), where));
                start = comma + 1;
              }
            },
            [](const Settings& c) {
              std::string text;
              for (double w : c.algorithm.initialWeights) {
                // Appended piece by piece: "literal" + temporary string makes GCC 12 report a
                // false -Wrestrict inside std::string::insert.
                if (!text.empty()) text += ',';
                text += numberText(w);
              }
              return text;
            })
        .choice(
            "start", [](auto& c) -> auto& { return c.knownStart; },
            std::vector<std::pair<std::string, bool>>{{"zero", false}, {"known", true}},
            "zero; known: the environment's known value weights over its raw state (tetris with "
            "state=bertsekas: Bertsekas & Ioffe's), with the raw state as features only")
        .rule(
            "start",
            [](const Settings& c) { return !c.knownStart || c.algorithm.initialWeights.empty(); },
            "give either start=known or weights, not both");
    declareFeatureParams(
        t, [](auto& c) -> auto& { return c.algorithm.features; });
    return t;
  }();
  return table;
}

class LambdaPolicyIterationLearner final : public Learner {
 public:
  explicit LambdaPolicyIterationLearner(Settings settings) : settings_(std::move(settings)) {}

  LearningCurve train(env::Environment& env, const features::FeatureMap& map, Rng& rng,
                      const PointCallback& onPoint) const override {
    LambdaPolicyIterationConfig config = settings_.algorithm;
    config.onPoint = onPoint;
    env::AfterstateGame& game = gameOf(env);
    // A map that ignores the state (the no-learning reference) starts from zero: starting
    // weights are over the state's own features.
    if (map.ignoresState()) {
      config.initialWeights.clear();
    } else if (settings_.knownStart) {
      config.initialWeights = knownStart(env, game, map);
    }
    GameAfterstateProblem problem(env, game);
    return trainLambdaPolicyIteration(problem, map, config, rng);
  }

  Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                      const LinearWeights& weights, int episodes, Rng& rng) const override {
    GameAfterstateProblem problem(env, gameOf(env));
    const auto e = playGreedy(problem, map, weights, settings_.algorithm, episodes, rng);
    return {e.games, e.meanReturn, e.moves, e.diverged};
  }

 private:
  static env::AfterstateGame& gameOf(env::Environment& env) {
    env::AfterstateGame* game = env.afterstateGame();
    if (game == nullptr) {
      throw InputError(
          "lambda-policy iteration needs an afterstate game; " + env.name() + " is not one",
          "learner lpi");
    }
    return *game;
  }

  // The environment's known weights, followed by 0 for the bias feature.
  std::vector<double> knownStart(const env::Environment& env, const env::AfterstateGame& game,
                                 const features::FeatureMap& map) const {
    std::vector<double> weights = game.knownValueWeights();
    if (weights.empty()) {
      throw InputError(env.name() + " knows no value weights with these parameters", "lpi.start");
    }
    if (!map.isIdentity()) {
      throw InputError("start=known needs the raw state variables as the features", "lpi.start");
    }
    if (settings_.algorithm.features.bias) weights.push_back(0.0);
    return weights;
  }

  Settings settings_;
};

}  // namespace

LearnerInfo lambdaPolicyIterationLearner() {
  return {"lpi",
          "approximate lambda-policy iteration over afterstates (Bertsekas & Ioffe 1996)",
          table().specs(),
          [](const Params& p) {
            return std::make_unique<LambdaPolicyIterationLearner>(table().read(p));
          },
          "an afterstate game (Environment::afterstateGame), e.g. tetris",
          [](env::Environment& env) {
            return std::string(env.afterstateGame() ? "" : "it is not an afterstate game");
          },
          "iterations",
          "lambda-PI iteration",
          [](const Params& p) {
            return static_cast<std::int64_t>(table().read(p).algorithm.gamesPerIteration);
          }};
}

}  // namespace gpfd::rl
