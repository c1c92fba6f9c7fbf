// python: a Gymnasium environment stepped in Python, as a gpfd environment, so that discovery and
// assessment run on it unchanged. The Python side (gpfd.user_env.Adapter) checks the spaces and
// every observation and turns the environment's exceptions into clear errors; this side holds the
// GIL only while it calls Python. gpfd's own environments made from their Gymnasium ids step
// through their C++ engine directly (gpfd.adapters.sources.native_single).
#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cmath>
#include <vector>

#include "bindings.hpp"
#include "env_batch.hpp"
#include "gpfd/env/numpy_scalar.hpp"
#include "gpfd/util/error.hpp"
#include "python_call.hpp"
#include "trial_runner.hpp"

namespace gpfd::python {
namespace {

using ReadArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;

class PythonEnvironment final : public env::Environment {
 public:
  // `adapter` is a gpfd.user_env.Adapter. Called with the GIL held.
  PythonEnvironment(std::string name, nb::object adapter)
      : name_(std::move(name)), adapter_(std::move(adapter)) {
    const std::size_t dim = nb::cast<std::size_t>(adapter_.attr("state_dim"));
    for (std::size_t i = 0; i < dim; ++i) names_.push_back(fmt::format("x{}", i));
    state_.assign(dim, 0.0);
    if (nb::cast<std::string>(adapter_.attr("action_kind")) == "discrete") {
      space_.kind = env::ActionSpace::Kind::Discrete;
      space_.choices = {nb::cast<int>(adapter_.attr("choices"))};
      space_.names = {"action"};
    } else {
      space_.low = nb::cast<std::vector<double>>(adapter_.attr("low"));
      space_.high = nb::cast<std::vector<double>>(adapter_.attr("high"));
      space_.components = space_.low.size();
      for (std::size_t i = 0; i < space_.components; ++i) {
        space_.names.push_back(fmt::format("a{}", i));
      }
    }
    action_ = nb::cast(newArray<double>({space_.components}));
    bindNative();
  }
  ~PythonEnvironment() override {
    withPython([&] {
      try {
        adapter_.attr("close")();      // The Gymnasium environment's close(), once.
      } catch (nb::python_error& e) {  // A destructor does not throw: printed, as Python does.
        e.discard_as_unraisable("closing a Gymnasium environment stepped by gpfd");
      }
      keepNative_.reset();
      action_.reset();
      adapter_.reset();
    });
  }

  std::string name() const override { return name_; }
  Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override { return space_; }

  void reset(Rng& rng) override {
    const std::uint64_t seed = rng() >> 1;  // Gymnasium takes seeds >= 0.
    if (native_ != nullptr) {
      // What GpfdEnv.reset(seed=seed) does (gpfd.envs.seed64: the seed's low 64 bits).
      native_->seed(0, seed);
      native_->reset(nullptr, state_.data());
      checkNative("reset");
      return;
    }
    withPython([&] { copyState(adapter_.attr("reset")(seed)); });
  }

  std::span<const double> state() const override { return state_; }

  void setState(std::span<const double>) override {
    throw InputError("a Gymnasium environment cannot be set to a given state", name_);
  }

  env::StepResult step(std::span<const double> action) override {
    if (native_ != nullptr) {
      // What GpfdEnv.step does through the adapter: the action as the space's dtype.
      for (std::size_t c = 0; c < action.size(); ++c) {
        nativeAction_[c] = roundToFloat_ ? env::numpy_scalar::toFloat32(action[c]) : action[c];
      }
      double reward = 0.0;
      bool terminated = false, truncated = false;
      native_->step(nativeAction_.data(), {state_.data(), &reward, &terminated, &truncated});
      checkNative("step");
      return {reward, terminated, truncated};
    }
    return withPython([&]() -> env::StepResult {
      auto buffer = nb::cast<nb::ndarray<double, nb::c_contig>>(action_);
      std::copy(action.begin(), action.end(), buffer.data());
      const nb::tuple result = nb::cast<nb::tuple>(adapter_.attr("step")(action_));
      copyState(result[0]);
      return {nb::cast<double>(result[1]), nb::cast<bool>(result[2]), nb::cast<bool>(result[3])};
    });
  }

 private:
  // gpfd's own environment made from its Gymnasium id (gpfd.adapters.sources.native_single): its
  // C++ engine steps without Python, as GpfdEnv's reset and step call it.
  void bindNative() {
    const nb::object native =
        nb::module_::import_("gpfd.adapters.sources").attr("native_single")(name_, adapter_);
    if (native.is_none()) return;
    native_ = nb::cast<EnvBatch*>(native[0]);
    roundToFloat_ = nb::cast<bool>(native[1]);
    keepNative_ = native;
    nativeAction_.assign(space_.components, 0.0);
  }

  // The adapter's check of every observation, for the native path: a non-finite one raises there.
  void checkNative(const char* call) {
    for (const double v : state_) {
      if (std::isfinite(v)) continue;
      withPython([&] {
        auto obs = newArray<double>({state_.size()});
        std::copy(state_.begin(), state_.end(), obs.data());
        adapter_.attr("check_observation")(obs, call);
      });
      return;
    }
  }

  // The adapter has checked the observation: float64, finite, state_dim values.
  void copyState(nb::handle obs) {
    const auto array = nb::cast<ReadArray>(obs);
    std::copy(array.data(), array.data() + state_.size(), state_.begin());
  }

  std::string name_;
  nb::object adapter_;
  EnvBatch* native_ = nullptr;  // Owned by keepNative_'s environment.
  nb::object keepNative_;
  bool roundToFloat_ = false;  // A float32 action space: the adapter would round the action.
  std::vector<double> nativeAction_;
  nb::object action_;  // The float64 array the adapter receives the action in.
  std::vector<std::string> names_;
  std::vector<double> state_;
  env::ActionSpace space_;
};

}  // namespace

void bindPythonEnvironments(nb::module_& m) {
  m.def(
      "register_python_env",
      [](const std::string& name, const std::string& description) {
        auto& registry = env::Registry::global();
        forgetCachedTasks();  // The name may now make another environment.
        for (const auto& known : registry.names()) {
          if (known == name) return;  // gpfd.user_env keeps the current factory per name.
        }
        env::EnvInfo info;
        info.name = name;
        info.description = description;
        info.batch = pythonVectorForm(name);  // Where gpfd.adapters.sources finds a vector form.
        info.make = [name](const Params&) {
          return withPython([&]() -> std::unique_ptr<env::Environment> {
            nb::object adapter =
                nb::module_::import_("gpfd.adapters.user_env").attr("make_adapter")(name);
            return std::make_unique<PythonEnvironment>(name, std::move(adapter));
          });
        };
        registry.add(std::move(info));
      },
      nb::arg("name"), nb::arg("description"),
      "Registers a Gymnasium environment stepped in Python under `name` (once per process); "
      "gpfd.user_env.make_adapter(name) makes its instances.");
}

}  // namespace gpfd::python
