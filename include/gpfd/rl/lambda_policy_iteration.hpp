// rl: approximate lambda-policy iteration (Bertsekas & Ioffe 1996, "Temporal differences-based
// policy iteration and applications in neuro-dynamic programming"; Bertsekas & Tsitsiklis,
// Neuro-Dynamic Programming, 1996, section 8.3) with a value linear in afterstate features.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/afterstate_problem.hpp"
#include "gpfd/rl/features.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

struct LambdaPolicyIterationConfig {
  int iterations = 30;          // Policy improvements; the curve has iterations + 1 rows.
  int gamesPerIteration = 100;  // Paper: 100.
  double lambda = 0.6;          // Paper: 0.6.
  // Ridge term per sample: r minimises mean_t (phi_t . r - y_t)^2 + ridge |r|^2.
  double ridge = 1e-6;
  double stepSize = 1.0;  // r <- (1 - step) r + step r_fit; 1 replaces r.
  // Moves per game at most (good policies on large boards play very long games). A capped game
  // is not terminal: its last afterstate keeps its own value as target.
  std::int64_t maxMovesPerGame = 100000;
  // How the greedy choice scores a move that ends the game. Zero (default, docs/benchmarks.md):
  // reward + 0, literally. Avoid: such a move is taken
  // only when every move ends the game (a linear J can be negative, e.g. the Bertsekas-Ioffe
  // start is <= 0 everywhere, and scoring game over as 0 would then make the policy end games on
  // purpose). Either way the lambda-returns use J(game over) = 0.
  enum class GameOverChoice { Avoid, Zero };
  GameOverChoice gameOver = GameOverChoice::Zero;
  // Starting weights over the pipeline's features (bias last); empty: all zero.
  std::vector<double> initialWeights;
  FeatureOptions features{.bias = true, .normalise = false};
  // Called with each row of the curve as soon as it is complete (progress output); may be empty.
  std::function<void(const CurvePoint&)> onPoint;
};

// Plays greedily w.r.t. reward + J(afterstate) (J = 0 for a move that ends the game), fits J to
// the lambda-returns by least squares after each batch of games. Row i of the curve is the batch
// played with the weights after i fits; its mean return is the mean reward (rows) per game.
// InputError when the map's input does not match the problem or initialWeights has a wrong size.
LearningCurve trainLambdaPolicyIteration(AfterstateProblem& problem,
                                         const features::FeatureMap& map,
                                         const LambdaPolicyIterationConfig& config, Rng& rng);

// Greedy play with fixed weights: mean reward per game over `games` games.
struct GreedyPlayResult {
  int games = 0;
  double meanReturn = 0.0;
  std::int64_t moves = 0;
  bool diverged = false;
};
GreedyPlayResult playGreedy(AfterstateProblem& problem, const features::FeatureMap& map,
                            const LinearWeights& weights, const LambdaPolicyIterationConfig& config,
                            int games, Rng& rng);

// Lambda-returns of one game, undiscounted: with values[t] = J(b_t) for the afterstates
// b_0..b_{T-1} and rewards[t] the reward between b_t and b_{t+1},
//   d_t = rewards[t] + J(b_{t+1}) - J(b_t), with J(b_T) = 0 when `terminal`;
//   when not terminal (capped), d_{T-1} = 0;
//   targets[t] = J(b_t) + sum_{s >= t} lambda^{s-t} d_s.
// All spans have size T.
void lambdaReturns(std::span<const double> values, std::span<const double> rewards, bool terminal,
                   double lambda, std::span<double> targets);

// Accumulates the normal equations of a ridge least-squares fit, a block of rows at a time.
// The registry entry "lpi": every field of LambdaPolicyIterationConfig as a parameter, plus
// `start` (zero, or the environment's known value weights over its raw state), on environments
// that offer an afterstate game.
LearnerInfo lambdaPolicyIterationLearner();

class LeastSquaresAccumulator {
 public:
  explicit LeastSquaresAccumulator(Eigen::Index dim);
  // rows x dim() features (row-major) and their targets.
  void add(const double* features, const double* targets, Eigen::Index rows);
  Eigen::Index samples() const { return samples_; }
  // argmin_r (1/n) sum_t (phi_t . r - y_t)^2 + ridge |r|^2; false when the solve is not finite.
  bool solve(double ridge, Eigen::VectorXd& out) const;
  void clear();

 private:
  Eigen::MatrixXd gram_;  // Lower triangle of sum phi phi^T.
  Eigen::VectorXd rhs_;   // sum phi y.
  Eigen::Index samples_ = 0;
};

}  // namespace gpfd::rl
