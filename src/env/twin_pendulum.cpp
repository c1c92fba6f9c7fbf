// env: the twin of Gymnasium's Pendulum-v1 (gymnasium/envs/classic_control/pendulum.py, the same
// in Gymnasium 1.1 to 1.4). The state is float64; the torque is the action's type (float32 from
// the action space), so the cost's u**2 and the acceleration's 3 u follow NumPy's promotion.
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gpfd/util/error.hpp"
#include "lane_copies.hpp"
#include "twin_params.hpp"
#include "twins.hpp"

namespace gpfd::env::twin {
namespace {

struct PendulumConfig {
  TwinSettings settings{Promotion::Nep50, 200};
  double g = 10.0;

  static const ParamTable<PendulumConfig>& table() {
    static const auto table = [] {
      ParamTable<PendulumConfig> t("Pendulum-v1");
      declareTwinSettings(t);
      t.real(
          "g", [](auto& c) -> auto& { return c.g; }, 0.0, 1000.0,
          "Gymnasium's keyword: gravitational acceleration");
      return t;
    }();
    return table;
  }
};

constexpr double kPi = 3.141592653589793;
constexpr double kMaxSpeed = 8, kMaxTorque = 2.0, kDt = 0.05, kMass = 1.0, kLength = 1.0;
constexpr double kDefaultX = kPi, kDefaultY = 1.0;  // The start state's bounds.

// Python's and NumPy's float modulo: the result takes the divisor's sign. fmod is exact; for a
// positive divisor and a dividend within (-b, 2b) its value is a, or a - b (exact by Sterbenz's
// lemma), without the call.
double floorMod(double a, double b) {
  double mod = 0.0;
  if (b > 0 && a > -b && a < b) {
    mod = a;
  } else if (b > 0 && a >= b && a < 2 * b) {
    mod = a - b;
  } else {
    mod = std::fmod(a, b);
  }
  if (mod != 0.0) {
    if ((b < 0) != (mod < 0)) mod += b;
  } else {
    mod = std::copysign(0.0, b);
  }
  return mod;
}

class PendulumTwin final : public GymnasiumTwin {
 public:
  explicit PendulumTwin(const PendulumConfig& config)
      : GymnasiumTwin("Pendulum-v1", 3, config.settings), config_(config) {
    dynamics_.assign(2, 0.0);
  }
  Params params() const override { return PendulumConfig::table().write(config_); }
  ActionSpace actionSpace() const override { return boxAction(-kMaxTorque, kMaxTorque, "torque"); }
  std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa isa) const override {
    return makeLaneCopies(*this, isa);
  }
  // (cos th, sin th, dth), th from the first two by atan2.
  void setState(std::span<const double> state) override {
    if (state.size() != 3) throw InputError("Pendulum-v1 takes 3 state variables", "state");
    dynamics_ = {std::atan2(state[1], state[0]), state[2]};
    observe();
    roundObservation();
  }

 private:
  friend class GymnasiumTwin;  // stepFinal calls advance.
  void start(numpy::Pcg64& random) override {
    // uniform(low=-high, high=high) over high = [x_init, y_init], element by element.
    dynamics_ = {random.uniform(-kDefaultX, kDefaultX), random.uniform(-kDefaultY, kDefaultY)};
    observe();
  }

  // Every call inlined (flatten), and gpfd's case (float32 actions under NumPy 2's rules) with
  // its types known where it is compiled, so that NumPy's promotion folds away: the same
  // operations on the same values, without a test of the types per operation.
  [[gnu::flatten]] StepResult advance(std::span<const double> action, ActionKind kind) override {
    checkActionSize(action, 1);
    if (kind == Kind::Float32 && promotion() == Promotion::Nep50) {
      return advanceAs(action[0], Kind::Float32, Promotion::Nep50);
    }
    return advanceAs(action[0], kind, promotion());
  }

  [[gnu::always_inline]] StepResult advanceAs(double action, ActionKind kind, Promotion p) {
    const Num th = f64(dynamics_[0], p), thdot = f64(dynamics_[1], p);
    const Num u = numpy_scalar::npClip({action, kind, p}, py(-kMaxTorque, p), py(kMaxTorque, p));
    const Num two = {2, Kind::PyInt, p};
    // angle_normalize(th) = ((th + pi) % (2 pi)) - pi
    const Num normalised = f64(floorMod((th + py(kPi, p)).value, 2 * kPi), p) - py(kPi, p);
    const Num costs =
        power(normalised, two) + py(0.1, p) * power(thdot, two) + py(0.001, p) * power(u, two);
    const double g = config_.g;
    static const double lengthSquared = libmPow(kLength, 2);  // l**2 of Python floats.
    const Num accel = py(3 * g / (2 * kLength), p) * f64(sine(th.value), p) +
                      py(3.0 / (kMass * lengthSquared), p) * u;
    Num newThdot = thdot + accel * py(kDt, p);
    newThdot =
        numpy_scalar::npClip(newThdot, {-kMaxSpeed, Kind::PyInt, p}, {kMaxSpeed, Kind::PyInt, p});
    const Num newTh = th + newThdot * py(kDt, p);
    dynamics_[0] = newTh.value;
    dynamics_[1] = newThdot.value;
    observe();
    StepResult result;
    result.reward = -costs.value;
    return result;
  }

  void observe() {
    double cosine = 0.0;
    sineOf_ = dynamics_[0];
    libmSinCos(dynamics_[0], sine_, cosine);
    observation_[0] = cosine;
    observation_[1] = sine_;
    observation_[2] = dynamics_[1];
  }

  // np.sin(th): the observation's sine of the same angle where it is the same (bit for bit).
  double sine(double th) const {
    return std::bit_cast<std::uint64_t>(th) == std::bit_cast<std::uint64_t>(sineOf_) ? sine_
                                                                                     : std::sin(th);
  }

  PendulumConfig config_;
  double sineOf_ = std::numeric_limits<double>::quiet_NaN(), sine_ = 0.0;
};

}  // namespace

EnvInfo pendulumTwin() {
  return twinInfo<PendulumTwin, PendulumConfig>(
      "Pendulum-v1", "Gymnasium's Pendulum-v1, the same episodes bit for bit (native twin)");
}

}  // namespace gpfd::env::twin
