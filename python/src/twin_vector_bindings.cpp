// python: N twins of one Gymnasium task stepped by one call (gpfd._core.TwinVector), with
// Gymnasium's autoreset modes, as SyncVectorEnv over gymnasium.make(id) steps them: lane i is
// the twin that instance i of SyncVectorEnv would be (gpfd.twins.TwinVectorEnv drives it).
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "gpfd/env/gymnasium_twin.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

using Kind = env::numpy_scalar::Kind;
using ActionArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;

enum class Mode { NextStep, SameStep, Disabled };

class TwinVector {
 public:
  TwinVector(const std::string& id, const Params& params, std::size_t n, const std::string& mode)
      : mode_(mode == "next_step"   ? Mode::NextStep
              : mode == "same_step" ? Mode::SameStep
              : mode == "disabled"  ? Mode::Disabled
                                    : throw InputError("autoreset mode: next_step, same_step or "
                                                        "disabled, got " +
                                                           mode,
                                                       "TwinVector")) {
    if (n == 0) throw InputError("a vector of twins needs at least one", "num_envs");
    for (std::size_t i = 0; i < n; ++i) {
      auto made = env::Registry::global().make(id, params);
      auto* twin = dynamic_cast<env::GymnasiumTwin*>(made.get());
      if (twin == nullptr)
        throw InputError(id + " is not a twin of a Gymnasium task", "TwinVector");
      made.release();
      twins_.emplace_back(twin);
    }
    dim_ = twins_.front()->stateDim();
    ended_.assign(n, 0);
  }
  TwinVector(const TwinVector&) = delete;
  TwinVector& operator=(const TwinVector&) = delete;

  // seeds: one per lane, -1 for none (a reset that continues the lane's stream); words as
  // gpfd.twins.seed_words gives them. mask: the lanes to reset (all when empty).
  nb::ndarray<nb::numpy, float> reset(
      const std::vector<std::optional<std::vector<std::uint32_t>>>& seeds,
      const std::vector<bool>& mask) {
    for (std::size_t i = 0; i < twins_.size(); ++i) {
      if (!mask.empty() && !mask.at(i)) continue;
      if (seeds.at(i)) {
        twins_[i]->resetWithSeed(*seeds[i]);
      } else {
        twins_[i]->resetWithoutSeed();
      }
      ended_[i] = 0;
    }
    auto obs = newArray<float>({twins_.size(), dim_});
    for (std::size_t i = 0; i < twins_.size(); ++i) write(i, obs.data() + i * dim_);
    return obs;
  }

  // actions: n x components doubles of the NumPy type `kind`. Returns (obs, rewards, terminated,
  // truncated, final_obs or None, final_mask or None).
  nb::tuple step(ActionArray actions, const std::string& kind) {
    const std::size_t n = twins_.size();
    const std::size_t components = actions.ndim() == 2 ? actions.shape(1) : 1;
    if (actions.shape(0) != n) {
      throw InputError("one action per environment: " + std::to_string(n) + " rows, got " +
                           std::to_string(actions.shape(0)),
                       "actions");
    }
    const Kind k = kind == "float32"   ? Kind::Float32
                   : kind == "float64" ? Kind::Float64
                                       : Kind::PyFloat;
    auto obs = newArray<float>({n, dim_});
    auto rewards = newArray<double>({n});
    auto terminated = newArray<bool>({n});
    auto truncated = newArray<bool>({n});
    std::optional<nb::ndarray<nb::numpy, float>> finalObs;
    std::optional<nb::ndarray<nb::numpy, bool>> finalMask;
    if (mode_ == Mode::SameStep) {
      finalObs = newArray<float>({n, dim_});
      finalMask = newArray<bool>({n});
    }
    for (std::size_t i = 0; i < n; ++i) {
      env::StepResult r;
      if (mode_ == Mode::NextStep && ended_[i]) {
        twins_[i]->resetWithoutSeed();  // The ended episode's next step is a reset: reward 0.
      } else {
        r = twins_[i]->stepAs({actions.data() + i * components, components}, k);
      }
      const bool ended = r.terminated || r.truncated;
      if (finalMask) {
        finalMask->data()[i] = ended;
        if (ended) {
          write(i, finalObs->data() + i * dim_);
          twins_[i]->resetWithoutSeed();
        }
      }
      ended_[i] = ended ? 1 : 0;
      write(i, obs.data() + i * dim_);
      rewards.data()[i] = r.reward;
      terminated.data()[i] = r.terminated;
      truncated.data()[i] = r.truncated;
    }
    nb::object final = finalObs ? nb::cast(*finalObs) : nb::none();
    nb::object mask = finalMask ? nb::cast(*finalMask) : nb::none();
    return nb::make_tuple(obs, rewards, terminated, truncated, final, mask);
  }

 private:
  void write(std::size_t i, float* row) const {
    const auto state = twins_[i]->state();
    for (std::size_t d = 0; d < dim_; ++d) row[d] = static_cast<float>(state[d]);
  }

  Mode mode_;
  std::vector<std::unique_ptr<env::GymnasiumTwin>> twins_;
  std::vector<char> ended_;
  std::size_t dim_ = 0;
};

}  // namespace

void bindTwinVectors(nb::module_& m) {
  nb::class_<TwinVector>(m, "TwinVector",
                         "N twins of one Gymnasium task (gpfd.twins.TwinVectorEnv drives it).")
      .def(nb::init<const std::string&, const Params&, std::size_t, const std::string&>(),
           nb::arg("id"), nb::arg("params"), nb::arg("num_envs"), nb::arg("autoreset_mode"))
      .def("reset", &TwinVector::reset, nb::arg("seeds"), nb::arg("mask"))
      .def("step", &TwinVector::step, nb::arg("actions"), nb::arg("kind"));
}

}  // namespace gpfd::python
