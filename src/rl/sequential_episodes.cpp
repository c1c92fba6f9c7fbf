// rl: the sequential reference player (episode_players.hpp).
#include <algorithm>
#include <cmath>

#include "episode_players.hpp"

namespace gpfd::rl::episodes {

void prepare(Records& out, std::size_t n, Eigen::Index parameters, std::size_t rawDim,
             bool sampling, bool normalising) {
  out.outcomes.assign(n, Outcome{});
  if (sampling) {
    out.eligibility.resize(n);
    for (auto& e : out.eligibility) e.setZero(parameters);
  }
  if (normalising) {
    out.moments.resize(n, FeatureMoments(rawDim));
    for (auto& m : out.moments) {
      if (m.mean.size() != rawDim) m = FeatureMoments(rawDim);
      m.clear();
    }
  }
}

namespace {

class SequentialPlayer final : public Player {
 public:
  SequentialPlayer(const Setup& setup, std::size_t capacity)
      : s_(setup),
        capacity_(capacity),
        phi_(setup.runs.front().features->dim(), 0.0),
        action_(setup.runs.front().policy->actionComponents(), 0.0),
        failed_(setup.runs.size(), 0) {}

  std::size_t capacity() const override { return capacity_; }

  void play(std::span<const Task> tasks, bool sampling, Records& out) override {
    const Run& first = s_.runs.front();
    const bool normalising = first.features->options().normalise;
    prepare(out, tasks.size(), first.policy->parameterCount(), first.features->rawDim(), sampling,
            normalising);
    std::fill(failed_.begin(), failed_.end(), 0);
    for (std::size_t e = 0; e < tasks.size(); ++e) {
      if (failed_[tasks[e].run]) continue;
      Rng rng(tasks[e].seed);
      Outcome& outcome = out.outcomes[e];
      runEpisode(s_.runs[tasks[e].run], rng, sampling ? &out.eligibility[e] : nullptr,
                 normalising ? &out.moments[e] : nullptr, outcome);
      if (sampling && outcome.ok) {
        outcome.ok = std::isfinite(outcome.discounted) && std::isfinite(out.eligibility[e].sum());
      }
      if (!outcome.ok) failed_[tasks[e].run] = 1;
    }
  }

 private:
  void runEpisode(const Run& run, Rng& rng, Eigen::VectorXd* eligibility, FeatureMoments* moments,
                  Outcome& outcome) {
    env::Environment& env = *s_.env;
    env.reset(rng);
    const std::span<const double> action(action_.data(), action_.size());
    const std::size_t raw = run.features->rawDim();
    double weight = 1.0;
    for (int t = 0; t < s_.maxSteps; ++t) {
      s_.map->evaluate(env.state().data(), phi_.data());
      if (moments != nullptr) {
        for (std::size_t j = 0; j < raw; ++j) {
          if (!std::isfinite(phi_[j])) {
            outcome.ok = false;
            return;
          }
        }
        moments->add(phi_.data());
      }
      const bool fine =
          run.features->transform(phi_.data()) &&
          (eligibility != nullptr
               ? run.policy->sample(rng, phi_.data(), action_.data(), eligibility->data())
               : run.policy->greedy(phi_.data(), action_.data()));
      if (!fine) {
        outcome.ok = false;
        return;
      }
      const env::StepResult result = env.step(action);
      ++outcome.steps;
      // A non-finite state is caught here, not by the features: GP's features map it to finite
      // values (ops.hpp), which would hide a broken simulation.
      const auto state = env.state();
      if (!std::isfinite(result.reward) ||
          !std::all_of(state.begin(), state.end(), [](double v) { return std::isfinite(v); })) {
        outcome.ok = false;
        return;
      }
      outcome.undiscounted += result.reward;
      outcome.discounted += weight * result.reward;
      weight *= s_.discount;
      if (result.terminated || result.truncated) return;
    }
  }

  Setup s_;
  std::size_t capacity_;
  std::vector<double> phi_, action_;
  std::vector<std::uint8_t> failed_;  // Per run: an episode of this call was not ok.
};

}  // namespace

std::unique_ptr<Player> makeSequentialPlayer(const Setup& setup, std::size_t capacity) {
  return std::make_unique<SequentialPlayer>(setup, capacity);
}

}  // namespace gpfd::rl::episodes
