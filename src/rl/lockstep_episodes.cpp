// rl: the lockstep player (episode_players.hpp): the episodes of one call advance together, one
// step of every running episode at a time. Per step: the states (structure of arrays, one lane
// per episode) go through the feature map's lane-block evaluation (the JIT's AVX2 kernel), the
// features are checked and normalised, the policy's outputs, Gaussian draws (each episode's own
// stream, util/rng_lanes.hpp), actions and likelihood gradients are computed four lanes at a time
// (lockstep_kernels.hpp), and the batched environment steps every lane. An episode that ends frees
// its lane: the last running lane moves into it, so the running lanes stay dense. Every lane
// performs the operations of the sequential player in the same order, so both give the same bits.
// Lanes may belong to different learning runs (the trials of a fitness evaluation): each lane
// carries its run's weights, standard deviations and normalisation.
#include <algorithm>
#include <cmath>

#include "episode_players.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/util/rng_lanes.hpp"
#include "lockstep_kernels.hpp"

namespace gpfd::rl::episodes {
namespace {

class LockstepPlayer final : public Player {
 public:
  LockstepPlayer(const Setup& setup, std::unique_ptr<env::BatchEnvironment> batch,
                 std::size_t capacity)
      : s_(setup),
        batch_(std::move(batch)),
        capacity_(capacity),
        stride_((capacity + 3) / 4 * 4),
        stateDim_(batch_->stateDim()),
        rawDim_(setup.runs.front().features->rawDim()),
        dim_(setup.runs.front().features->dim()),
        outputs_(setup.runs.front().policy->outputs()),
        parameters_(static_cast<std::size_t>(setup.runs.front().policy->parameterCount())),
        normalise_(setup.runs.front().features->options().normalise),
        store_(0, stride_, stateDim_, batch_->actionComponents()),
        io_(store_.buffers()),
        blocks_(stride_ * std::max(stateDim_, std::size_t{1}), 0.0),
        raw_(stride_ * std::max(rawDim_, std::size_t{1}), 0.0),
        phi_(dim_ * stride_, 1.0),  // The bias row, if any, stays 1.
        mu_(outputs_ * stride_, 0.0),
        eps_(stride_, 0.0),
        coefficient_(stride_, 0.0),
        choiceCoefficient_(outputs_, 0.0),
        logits_(outputs_, 0.0),
        eligibility_(parameters_ * stride_, 0.0),
        choiceRows_(outputs_ * stride_, 0.0),
        weights_(outputs_ * dim_ * stride_, 0.0),
        sd_(outputs_ * stride_, 1.0),
        shift_(normalise_ ? rawDim_ * stride_ : 0, 0.0),
        scale_(normalise_ ? rawDim_ * stride_ : 0, 1.0),
        weight_(stride_, 1.0),
        failed_(stride_, 0),
        broken_(stride_, 0),
        episode_(stride_, 0),
        run_(stride_, 0),
        rngs_(stride_),
        starts_(stride_) {
    io_.scratchTail = true;
    lanes_.stride = stride_;
    lanes_.avx2 = batch_->usesAvx2();
  }

  std::size_t capacity() const override { return capacity_; }

  void play(std::span<const Task> tasks, bool sampling, Records& out) override {
    const std::size_t n = tasks.size();
    prepare(out, n, static_cast<Eigen::Index>(parameters_), rawDim_, sampling, normalise_);
    if (sampling) std::fill(eligibility_.begin(), eligibility_.end(), 0.0);
    for (std::size_t e = 0; e < n; ++e) starts_[e] = Rng(tasks[e].seed);
    batch_->resetAll(std::span(starts_.data(), n), io_);
    for (std::size_t e = 0; e < n; ++e) {
      rngs_.set(e, starts_[e]);
      episode_[e] = e;
      weight_[e] = 1.0;
      takeRun(e, tasks[e].run);
    }
    std::size_t active = n;
    while (active > 0) {
      io_.lanes = active;
      lanes_.lanes = (active + 3) / 4 * 4;
      features(active, normalise_ ? &out.moments : nullptr);
      lockstep::linearOutputs(lanes_, weights_.data(), outputs_, dim_, phi_.data(), mu_.data());
      lockstep::flagNotFinite(lanes_, mu_.data(), outputs_, failed_.data());
      if (sampling) {
        sample(active);
      } else {
        greedy(active);
      }
      batch_->step(io_);
      active = finish(active, sampling, out);
    }
  }

 private:
  // phi (dim_ rows of stride_) for lanes [0, active), as FeaturePipeline::transform makes them;
  // marks the lanes whose features are not finite. The map evaluates whole blocks of four lanes
  // (the JIT's lane-block kernel; the lanes beyond `active` hold old states and are ignored).
  void features(std::size_t active, std::vector<FeatureMoments>* moments) {
    lockstep::toLaneBlocks(lanes_, store_.state.data(), stateDim_, blocks_.data());
    s_.map->evaluateLaneBlocks(blocks_.data(), lanes_.lanes / 4, raw_.data());
    lockstep::fromLaneBlocks(lanes_, raw_.data(), rawDim_, phi_.data());
    lockstep::checkAndNormalise(lanes_, phi_.data(), rawDim_, normalise_ ? shift_.data() : nullptr,
                                scale_.data(), failed_.data());
    if (moments == nullptr) return;
    for (std::size_t l = 0; l < active; ++l) {
      // Lane l's raw features: feature j at [(l / 4 * rawDim_ + j) * 4 + l % 4].
      if (!failed_[l]) (*moments)[episode_[l]].add(raw_.data() + l / 4 * 4 * rawDim_ + l % 4, 4);
    }
  }

  // LinearPolicy::sample, lane by lane.
  void sample(std::size_t active) {
    const LinearPolicy& policy = *s_.runs.front().policy;  // For the shape and the action box.
    if (policy.continuous()) {
      const std::size_t weightCount = outputs_ * dim_;
      const bool learnStd = parameters_ > weightCount;
      for (std::size_t i = 0; i < outputs_; ++i) {
        // With AVX2 the lanes up to the group of four draw too: the lanes beyond `active` hold
        // no episode (a lane that starts one gets its stream anew), so their draws are unused.
        rngs_.standardNormal(lanes_.avx2 ? lanes_.lanes : active, eps_.data(), lanes_.avx2);
        lockstep::gaussianActions(
            lanes_, mu_.data() + i * stride_, eps_.data(), sd_.data() + i * stride_,
            policy.centre(i), policy.halfWidth(i), store_.action.data() + i * stride_,
            coefficient_.data(),
            learnStd ? eligibility_.data() + (weightCount + i) * stride_ : nullptr);
        lockstep::addGradient(lanes_, eligibility_.data(), i * dim_, coefficient_.data(),
                              phi_.data(), dim_);
      }
      for (std::size_t l = 0; l < active; ++l) {
        if (!failed_[l]) continue;
        for (std::size_t i = 0; i < outputs_; ++i) store_.action[i * stride_ + l] = 0.0;
      }
      return;
    }
    // Each lane's choice and coefficients; then the gradients of all lanes, row by row (each
    // element gets the one product it gets lane by lane; a failed lane's episode ends here, its
    // eligibility unused, as on the continuous path).
    for (std::size_t l = 0; l < active; ++l) {
      if (failed_[l]) {
        store_.action[l] = 0.0;
        for (std::size_t k = 0; k < outputs_; ++k) choiceRows_[k * stride_ + l] = 0.0;
        continue;
      }
      for (std::size_t k = 0; k < outputs_; ++k) logits_[k] = mu_[k * stride_ + l];
      Rng rng = rngs_.get(l);
      const std::size_t choice =
          s_.runs[run_[l]].policy->drawChoice(logits_.data(), rng, choiceCoefficient_.data());
      rngs_.set(l, rng);
      store_.action[l] = static_cast<double>(choice);
      for (std::size_t k = 0; k < outputs_; ++k) {
        choiceRows_[k * stride_ + l] = choiceCoefficient_[k];
      }
    }
    for (std::size_t k = 0; k < outputs_; ++k) {
      lockstep::addGradient(lanes_, eligibility_.data(), k * dim_, choiceRows_.data() + k * stride_,
                            phi_.data(), dim_);
    }
  }

  // LinearPolicy::greedy, lane by lane.
  void greedy(std::size_t active) {
    const LinearPolicy& policy = *s_.runs.front().policy;  // For the shape and the action box.
    for (std::size_t l = 0; l < active; ++l) {
      if (policy.continuous()) {
        for (std::size_t i = 0; i < outputs_; ++i) {
          store_.action[i * stride_ + l] =
              failed_[l] ? 0.0 : policy.centre(i) + policy.halfWidth(i) * mu_[i * stride_ + l];
        }
        continue;
      }
      std::size_t best = 0;
      for (std::size_t k = 1; k < outputs_ && !failed_[l]; ++k) {
        if (mu_[k * stride_ + l] > mu_[best * stride_ + l]) best = k;
      }
      store_.action[l] = static_cast<double>(best);
    }
  }

  // Books the step of every lane, retires the episodes that ended and compacts the lanes.
  // Returns the number of lanes still running.
  std::size_t finish(std::size_t active, bool sampling, Records& out) {
    // As the sequential player checks: a reward or state variable that is not finite.
    std::fill(broken_.begin(), broken_.begin() + static_cast<std::ptrdiff_t>(lanes_.lanes), 0);
    lockstep::flagNotFinite(lanes_, store_.reward.data(), 1, broken_.data(), store_.state.data(),
                            stateDim_);
    for (std::size_t l = active; l-- > 0;) {
      Outcome& outcome = out.outcomes[episode_[l]];
      bool done = true;
      if (failed_[l]) {
        outcome.ok = false;
      } else {
        ++outcome.steps;
        const double r = store_.reward[l];
        if (broken_[l]) {
          outcome.ok = false;
        } else {
          outcome.undiscounted += r;
          outcome.discounted += weight_[l] * r;
          weight_[l] *= s_.discount;
          done = store_.terminated[l] || store_.truncated[l] || outcome.steps >= s_.maxSteps;
        }
      }
      if (!done) continue;
      if (sampling) retire(l, out.eligibility[episode_[l]], outcome);
      moveLane(active - 1, l, sampling);
      --active;
    }
    return active;
  }

  void retire(std::size_t lane, Eigen::VectorXd& eligibility, Outcome& outcome) {
    for (std::size_t k = 0; k < parameters_; ++k) {
      eligibility[static_cast<Eigen::Index>(k)] = eligibility_[k * stride_ + lane];
    }
    if (outcome.ok) {
      outcome.ok = std::isfinite(outcome.discounted) && std::isfinite(eligibility.sum());
    }
  }

  void moveLane(std::size_t from, std::size_t to, bool sampling) {
    if (sampling) {
      for (std::size_t k = 0; k < parameters_; ++k) {
        eligibility_[k * stride_ + to] = eligibility_[k * stride_ + from];
        eligibility_[k * stride_ + from] = 0.0;
      }
    }
    if (from == to) return;
    batch_->moveLane(from, to);
    for (std::size_t i = 0; i < stateDim_; ++i)
      store_.state[i * stride_ + to] = store_.state[i * stride_ + from];
    store_.elapsed[to] = store_.elapsed[from];
    weight_[to] = weight_[from];
    episode_[to] = episode_[from];
    run_[to] = run_[from];
    rngs_.move(from, to);
    for (std::size_t k = 0; k < outputs_ * dim_; ++k) {
      weights_[k * stride_ + to] = weights_[k * stride_ + from];
    }
    for (std::size_t i = 0; i < outputs_; ++i) sd_[i * stride_ + to] = sd_[i * stride_ + from];
    for (std::size_t j = 0; j < shift_.size() / stride_; ++j) {
      shift_[j * stride_ + to] = shift_[j * stride_ + from];
      scale_[j * stride_ + to] = scale_[j * stride_ + from];
    }
  }

  // Lane `lane` plays an episode of run `run`: it takes the run's weights, standard deviations
  // and normalisation.
  void takeRun(std::size_t lane, std::size_t run) {
    run_[lane] = run;
    const LinearPolicy& policy = *s_.runs[run].policy;
    const double* w = policy.parameters().data();
    for (std::size_t k = 0; k < outputs_ * dim_; ++k) weights_[k * stride_ + lane] = w[k];
    if (policy.continuous()) {
      for (std::size_t i = 0; i < outputs_; ++i) sd_[i * stride_ + lane] = policy.stdOf(i);
    }
    if (normalise_) {
      const FeaturePipeline& features = *s_.runs[run].features;
      for (std::size_t j = 0; j < rawDim_; ++j) {
        shift_[j * stride_ + lane] = features.shift()[j];
        scale_[j * stride_ + lane] = features.scale()[j];
      }
    }
  }

  Setup s_;
  std::unique_ptr<env::BatchEnvironment> batch_;
  std::size_t capacity_, stride_, stateDim_, rawDim_, dim_, outputs_, parameters_;
  bool normalise_;
  lockstep::Rows lanes_;     // The lane rows as the kernels see them.
  env::BatchStorage store_;  // The environment's lanes: structure of arrays, `stride_` apart.
  env::BatchBuffers& io_;
  std::vector<double> blocks_, raw_;  // States and raw features in lane blocks (the map's layout).
  std::vector<double> phi_, mu_, eps_, coefficient_, choiceCoefficient_, logits_, eligibility_;
  std::vector<double> choiceRows_;  // Each lane's softmax coefficients, one row per choice.
  std::vector<double> weights_, sd_, shift_, scale_;  // Each lane's run's parameters.
  std::vector<double> weight_;                        // Discount weight of the next reward.
  std::vector<std::uint8_t> failed_;
  std::vector<std::uint8_t> broken_;  // A step's reward or state is not finite.
  std::vector<std::size_t> episode_;  // The episode (index into the call's tasks) of each lane.
  std::vector<std::size_t> run_;      // Its run.
  RngLanes rngs_;                     // Each lane's episode's stream.
  std::vector<Rng> starts_;           // The streams of a call's episodes as their resets begin.
};

}  // namespace

std::unique_ptr<Player> makeLockstepPlayer(const Setup& setup, std::size_t capacity) {
  auto batch = env::makeBatchEnvironment(*setup.env);
  if (!batch) batch = env::makeLaneByLaneBatch(*setup.env);
  if (!batch) return nullptr;
  return std::make_unique<LockstepPlayer>(setup, std::move(batch), capacity);
}

}  // namespace gpfd::rl::episodes
