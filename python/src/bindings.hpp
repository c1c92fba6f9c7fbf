// python: what the binding files of the extension module gpfd._core share: their entry points and
// the NumPy array helpers.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>

#include "gpfd/env/environment.hpp"

namespace gpfd::python {

namespace nb = nanobind;

// A new C-contiguous NumPy array of `shape` that owns its (uninitialised) memory.
template <typename T>
nb::ndarray<nb::numpy, T> newArray(std::span<const std::size_t> shape) {
  std::size_t count = 1;
  for (std::size_t n : shape) count *= n;
  T* data = new T[count > 0 ? count : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<T*>(p); });
  return nb::ndarray<nb::numpy, T>(data, shape.size(), shape.data(), owner);
}
template <typename T>
nb::ndarray<nb::numpy, T> newArray(std::initializer_list<std::size_t> shape) {
  return newArray<T>(std::span<const std::size_t>(shape.begin(), shape.size()));
}

// str(value), as Python prints it.
inline std::string pyText(nb::handle value) {
  return nb::cast<std::string>(nb::steal<nb::str>(PyObject_Str(value.ptr())));
}

// `object` held for code that copies it without the GIL (a std::function the engine copies): the
// copies share one reference, and the last one releases it with the GIL taken. Call with the GIL.
inline std::shared_ptr<const nb::object> heldWithGil(nb::object object) {
  return {new nb::object(std::move(object)), [](const nb::object* held) {
            const nb::gil_scoped_acquire gil;
            delete held;
          }};
}

// The numpy module (imported once by Python, then a dictionary look-up).
inline nb::module_ numpy() { return nb::module_::import_("numpy"); }

// Environment parameters given as Python keywords, as the text the registry reads: str as is,
// bool as true/false, int and float in shortest round-trip form. TypeError for anything else.
Params paramsFromDict(const nb::dict& values, const std::string& where);
// Parameter values as Python values of their declared types (ParamSpec::Type: float, int, bool;
// str for text and for a name `specs` does not declare); paramsFromDict takes them back.
nb::dict typedParams(const Params& params, const std::vector<ParamSpec>& specs);

// The batched form of the environment registered from Python as `name`: its vector form, where
// gpfd.adapters.sources finds one (python_vector_environment.cpp).
env::BatchForm pythonVectorForm(const std::string& name);

void bindFeatureSet(nb::module_& m);
void bindEnvironments(nb::module_& m);
// After bindEnvironments: pickling and Tetris' board on EnvBatch (env_state_bindings.cpp).
void bindEnvironmentState(nb::module_& m);
void bindPythonEnvironments(nb::module_& m);
void bindTwins(nb::module_& m);        // twin_bindings.cpp
void bindTwinVectors(nb::module_& m);  // twin_vector_bindings.cpp
void bindDiscovery(nb::module_& m);
// _core.train_runs_group: the worker processes' learning runs (trial_runner.cpp).
void bindTrialRunner(nb::module_& m);

}  // namespace gpfd::python
