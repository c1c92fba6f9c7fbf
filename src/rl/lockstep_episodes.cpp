// rl: the lockstep player (episode_players.hpp): the episodes of one call advance together, one
// step of every running episode at a time. Per step: the states (structure of arrays, one lane
// per episode) go through the feature map's batch evaluation (the JIT's AVX2 kernel), the policy's
// outputs and likelihood gradients are computed four lanes at a time, the Gaussian draws come
// from each episode's own stream, and the batched environment steps every lane. An episode that
// ends frees its lane: the last running lane moves into it, so the running lanes stay dense.
// Every lane performs the operations of the sequential player in the same order, so both give the
// same bits.
#include <algorithm>
#include <cmath>

#include "episode_players.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/util/lanes.hpp"
#include "gpfd/util/ziggurat.hpp"

namespace gpfd::rl::episodes {
namespace {

// mu[i * stride + l] = sum over j (in order) of w[i * dim + j] * phi[j * stride + l], for lanes
// [0, lanes) rounded up to the width of T.
template <class T>
void linearOutputs(const double* w, std::size_t outputs, std::size_t dim, const double* phi,
                   std::size_t stride, std::size_t lanes, double* mu) {
  for (std::size_t l = 0; l < lanes; l += lanes::kWidth<T>) {
    for (std::size_t i = 0; i < outputs; ++i) {
      T acc = 0.0;
      for (std::size_t j = 0; j < dim; ++j) {
        acc += w[i * dim + j] * lanes::loadAs<T>(phi + j * stride + l);
      }
      lanes::store(mu + i * stride + l, acc);
    }
  }
}

// eligibility[(row + j) * stride + l] += coefficient[l] * phi[j * stride + l], j < dim.
template <class T>
void addGradient(double* eligibility, std::size_t row, const double* coefficient, const double* phi,
                 std::size_t dim, std::size_t stride, std::size_t lanes) {
  for (std::size_t l = 0; l < lanes; l += lanes::kWidth<T>) {
    const T c = lanes::loadAs<T>(coefficient + l);
    for (std::size_t j = 0; j < dim; ++j) {
      double* e = eligibility + (row + j) * stride + l;
      lanes::store(e, lanes::loadAs<T>(e) + c * lanes::loadAs<T>(phi + j * stride + l));
    }
  }
}

GPFD_AVX2_KERNEL void linearOutputsAvx2(const double* w, std::size_t outputs, std::size_t dim,
                                        const double* phi, std::size_t stride, std::size_t lanes,
                                        double* mu) {
  linearOutputs<lanes::Lanes4>(w, outputs, dim, phi, stride, lanes, mu);
}

GPFD_AVX2_KERNEL void addGradientAvx2(double* eligibility, std::size_t row,
                                      const double* coefficient, const double* phi, std::size_t dim,
                                      std::size_t stride, std::size_t lanes) {
  addGradient<lanes::Lanes4>(eligibility, row, coefficient, phi, dim, stride, lanes);
}

class LockstepPlayer final : public Player {
 public:
  LockstepPlayer(const Setup& setup, std::unique_ptr<env::BatchEnvironment> batch,
                 std::size_t capacity)
      : s_(setup),
        batch_(std::move(batch)),
        capacity_(capacity),
        stride_((capacity + 3) / 4 * 4),
        stateDim_(batch_->stateDim()),
        rawDim_(setup.features->rawDim()),
        dim_(setup.features->dim()),
        outputs_(setup.policy->outputs()),
        avx2_(batch_->usesAvx2()),
        state_(stateDim_ * stride_, 0.0),
        action_(batch_->actionComponents() * stride_, 0.0),
        reward_(stride_, 0.0),
        elapsed_(stride_, 0),
        terminated_(stride_, 0),
        truncated_(stride_, 0),
        rows_(stride_ * std::max(stateDim_, std::size_t{1}), 0.0),
        raw_(stride_ * std::max(rawDim_, std::size_t{1}), 0.0),
        row_(dim_, 0.0),
        phi_(dim_ * stride_, 0.0),
        mu_(outputs_ * stride_, 0.0),
        coefficient_(std::max(outputs_, stride_), 0.0),
        choiceCoefficient_(outputs_, 0.0),
        logits_(outputs_, 0.0),
        eligibility_(static_cast<std::size_t>(setup.policy->parameterCount()) * stride_, 0.0),
        weight_(stride_, 1.0),
        failed_(stride_, 0),
        episode_(stride_, 0),
        rngs_(capacity) {
    io_.stride = stride_;
    io_.state = state_.data();
    io_.action = action_.data();
    io_.elapsed = elapsed_.data();
    io_.reward = reward_.data();
    io_.terminated = terminated_.data();
    io_.truncated = truncated_.data();
  }

  std::size_t capacity() const override { return capacity_; }

  void play(std::span<const std::uint64_t> seeds, bool sampling, Records& out) override {
    const std::size_t n = seeds.size();
    const bool normalising = s_.features->options().normalise;
    prepare(out, n, s_.policy->parameterCount(), rawDim_, sampling, normalising);
    if (sampling) std::fill(eligibility_.begin(), eligibility_.end(), 0.0);
    for (std::size_t e = 0; e < n; ++e) {
      rngs_[e].reseed(seeds[e]);
      batch_->reset(rngs_[e], io_, e);
      episode_[e] = e;
      weight_[e] = 1.0;
    }
    std::size_t active = n;
    while (active > 0) {
      io_.lanes = active;
      features(active, normalising ? &out.moments : nullptr);
      policyOutputs(active);
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
  // phi (dim_ rows of stride_) for lanes [0, active); marks lanes whose features are not finite.
  void features(std::size_t active, std::vector<FeatureMoments>* moments) {
    for (std::size_t l = 0; l < active; ++l) {
      for (std::size_t i = 0; i < stateDim_; ++i)
        rows_[l * stateDim_ + i] = state_[i * stride_ + l];
    }
    s_.map->evaluateBatch(rows_.data(), active, raw_.data());
    for (std::size_t l = 0; l < active; ++l) {
      const double* raw = raw_.data() + l * rawDim_;
      std::copy(raw, raw + rawDim_, row_.begin());
      failed_[l] = 0;
      if (moments != nullptr) {
        if (!std::all_of(raw, raw + rawDim_, [](double v) { return std::isfinite(v); })) {
          failed_[l] = 1;
          continue;
        }
        (*moments)[episode_[l]].add(raw);
      }
      if (!s_.features->transform(row_.data())) {
        failed_[l] = 1;
        continue;
      }
      for (std::size_t j = 0; j < dim_; ++j) phi_[j * stride_ + l] = row_[j];
    }
  }

  // The policy's outputs; marks lanes whose outputs are not finite.
  void policyOutputs(std::size_t active) {
    const double* w = s_.policy->parameters().data();
    if (avx2_) {
      linearOutputsAvx2(w, outputs_, dim_, phi_.data(), stride_, active, mu_.data());
    } else {
      linearOutputs<double>(w, outputs_, dim_, phi_.data(), stride_, active, mu_.data());
    }
    for (std::size_t l = 0; l < active; ++l) {
      for (std::size_t i = 0; i < outputs_ && !failed_[l]; ++i) {
        if (!std::isfinite(mu_[i * stride_ + l])) failed_[l] = 1;
      }
    }
  }

  void gradientRows(std::size_t row, std::size_t active) {
    if (avx2_) {
      addGradientAvx2(eligibility_.data(), row, coefficient_.data(), phi_.data(), dim_, stride_,
                      active);
    } else {
      addGradient<double>(eligibility_.data(), row, coefficient_.data(), phi_.data(), dim_, stride_,
                          active);
    }
  }

  // LinearPolicy::sample, lane by lane.
  void sample(std::size_t active) {
    const LinearPolicy& policy = *s_.policy;
    if (policy.continuous()) {
      const std::size_t weightCount = outputs_ * dim_;
      const bool learnStd = policy.parameterCount() > static_cast<Eigen::Index>(weightCount);
      for (std::size_t i = 0; i < outputs_; ++i) {
        const double sd = policy.stdOf(i), centre = policy.centre(i), half = policy.halfWidth(i);
        for (std::size_t l = 0; l < active; ++l) {
          if (failed_[l]) {
            action_[i * stride_ + l] = 0.0;
            coefficient_[l] = 0.0;
            continue;
          }
          const double eps = standardNormal(rngs_[episode_[l]]);
          const double u = mu_[i * stride_ + l] + sd * eps;
          action_[i * stride_ + l] = centre + half * u;
          coefficient_[l] = eps / sd;
          if (learnStd) eligibility_[(weightCount + i) * stride_ + l] += eps * eps - 1.0;
        }
        gradientRows(i * dim_, active);
      }
      return;
    }
    for (std::size_t l = 0; l < active; ++l) {
      if (failed_[l]) {
        action_[l] = 0.0;
        continue;
      }
      for (std::size_t k = 0; k < outputs_; ++k) logits_[k] = mu_[k * stride_ + l];
      const std::size_t choice =
          policy.drawChoice(logits_.data(), rngs_[episode_[l]], choiceCoefficient_.data());
      action_[l] = static_cast<double>(choice);
      for (std::size_t k = 0; k < outputs_; ++k) {
        double* g = eligibility_.data() + k * dim_ * stride_ + l;
        for (std::size_t j = 0; j < dim_; ++j) {
          g[j * stride_] += choiceCoefficient_[k] * phi_[j * stride_ + l];
        }
      }
    }
  }

  // LinearPolicy::greedy, lane by lane.
  void greedy(std::size_t active) {
    const LinearPolicy& policy = *s_.policy;
    for (std::size_t l = 0; l < active; ++l) {
      if (policy.continuous()) {
        for (std::size_t i = 0; i < outputs_; ++i) {
          action_[i * stride_ + l] =
              failed_[l] ? 0.0 : policy.centre(i) + policy.halfWidth(i) * mu_[i * stride_ + l];
        }
        continue;
      }
      std::size_t best = 0;
      for (std::size_t k = 1; k < outputs_ && !failed_[l]; ++k) {
        if (mu_[k * stride_ + l] > mu_[best * stride_ + l]) best = k;
      }
      action_[l] = static_cast<double>(best);
    }
  }

  // Books the step of every lane, retires the episodes that ended and compacts the lanes.
  // Returns the number of lanes still running.
  std::size_t finish(std::size_t active, bool sampling, Records& out) {
    for (std::size_t l = active; l-- > 0;) {
      Outcome& outcome = out.outcomes[episode_[l]];
      bool done = true;
      if (failed_[l]) {
        outcome.ok = false;
      } else {
        ++outcome.steps;
        const double r = reward_[l];
        if (!std::isfinite(r)) {
          outcome.ok = false;
        } else {
          outcome.undiscounted += r;
          outcome.discounted += weight_[l] * r;
          weight_[l] *= s_.discount;
          done = terminated_[l] || truncated_[l] || outcome.steps >= s_.maxSteps;
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
    for (Eigen::Index k = 0; k < eligibility.size(); ++k) {
      double& e = eligibility_[static_cast<std::size_t>(k) * stride_ + lane];
      eligibility[k] = e;
      e = 0.0;
    }
    if (outcome.ok) {
      outcome.ok = std::isfinite(outcome.discounted) && std::isfinite(eligibility.sum());
    }
  }

  void moveLane(std::size_t from, std::size_t to, bool sampling) {
    if (from == to) return;
    for (std::size_t i = 0; i < stateDim_; ++i)
      state_[i * stride_ + to] = state_[i * stride_ + from];
    if (sampling) {
      const std::size_t rows = eligibility_.size() / stride_;
      for (std::size_t k = 0; k < rows; ++k) {
        eligibility_[k * stride_ + to] = eligibility_[k * stride_ + from];
        eligibility_[k * stride_ + from] = 0.0;
      }
    }
    elapsed_[to] = elapsed_[from];
    weight_[to] = weight_[from];
    episode_[to] = episode_[from];
  }

  Setup s_;
  std::unique_ptr<env::BatchEnvironment> batch_;
  std::size_t capacity_, stride_, stateDim_, rawDim_, dim_, outputs_;
  bool avx2_;
  // Lanes: structure of arrays, `stride_` apart.
  std::vector<double> state_, action_, reward_;
  std::vector<std::int32_t> elapsed_;
  std::vector<std::uint8_t> terminated_, truncated_;
  env::BatchBuffers io_;
  std::vector<double> rows_, raw_;  // States and raw features, one row per lane (the map's layout).
  std::vector<double> row_;         // One lane's features while they are transformed.
  std::vector<double> phi_, mu_, coefficient_, choiceCoefficient_, logits_, eligibility_, weight_;
  std::vector<std::uint8_t> failed_;
  std::vector<std::size_t> episode_;  // The episode (index into the call's seeds) of each lane.
  std::vector<Rng> rngs_;             // Per episode.
};

}  // namespace

std::unique_ptr<Player> makeLockstepPlayer(const Setup& setup, std::size_t capacity) {
  auto batch = env::makeBatchEnvironment(*setup.env);
  if (!batch) return nullptr;
  return std::make_unique<LockstepPlayer>(setup, std::move(batch), capacity);
}

}  // namespace gpfd::rl::episodes
