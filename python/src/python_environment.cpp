// python: a Gymnasium environment stepped in Python, as a gpfd environment, so that discovery and
// assessment run on it unchanged. The Python side (gpfd.user_env.Adapter) checks the spaces and
// every observation and turns the environment's exceptions into clear errors; this side holds the
// GIL only while it calls Python.
#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <vector>

#include "bindings.hpp"
#include "gpfd/util/error.hpp"

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
      space_.choices = nb::cast<int>(adapter_.attr("choices"));
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
  }
  ~PythonEnvironment() override {
    nb::gil_scoped_acquire gil;
    action_.reset();
    adapter_.reset();
  }

  std::string name() const override { return name_; }
  Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override { return space_; }

  void reset(Rng& rng) override {
    const std::uint64_t seed = rng() >> 1;  // Gymnasium takes seeds >= 0.
    nb::gil_scoped_acquire gil;
    copyState(adapter_.attr("reset")(seed));
  }

  std::span<const double> state() const override { return state_; }

  void setState(std::span<const double>) override {
    throw InputError("a Gymnasium environment cannot be set to a given state", name_);
  }

  env::StepResult step(std::span<const double> action) override {
    nb::gil_scoped_acquire gil;
    auto buffer = nb::cast<nb::ndarray<double, nb::c_contig>>(action_);
    std::copy(action.begin(), action.end(), buffer.data());
    const nb::tuple result = nb::cast<nb::tuple>(adapter_.attr("step")(action_));
    copyState(result[0]);
    return {nb::cast<double>(result[1]), nb::cast<bool>(result[2]), nb::cast<bool>(result[3])};
  }

 private:
  // The adapter has checked the observation: float64, finite, state_dim values.
  void copyState(nb::handle obs) {
    const auto array = nb::cast<ReadArray>(obs);
    std::copy(array.data(), array.data() + state_.size(), state_.begin());
  }

  std::string name_;
  nb::object adapter_;
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
        for (const auto& known : registry.names()) {
          if (known == name) return;  // gpfd.user_env keeps the current factory per name.
        }
        env::EnvInfo info;
        info.name = name;
        info.description = description;
        info.batch = pythonVectorForm(name);  // Where gpfd.vector_source finds a vector form.
        info.make = [name](const Params&) -> std::unique_ptr<env::Environment> {
          nb::gil_scoped_acquire gil;
          nb::object adapter = nb::module_::import_("gpfd.user_env").attr("make_adapter")(name);
          return std::make_unique<PythonEnvironment>(name, std::move(adapter));
        };
        registry.add(std::move(info));
      },
      nb::arg("name"), nb::arg("description"),
      "Registers a Gymnasium environment stepped in Python under `name` (once per process); "
      "gpfd.user_env.make_adapter(name) makes its instances.");
}

}  // namespace gpfd::python
