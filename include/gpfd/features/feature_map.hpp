// features: the interface through which learners see states, and the trivial maps. Compiled
// genomes (jit) and generic bases (rl's Fourier basis) implement it; learners depend only on it.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace gpfd::features {

// Maps a state of inputDim() values to outputDim() features. Contract: evaluate() is const and
// safe to call from several threads at once; it reads only state[0, inputDim()) and writes only
// features[0, outputDim()).
class FeatureMap {
 public:
  virtual ~FeatureMap() = default;
  virtual std::size_t inputDim() const = 0;
  virtual std::size_t outputDim() const = 0;
  virtual void evaluate(const double* state, double* features) const = 0;
  // n states laid out one after another (n * inputDim() values) to n feature rows
  // (n * outputDim() values). The default calls evaluate() per state.
  virtual void evaluateBatch(const double* states, std::size_t n, double* out) const;
  // `groups` blocks of four states, variable i of lane l of block g at
  // blocks[(g * inputDim() + i) * 4 + l], to blocks of features
  // (out[(g * outputDim() + k) * 4 + l]): the lockstep learners' layout. The default gathers each
  // lane's state and calls evaluate().
  virtual void evaluateLaneBlocks(const double* blocks, std::size_t groups, double* out) const;
  // Whether the features are the state variables themselves, in order (RawFeatureMap): a learner
  // may then start from weights known for the state (AfterstateGame::knownValueWeights).
  virtual bool isIdentity() const { return false; }
  // Whether the features are the same for every state (ZeroFeatureMap): starting weights over
  // the state's own features (AfterstateGame::knownValueWeights, given weights) do not apply.
  virtual bool ignoresState() const { return false; }
};

// The raw state variables as features (the identity).
class RawFeatureMap final : public FeatureMap {
 public:
  explicit RawFeatureMap(std::size_t dim) : dim_(dim) {}
  std::size_t inputDim() const override { return dim_; }
  std::size_t outputDim() const override { return dim_; }
  void evaluate(const double* state, double* features) const override;
  void evaluateLaneBlocks(const double* blocks, std::size_t groups, double* out) const override;
  bool isIdentity() const override { return true; }

 private:
  std::size_t dim_;
};

// One feature that is always 0, whatever the state: what a learner sees when it is to learn
// nothing from the state (run's "no-learning" reference). With its bias a linear learner can still
// learn the best state-independent output; without one it keeps its initial policy.
class ZeroFeatureMap final : public FeatureMap {
 public:
  explicit ZeroFeatureMap(std::size_t inputDim) : inputDim_(inputDim) {}
  std::size_t inputDim() const override { return inputDim_; }
  std::size_t outputDim() const override { return 1; }
  void evaluate(const double* state, double* features) const override;
  bool ignoresState() const override { return true; }

 private:
  std::size_t inputDim_;
};

// The outputs of several maps over the same state, side by side (e.g. discovered + original).
class ConcatFeatureMap final : public FeatureMap {
 public:
  explicit ConcatFeatureMap(std::vector<std::shared_ptr<const FeatureMap>> parts);
  std::size_t inputDim() const override { return inputDim_; }
  std::size_t outputDim() const override { return outputDim_; }
  void evaluate(const double* state, double* features) const override;

 private:
  std::vector<std::shared_ptr<const FeatureMap>> parts_;
  std::size_t inputDim_ = 0;
  std::size_t outputDim_ = 0;
};

}  // namespace gpfd::features
