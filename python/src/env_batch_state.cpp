// python: EnvBatch's snapshot and restore (declared in env_batch.hpp), with which gpfd's Gymnasium
// environments pickle and deep-copy mid-episode.
#include <fmt/format.h>

#include <limits>

#include "env_batch.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

// The snapshot's name: the environment's, so that one batch's words are never read by another
// environment's batch.
std::string snapshotName(const EnvBatch& batch) { return "batch of " + batch.prototype().name(); }

}  // namespace

std::vector<std::uint64_t> EnvBatch::snapshot() const {
  env::SnapshotWriter out(snapshotName(*this));
  out.integer(static_cast<std::int64_t>(size())).integer(batched() ? 1 : 0);
  std::vector<double> row(dim_);
  for (std::size_t i = 0; i < size(); ++i) {
    out.rng(rngs_[i]).integer(ended_[i]);
    if (lanes_) {
      lanes_->readState(i, row.data());
      out.reals(row).integer(lanes_->elapsed(i));
      continue;
    }
    const auto words = envs_[i]->snapshot();
    if (words.empty()) {
      throw InputError(fmt::format("{} has no snapshots (Environment::snapshot), so it cannot be "
                                   "pickled or copied",
                                   prototype().name()),
                       prototype().name());
    }
    out.words(words);
  }
  return out.take();
}

void EnvBatch::restore(std::span<const std::uint64_t> words) {
  const std::string name = prototype().name();
  env::SnapshotReader in(snapshotName(*this), words);
  const auto n = static_cast<std::size_t>(
      in.integer(static_cast<std::int64_t>(size()), static_cast<std::int64_t>(size()), "size"));
  const bool lanes = in.integer(batched() ? 1 : 0, batched() ? 1 : 0, "batched engine") == 1;
  // Everything is read into these first, so that an InputError changes nothing.
  std::vector<Rng::State> rngs(n);
  std::vector<char> ended(n);
  std::vector<std::vector<double>> rows(lanes ? n : 0, std::vector<double>(dim_));
  std::vector<std::int32_t> elapsed(lanes ? n : 0);
  std::vector<std::unique_ptr<env::Environment>> envs(lanes ? 0 : n);
  for (std::size_t i = 0; i < n; ++i) {
    rngs[i] = in.rng();
    ended[i] = static_cast<char>(in.integer(0, 1, "episode ended"));
    if (lanes) {
      in.reals(rows[i]);
      elapsed[i] = static_cast<std::int32_t>(
          in.integer(0, std::numeric_limits<std::int32_t>::max(), "the step count"));
      continue;
    }
    envs[i] = envs_[i]->freshCopy();
    if (!envs[i]) throw InputError(name + " cannot be copied to restore a snapshot", name);
    envs[i]->restore(in.words());
  }
  in.finish();
  for (std::size_t i = 0; i < n; ++i) {
    rngs_[i].setState(rngs[i]);
    ended_[i] = ended[i];
    if (lanes) {
      lanes_->writeState(i, rows[i]);
      lanes_->setElapsed(i, elapsed[i]);
    } else {
      envs_[i] = std::move(envs[i]);
    }
  }
}

}  // namespace gpfd::python
