// rl: what a learning run returns: the performance per update, the final linear weights and the
// counters. Shared by policy gradient and lambda-policy iteration.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gpfd::rl {

// One row of a learning curve: the batch of episodes played with the policy after `update`
// updates (row 0 is the initial policy).
struct CurvePoint {
  int update = 0;
  std::int64_t episodes = 0;  // Cumulative episodes (games) played, this batch included.
  std::int64_t steps = 0;     // Cumulative environment steps (placements), this batch included.
  double meanReturn = 0.0;    // Mean undiscounted return of this batch's episodes.
};

// The learned linear model: `rows` outputs (action dimensions, softmax choices, or 1 value)
// over `cols` features (the bias feature last when present), row-major, followed by `extra`
// parameters (the log standard deviation per action dimension when it is learned).
// Features seen by the weights are (phi - shift) / scale when shift/scale are not empty.
struct LinearWeights {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> values;  // rows * cols + extra values.
  std::vector<double> shift;   // Per raw feature (cols minus the bias), empty when not normalised.
  std::vector<double> scale;   // Same size as shift.
  bool bias = false;
};

struct LearningCurve {
  std::vector<CurvePoint> points;
  LinearWeights weights;  // The weights of the last row's policy.
  std::int64_t episodes = 0;
  std::int64_t steps = 0;
  double wallSeconds = 0.0;
  // A non-finite feature, return, value or weight stopped the run; the curve ends at the last
  // complete row. The fitness layer scores a diverged run worst.
  bool diverged = false;
  std::string divergedReason;

  // The last row's mean return (-inf for an empty curve).
  double finalMeanReturn() const;
};

}  // namespace gpfd::rl
