// env: any environment as a batch, lane by lane (makeLaneByLaneBatch, env/batch.hpp; the lanes:
// lane_copies.hpp). A twin of a Gymnasium task gives its own form (GymnasiumTwin::makeLanes), the
// same lanes without a virtual call per lane.
#include "batch_factories.hpp"
#include "gpfd/env/gymnasium_twin.hpp"
#include "lane_copies.hpp"

namespace gpfd::env {

std::unique_ptr<BatchEnvironment> makeLaneByLaneBatch(const Environment& env, BatchIsa isa) {
  if (const auto* twin = dynamic_cast<const GymnasiumTwin*>(&env)) {
    if (auto lanes = twin->makeLanes(batch::resolveIsa(isa))) return lanes;
  }
  return makeLaneCopies(env, batch::resolveIsa(isa));
}

}  // namespace gpfd::env
