#include "gpfd/rl/lambda_policy_iteration.hpp"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <limits>

#include "gpfd/util/error.hpp"

namespace gpfd::rl {

void lambdaReturns(std::span<const double> values, std::span<const double> rewards, bool terminal,
                   double lambda, std::span<double> targets) {
  const std::size_t n = values.size();
  if (n == 0) return;
  // Backwards: D_t = d_t + lambda D_{t+1}, targets = J(b_t) + D_t.
  double tail = terminal ? rewards[n - 1] - values[n - 1] : 0.0;
  targets[n - 1] = values[n - 1] + tail;
  for (std::size_t t = n - 1; t-- > 0;) {
    const double d = rewards[t] + values[t + 1] - values[t];
    tail = d + lambda * tail;
    targets[t] = values[t] + tail;
  }
}

LeastSquaresAccumulator::LeastSquaresAccumulator(Eigen::Index dim)
    : gram_(Eigen::MatrixXd::Zero(dim, dim)), rhs_(Eigen::VectorXd::Zero(dim)) {}

void LeastSquaresAccumulator::add(const double* features, const double* targets,
                                  Eigen::Index rows) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> phi(features, rows, gram_.cols());
  const Eigen::Map<const Eigen::VectorXd> y(targets, rows);
  gram_.selfadjointView<Eigen::Lower>().rankUpdate(phi.transpose());
  rhs_.noalias() += phi.transpose() * y;
  samples_ += rows;
}

bool LeastSquaresAccumulator::solve(double ridge, Eigen::VectorXd& out) const {
  if (samples_ == 0) return false;
  const double n = static_cast<double>(samples_);
  Eigen::MatrixXd a = gram_.selfadjointView<Eigen::Lower>();
  a.diagonal().array() += ridge * n;
  out = a.ldlt().solve(rhs_);
  return out.allFinite();
}

void LeastSquaresAccumulator::clear() {
  gram_.setZero();
  rhs_.setZero();
  samples_ = 0;
}

namespace {

void checkInputs(const AfterstateProblem& problem, const features::FeatureMap& map,
                 const LambdaPolicyIterationConfig& config, std::size_t dim) {
  if (map.inputDim() != problem.stateDim()) {
    throw InputError("the feature map reads " + std::to_string(map.inputDim()) +
                         " state variables but the afterstates have " +
                         std::to_string(problem.stateDim()),
                     "features");
  }
  if (!config.initialWeights.empty() && config.initialWeights.size() != dim) {
    throw InputError("the initial value weights have " +
                         std::to_string(config.initialWeights.size()) + " values, the features " +
                         std::to_string(dim),
                     "initial weights");
  }
  if (config.iterations < 0 || config.gamesPerIteration < 1 || config.maxMovesPerGame < 1 ||
      !(config.lambda >= 0.0 && config.lambda <= 1.0) || !(config.ridge >= 0.0) ||
      !(config.stepSize > 0.0 && config.stepSize <= 1.0)) {
    throw InputError(
        "lambda-PI needs iterations >= 0, games >= 1, max moves >= 1, lambda in [0, 1], "
        "ridge >= 0, step size in (0, 1]",
        "lambda-PI");
  }
}

// One game's trajectory, grown as needed and reused across games.
struct Trajectory {
  std::vector<double> phi;  // moves x dim, row-major.
  std::vector<double> values, rewards, targets;
  std::size_t moves = 0;
};

struct GameOutcome {
  double total = 0.0;  // Sum of rewards (rows removed).
  std::int64_t moves = 0;
  bool terminal = false;
  bool ok = true;
};

// Plays one greedy game with `weights`; records the afterstates into `trajectory` when given.
GameOutcome playGame(AfterstateProblem& problem, FeaturePipeline& features,
                     const Eigen::VectorXd& weights, std::int64_t maxMoves, bool avoidEnding,
                     Rng& rng, std::vector<double>& candidatePhi, Trajectory* trajectory) {
  GameOutcome outcome;
  const std::size_t dim = features.dim();
  if (trajectory) trajectory->moves = 0;
  problem.reset(rng);
  while (outcome.moves < maxMoves) {
    const AfterstateView view = problem.candidates();
    if (view.count == 0) {
      outcome.terminal = true;
      break;
    }
    if (candidatePhi.size() < view.count * dim) candidatePhi.resize(view.count * dim);
    if (!features.evaluateBatch(view.states, view.count, candidatePhi.data())) {
      outcome.ok = false;
      return outcome;
    }
    std::size_t best = 0;
    double bestScore = -std::numeric_limits<double>::infinity();
    double bestValue = 0.0;
    for (std::size_t c = 0; c < view.count; ++c) {
      const double value = view.ends[c]
                               ? 0.0
                               : Eigen::Map<const Eigen::VectorXd>(candidatePhi.data() + c * dim,
                                                                   static_cast<Eigen::Index>(dim))
                                     .dot(weights);
      double score = view.rewards[c] + value;
      if (!std::isfinite(score)) {
        outcome.ok = false;
        return outcome;
      }
      // Avoid: ending moves rank below every other, in their own order among themselves.
      if (avoidEnding && view.ends[c]) score = view.rewards[c] - 1e300;
      if (score > bestScore) {
        bestScore = score;
        best = c;
        bestValue = value;
      }
    }
    const double reward = view.rewards[best];
    outcome.total += reward;
    ++outcome.moves;
    if (trajectory) {
      Trajectory& tr = *trajectory;
      // This move's reward is the reward between the previous afterstate and this one.
      if (tr.moves > 0) tr.rewards[tr.moves - 1] = reward;
      if (!view.ends[best]) {
        if (tr.values.size() <= tr.moves) {
          const std::size_t grown = std::max<std::size_t>(64, 2 * tr.values.size());
          tr.values.resize(grown);
          tr.rewards.resize(grown);
          tr.targets.resize(grown);
          tr.phi.resize(grown * dim);
        }
        std::copy(candidatePhi.begin() + static_cast<std::ptrdiff_t>(best * dim),
                  candidatePhi.begin() + static_cast<std::ptrdiff_t>((best + 1) * dim),
                  tr.phi.begin() + static_cast<std::ptrdiff_t>(tr.moves * dim));
        tr.values[tr.moves] = bestValue;
        tr.rewards[tr.moves] = 0.0;
        ++tr.moves;
      }
    }
    if (view.ends[best]) {
      outcome.terminal = true;
      break;
    }
    problem.choose(best, rng);
  }
  return outcome;
}

}  // namespace

LearningCurve trainLambdaPolicyIteration(AfterstateProblem& problem,
                                         const features::FeatureMap& map,
                                         const LambdaPolicyIterationConfig& config, Rng& rng) {
  const auto start = std::chrono::steady_clock::now();
  FeaturePipeline features(map, config.features);
  const std::size_t dim = features.dim();
  checkInputs(problem, map, config, dim);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dim));
  for (std::size_t j = 0; j < config.initialWeights.size(); ++j) {
    weights[static_cast<Eigen::Index>(j)] = config.initialWeights[j];
  }
  const bool avoid = config.gameOver == LambdaPolicyIterationConfig::GameOverChoice::Avoid;
  LeastSquaresAccumulator fit(static_cast<Eigen::Index>(dim));
  Eigen::VectorXd fitted;
  Trajectory trajectory;
  std::vector<double> candidatePhi;

  LearningCurve curve;
  auto exportWeights = [&] {
    curve.weights.rows = 1;
    curve.weights.cols = dim;
    curve.weights.values.assign(weights.data(), weights.data() + weights.size());
    features.exportTo(curve.weights);
  };
  for (int iteration = 0; iteration <= config.iterations; ++iteration) {
    const bool fitting = iteration < config.iterations;
    fit.clear();
    double sum = 0.0;
    for (int g = 0; g < config.gamesPerIteration; ++g) {
      const GameOutcome outcome =
          playGame(problem, features, weights, config.maxMovesPerGame, avoid, rng, candidatePhi,
                   fitting ? &trajectory : nullptr);
      ++curve.episodes;
      curve.steps += outcome.moves;
      if (!outcome.ok || !std::isfinite(outcome.total)) {
        curve.diverged = true;
        curve.divergedReason = "non-finite feature, reward or value";
        break;
      }
      sum += outcome.total;
      if (fitting && trajectory.moves > 0) {
        const std::size_t n = trajectory.moves;
        lambdaReturns({trajectory.values.data(), n}, {trajectory.rewards.data(), n},
                      outcome.terminal, config.lambda, {trajectory.targets.data(), n});
        fit.add(trajectory.phi.data(), trajectory.targets.data(), static_cast<Eigen::Index>(n));
      }
    }
    if (curve.diverged) break;
    curve.points.push_back({iteration, curve.episodes, curve.steps,
                            sum / static_cast<double>(config.gamesPerIteration)});
    exportWeights();
    if (config.onPoint) config.onPoint(curve.points.back());
    if (!fitting || fit.samples() == 0) {
      if (fitting) continue;  // Every game ended at once: nothing to fit, keep the weights.
      break;
    }
    if (!fit.solve(config.ridge, fitted)) {
      curve.diverged = true;
      curve.divergedReason = "non-finite least-squares solution";
      break;
    }
    weights = (1.0 - config.stepSize) * weights + config.stepSize * fitted;
    features.refresh(weights.data(), 1);
  }
  curve.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

GreedyPlayResult playGreedy(AfterstateProblem& problem, const features::FeatureMap& map,
                            const LinearWeights& weights, const LambdaPolicyIterationConfig& config,
                            int games, Rng& rng) {
  FeaturePipeline features(map, config.features);
  const std::size_t dim = features.dim();
  LambdaPolicyIterationConfig checked = config;
  checked.initialWeights = weights.values;
  checkInputs(problem, map, checked, dim);
  if (weights.values.size() != dim) {
    throw InputError("the value weights have " + std::to_string(weights.values.size()) +
                         " values, the features " + std::to_string(dim),
                     "weights");
  }
  features.importFrom(weights);
  const Eigen::Map<const Eigen::VectorXd> w(weights.values.data(), static_cast<Eigen::Index>(dim));
  const Eigen::VectorXd r = w;
  std::vector<double> candidatePhi;
  const bool avoid = config.gameOver == LambdaPolicyIterationConfig::GameOverChoice::Avoid;
  GreedyPlayResult result;
  double sum = 0.0;
  for (int g = 0; g < games; ++g) {
    const GameOutcome outcome =
        playGame(problem, features, r, config.maxMovesPerGame, avoid, rng, candidatePhi, nullptr);
    result.moves += outcome.moves;
    if (!outcome.ok) {
      result.diverged = true;
      break;
    }
    ++result.games;
    sum += outcome.total;
  }
  if (result.games > 0) result.meanReturn = sum / result.games;
  return result;
}

}  // namespace gpfd::rl
