#include "gpfd/run/state_ranges.hpp"

#include <numbers>

#include "gpfd/util/error.hpp"

namespace gpfd::run {

std::vector<rl::StateRange> typicalStateRanges(const std::string& env,
                                               const std::vector<std::string>& variables) {
  constexpr double pi = std::numbers::pi;
  std::vector<rl::StateRange> ranges;
  for (const auto& v : variables) {
    if (env == "acrobot") {
      // Gymnasium clips dth1 to [-4 pi, 4 pi] and dth2 to [-9 pi, 9 pi]; angles are wrapped.
      const double bound = v == "dth1" ? 4 * pi : v == "dth2" ? 9 * pi : pi;
      ranges.push_back({-bound, bound});
    } else if (env == "cartpole") {
      // x and th: the failure limits; dx and dth: seen within episodes under random forces.
      const double bound = v == "x" ? 2.4 : v == "th" ? 0.20943951023931953 : v == "dx" ? 3.0 : 3.5;
      ranges.push_back({-bound, bound});
    } else if (env == "swimmer") {
      // Angles are wrapped into [-pi, pi]; velocities: seen under random torques (|u| <= 5).
      const double bound = v.rfind("th", 0) == 0 ? pi : v.rfind("dth", 0) == 0 ? 5.0 : 1.0;
      ranges.push_back({-bound, bound});
    } else {
      throw InputError("no typical state ranges are known for " + env +
                           ", so the Fourier basis is not available for it",
                       "--fourier");
    }
  }
  return ranges;
}

}  // namespace gpfd::run
