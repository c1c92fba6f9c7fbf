// python: the twins of Gymnasium's classic-control tasks (env/gymnasium_twin.hpp) as
// gpfd._core.Twin, which gpfd.twins drives: Gymnasium's reset(seed=...) and step, the observation
// as a float32 array.
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "gpfd/env/gymnasium_twin.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

using Kind = env::numpy_scalar::Kind;

class Twin {
 public:
  Twin(const std::string& id, const Params& params) {
    auto made = env::Registry::global().make(id, params);
    twin_.reset(dynamic_cast<env::GymnasiumTwin*>(made.get()));
    if (twin_ == nullptr) throw InputError(id + " is not a twin of a Gymnasium task", "Twin");
    made.release();
  }

  nb::ndarray<nb::numpy, float> reset(const std::optional<std::vector<std::uint32_t>>& seed) {
    if (seed) {
      twin_->resetWithSeed(*seed);
    } else {
      twin_->resetWithoutSeed();
    }
    return observation();
  }

  nb::tuple step(const std::vector<double>& action, const std::string& kind) {
    const env::StepResult r = twin_->stepAs(action, kindOf(kind));
    return nb::make_tuple(observation(), r.reward, r.terminated, r.truncated);
  }

  nb::ndarray<nb::numpy, float> observation() const {
    const auto state = twin_->state();
    auto out = newArray<float>({state.size()});
    for (std::size_t i = 0; i < state.size(); ++i) out.data()[i] = static_cast<float>(state[i]);
    return out;
  }

  const env::GymnasiumTwin& twin() const { return *twin_; }
  env::GymnasiumTwin& twin() { return *twin_; }

 private:
  static Kind kindOf(const std::string& kind) {
    if (kind == "float32") return Kind::Float32;
    if (kind == "float64") return Kind::Float64;
    if (kind == "python") return Kind::PyFloat;
    throw InputError("an action's kind is float32, float64 or python, got " + kind, "Twin.step");
  }

  std::unique_ptr<env::GymnasiumTwin> twin_;
};

}  // namespace

void bindTwins(nb::module_& m) {
  nb::class_<Twin>(m, "Twin", "A twin of a Gymnasium classic-control task (gpfd.twins drives it).")
      .def(nb::init<const std::string&, const Params&>(), nb::arg("id"), nb::arg("params"))
      .def("reset", &Twin::reset, nb::arg("seed").none(),
           "Gymnasium's reset(seed=s), s as 32-bit words (least significant first), or reset() "
           "for None; the observation (float32).")
      .def("step", &Twin::step, nb::arg("action"), nb::arg("kind"),
           "(observation, reward, terminated, truncated) of one step; kind: the NumPy type of "
           "the action's elements (float32, float64 or python).")
      .def("observation", &Twin::observation)
      .def("set_state", [](Twin& t, const std::vector<double>& s) { t.twin().setState(s); })
      .def("snapshot", [](const Twin& t) { return t.twin().snapshot(); })
      .def("restore",
           [](Twin& t, const std::vector<std::uint64_t>& words) { t.twin().restore(words); })
      .def_prop_ro("params", [](const Twin& t) { return t.twin().params(); });
}

}  // namespace gpfd::python
