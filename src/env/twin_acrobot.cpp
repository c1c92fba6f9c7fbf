// env: the twin of Gymnasium's Acrobot-v1 (gymnasium/envs/classic_control/acrobot.py, the same
// in Gymnasium 1.1 to 1.4): Sutton's "book" dynamics, one step of its rk4 over dt = 0.2, the
// angles wrapped and the velocities bounded, in the order of its Python. Every quantity after the
// reset is a float64; the start state is float32 (its reset's astype).
#include <fmt/format.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "gpfd/util/error.hpp"
#include "lane_copies.hpp"
#include "numpy_trig_f32.hpp"
#include "twin_params.hpp"
#include "twins.hpp"

namespace gpfd::env::twin {
namespace {

struct AcrobotConfig {
  TwinSettings settings{Promotion::Nep50, 500};

  static const ParamTable<AcrobotConfig>& table() {
    static const auto table = [] {
      ParamTable<AcrobotConfig> t("Acrobot-v1");
      declareTwinSettings(t);
      return t;
    }();
    return table;
  }
};

// AcrobotEnv's class constants (masses, lengths, centres of mass, moments of inertia).
constexpr double kPi = 3.141592653589793;
constexpr double kDt = 0.2, kM1 = 1.0, kM2 = 1.0, kL1 = 1.0, kLc1 = 0.5, kLc2 = 0.5;
constexpr double kI1 = 1.0, kI2 = 1.0, kG = 9.8;
constexpr double kMaxVel1 = 4 * kPi, kMaxVel2 = 9 * kPi;
constexpr std::array<double, 3> kTorques{-1.0, 0.0, 1.0};  // AVAIL_TORQUE

using Vec = std::array<double, 5>;  // theta1, theta2, dtheta1, dtheta2, torque

// cos and sin of an angle, as libm's cos and sin give them.
struct CosSin {
  double cos = 0.0, sin = 0.0;
};
CosSin cosSin(double angle) {
  CosSin out;
  libmSinCos(angle, out.sin, out.cos);
  return out;
}

// lc1**2, lc2**2 and l1**2 of Python floats: libm's pow, the same every call.
const double lc1Sq = libmPow(kLc1, 2), lc2Sq = libmPow(kLc2, 2), l1Sq = libmPow(kL1, 2);

// _dsdt, term by term in its order, given cos and sin of theta2; Python's ** on a float64 is libm's
// pow.
Vec derivative(const Vec& s, CosSin trig2) {
  const double a = s[4], theta1 = s[0], theta2 = s[1], dtheta1 = s[2], dtheta2 = s[3];
  const double cos2 = trig2.cos, sin2 = trig2.sin;
  const double d1 = kM1 * lc1Sq + kM2 * (l1Sq + lc2Sq + 2 * kL1 * kLc2 * cos2) + kI1 + kI2;
  const double d2 = kM2 * (lc2Sq + kL1 * kLc2 * cos2) + kI2;
  const double phi2 = kM2 * kLc2 * kG * std::cos(theta1 + theta2 - kPi / 2.0);
  const double phi1 = -kM2 * kL1 * kLc2 * libmSquare(dtheta2) * sin2 -
                      2 * kM2 * kL1 * kLc2 * dtheta2 * dtheta1 * sin2 +
                      (kM1 * kLc1 + kM2 * kL1) * kG * std::cos(theta1 - kPi / 2) + phi2;
  const double ddtheta2 =
      (a + d2 / d1 * phi1 - kM2 * kL1 * kLc2 * libmSquare(dtheta1) * sin2 - phi2) /
      (kM2 * lc2Sq + kI2 - libmSquare(d2) / d1);
  const double ddtheta1 = -(d2 * ddtheta2 + phi1) / d1;
  return {dtheta1, dtheta2, ddtheta1, ddtheta2, 0.0};
}

// y + h * k, element by element (NumPy's array arithmetic).
Vec plus(const Vec& y, double h, const Vec& k) {
  Vec out;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = y[i] + h * k[i];
  return out;
}

Vec derivative(const Vec& s) { return derivative(s, cosSin(s[1])); }

// rk4(derivs, y0, [0, dt]): one classic Runge-Kutta step; `trig2` is cos and sin of y0's theta2.
Vec rk4(const Vec& y0, CosSin trig2) {
  const double dt = kDt - 0, dt2 = dt / 2.0;
  const Vec k1 = derivative(y0, trig2);
  const Vec k2 = derivative(plus(y0, dt2, k1));
  const Vec k3 = derivative(plus(y0, dt2, k2));
  const Vec k4 = derivative(plus(y0, dt, k3));
  Vec out;
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = y0[i] + dt / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  return out;
}

// wrap(x, m, M) and bound(x, m, M) as acrobot.py writes them.
double wrap(double x, double m, double big) {
  const double diff = big - m;
  while (x > big) x = x - diff;
  while (x < m) x = x + diff;
  return x;
}
double bound(double x, double m, double big) {
  const double low = m > x ? m : x;  // Python's max(x, m), then min(., M).
  return big < low ? big : low;
}

class AcrobotTwin final : public GymnasiumTwin {
 public:
  explicit AcrobotTwin(const AcrobotConfig& config)
      : GymnasiumTwin("Acrobot-v1", 6, config.settings), config_(config) {
    dynamics_.assign(4, 0.0);
  }
  Params params() const override { return AcrobotConfig::table().write(config_); }
  ActionSpace actionSpace() const override { return discreteActions(3); }
  std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa isa) const override {
    return makeLaneCopies(*this, isa);
  }
  void setState(std::span<const double> state) override {
    if (state.size() != 4) {
      throw InputError("Acrobot-v1 is set by its 4 angles and velocities", "state");
    }
    dynamics_.assign(state.begin(), state.end());
    observe(false);
    roundObservation();
  }

 private:
  friend class GymnasiumTwin;  // stepFinal calls advance.
  void start(numpy::Pcg64& random) override {
    for (double& v : dynamics_) v = static_cast<float>(random.uniform(-0.1, 0.1));
    observe(true);
  }

  StepResult advance(std::span<const double> action, ActionKind) override {
    checkActionSize(action, 1);
    const double a = action[0];
    if (!(a == 0.0 || a == 1.0 || a == 2.0)) {
      throw InputError(fmt::format("Acrobot-v1's action is 0, 1 or 2 (Discrete(3)), got {}", a),
                       "Acrobot-v1 action");
    }
    const Vec augmented{dynamics_[0], dynamics_[1], dynamics_[2], dynamics_[3],
                        kTorques[static_cast<std::size_t>(a)]};
    const Vec next = rk4(augmented, cosSinOfState(1));
    dynamics_ = {wrap(next[0], -kPi, kPi), wrap(next[1], -kPi, kPi),
                 bound(next[2], -kMaxVel1, kMaxVel1), bound(next[3], -kMaxVel2, kMaxVel2)};
    observe(false);
    StepResult result;
    result.terminated = -cosSinOfState(0).cos - std::cos(dynamics_[1] + dynamics_[0]) > 1.0;
    result.reward = result.terminated ? 0.0 : -1.0;
    return result;
  }

  // _get_ob: cos and sin of the angles, then the velocities, as float32. After the reset the state
  // is a float32 array, whose cos and sin NumPy computes in float32 (numpy_trig_f32.hpp).
  void observe(bool float32State) {
    for (std::size_t i = 0; i < 2; ++i) {
      if (float32State) {
        const auto angle = static_cast<float>(dynamics_[i]);
        observation_[2 * i] = numpy_trig::sinOrCos(angle, true);
        observation_[2 * i + 1] = numpy_trig::sinOrCos(angle, false);
      } else {
        const CosSin trig = cosSinOfState(i);
        observation_[2 * i] = trig.cos;
        observation_[2 * i + 1] = trig.sin;
      }
      observation_[4 + i] = dynamics_[2 + i];
    }
  }

  // np.cos and np.sin of the state's angle i in float64, computed once per value: the observation,
  // the terminal test and the next step's first derivative all take them of the same double.
  CosSin cosSinOfState(std::size_t i) {
    const auto bits = std::bit_cast<std::uint64_t>(dynamics_[i]);
    if (!trigKnown_[i] || trigOf_[i] != bits) {
      trig_[i] = cosSin(dynamics_[i]);
      trigOf_[i] = bits;
      trigKnown_[i] = true;
    }
    return trig_[i];
  }

  AcrobotConfig config_;
  std::array<CosSin, 2> trig_{};  // cos and sin of the angles whose bits are trigOf_.
  std::array<std::uint64_t, 2> trigOf_{};
  std::array<bool, 2> trigKnown_{};
};

}  // namespace

EnvInfo acrobotTwin() {
  return twinInfo<AcrobotTwin, AcrobotConfig>(
      "Acrobot-v1", "Gymnasium's Acrobot-v1, the same episodes bit for bit (native twin)");
}

}  // namespace gpfd::env::twin
