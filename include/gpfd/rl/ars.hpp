// rl: Augmented Random Search (Mania, Guy & Recht 2018, "Simple random search provides a
// competitive approach to reinforcement learning", NeurIPS; Algorithm 2, versions V1-t and V2-t):
// a deterministic linear policy (with a bias feature by default) improved by finite differences
// of returns along random directions of its weights. Each iteration draws N Gaussian directions
// delta_k, plays theta + nu delta_k and theta - nu delta_k once each, keeps the b directions
// whose better return is highest and steps
//   theta += alpha / (b sigma_R) * sum_k (r+_k - r-_k) delta_k,
// sigma_R the standard deviation of the 2b returns kept. V2 (normalise = true) acts on
// (phi - mu) / sigma, the mean and standard deviation of every raw feature seen in the
// iterations before (row 0: mu = 0, sigma = 1).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/features.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/util/params.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

// Defaults are sb3-contrib's ARS where it has the parameter (n_delta 8, n_top = n_delta,
// learning_rate 0.02, delta_std 0.05, zero_policy).
struct ArsConfig {
  int updates = 100;           // Iterations (weight updates); the curve has updates + 1 rows.
  int directions = 8;          // N, sampled directions per iteration (2N episodes).
  int topDirections = 0;       // b <= N, directions used by the step; 0: all N.
  double learningRate = 0.02;  // alpha.
  double deltaStd = 0.05;      // nu, the scale of the perturbations.
  // Start from zero weights; false: each weight uniform in [-1/sqrt(d), 1/sqrt(d)], d the
  // number of features without the bias (PyTorch's default for a linear layer of fan-in d, what
  // sb3-contrib then starts from).
  bool zeroPolicy = true;
  int maxEpisodeSteps = 100000;    // A safety cap on top of the environment's own time limit.
  std::int64_t maxTotalSteps = 0;  // Stop after the row in which the steps reach this (0: none).
  bool greedyLastRow = false;      // The last row plays the final weights unperturbed.
  bool lockstep = true;            // Play an iteration's episodes side by side (false: in turn).
  FeatureOptions features;         // bias; normalise = V2.
  PointCallback onPoint;           // Each row as soon as it is complete; may be empty.
  RunPointCallback onRunPoint;     // The same with the run's index (trainArsRuns).

  // N's b: topDirections, or N when 0.
  int top() const { return topDirections > 0 ? topDirections : directions; }
};

// The learner's parameters ("ars": gpfd learners lists them).
const ParamTable<ArsConfig>& arsParams();

// The step of one iteration (Algorithm 2, line 7) on `theta`: the `top` directions whose
// max(plus[k], minus[k]) is highest (ties: the lower k first), sigma_R the population standard
// deviation of their 2 * top returns; no step when sigma_R is 0 (then every difference is 0).
void arsStep(std::span<const double> plus, std::span<const double> minus,
             std::span<const Eigen::VectorXd> deltas, int top, double learningRate,
             Eigen::VectorXd& theta);

// One run from the weights zero_policy says, drawing one value from `rng` (the run's seed).
// Row u of the curve is the mean return of the 2N episodes played around the weights after u
// updates (with greedyLastRow the last row plays the weights themselves, 2N episodes). Direction
// k of iteration u plays both its episodes from the start state of its own stream
// deriveSeed(seed, u, k) (common random numbers). A non-finite state, feature, reward or weight
// marks the curve diverged and ends it; bad settings throw InputError.
LearningCurve trainArs(env::Environment& env, const features::FeatureMap& map,
                       const ArsConfig& config, Rng& rng);

// Several independent runs: run k gives exactly trainArs(env, map, config, rngs[k]). With
// config.lockstep every run's episodes of an iteration share the lanes (runs x 2N).
std::vector<LearningCurve> trainArsRuns(env::Environment& env, const features::FeatureMap& map,
                                        const ArsConfig& config, std::span<Rng> rngs);

// The registry entry "ars", on environments whose actions are a box or one discrete choice.
LearnerInfo arsLearner();

}  // namespace gpfd::rl
