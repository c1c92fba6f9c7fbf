// python: the extension module gpfd._core. The Python package gpfd (python/gpfd) is the public
// face; this module holds what runs in C++: feature sets, environments, discovery, assessment.
#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>

#include "bindings.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"
#include "gpfd/util/params.hpp"
#include "gpfd/version.hpp"

namespace gpfd::python {
namespace {

// gpfd::InputError becomes gpfd.InputError (a ValueError) with the message "what (where)", the
// form the command line prints.
void bindErrors(nb::module_& m) {
  static PyObject* type =
      PyErr_NewExceptionWithDoc("gpfd._core.InputError",
                                "Bad input to gpfd: a parameter, a config, a features file, an "
                                "argument. The message names what and where.",
                                PyExc_ValueError, nullptr);
  m.attr("InputError") = nb::handle(type);
  nb::register_exception_translator(
      [](const std::exception_ptr& p, void*) {
        try {
          std::rethrow_exception(p);
        } catch (const InputError& e) {
          PyErr_SetString(type, e.message().c_str());
        }
      },
      nullptr);
}

// The registry as Python sees it: names, descriptions and declared parameters.
void bindRegistry(nb::module_& m) {
  m.def("env_names", [] { return env::Registry::global().names(); });
  m.def(
      "env_description",
      [](const std::string& name) { return env::Registry::global().info(name).description; },
      nb::arg("name"));
  m.def(
      "env_params",
      [](const std::string& name) {
        nb::list out;
        for (const auto& spec : env::Registry::global().info(name).params) {
          out.append(nb::make_tuple(spec.name, spec.defaultValue, spec.meaning));
        }
        return out;
      },
      nb::arg("name"), "The declared parameters of an environment: (name, default, meaning).");
}

}  // namespace

Params paramsFromDict(const nb::dict& values, const std::string& where) {
  Params params;
  for (auto [key, value] : values) {
    const std::string name = pyText(key);
    std::string text;
    if (nb::isinstance<nb::bool_>(value)) {
      text = nb::cast<bool>(value) ? "true" : "false";
    } else if (nb::isinstance<nb::str>(value)) {
      text = nb::cast<std::string>(value);
    } else if (PyIndex_Check(value.ptr())) {  // int, numpy integers
      text = pyText(nb::int_(value));
    } else if (PyFloat_Check(value.ptr()) || nb::hasattr(value, "__float__")) {
      text = numberText(nb::cast<double>(nb::float_(value)));
    } else {
      throw nb::type_error(
          fmt::format("{}: parameter '{}' must be a number, a bool or a string, not {}", where,
                      name, pyText(value.type().attr("__name__")))
              .c_str());
    }
    params[name] = text;
  }
  return params;
}

nb::dict typedParams(const Params& params, const std::vector<ParamSpec>& specs) {
  nb::dict out;
  for (const auto& [name, text] : params) {
    const auto spec = std::find_if(specs.begin(), specs.end(),
                                   [&](const ParamSpec& s) { return s.name == name; });
    const ParamSpec::Type type = spec == specs.end() ? ParamSpec::Type::Text : spec->type;
    const char* key = name.c_str();
    switch (type) {
      case ParamSpec::Type::Real:
        out[key] = parseNumber(text, name);
        break;
      case ParamSpec::Type::Integer:
        out[key] = parseInteger(text, name);
        break;
      case ParamSpec::Type::Flag:
        out[key] = parseFlag(text, name);
        break;
      case ParamSpec::Type::Text:
        out[key] = text;
        break;
    }
  }
  return out;
}

NB_MODULE(_core, m) {
  m.doc() = "gpfd's C++ core: feature sets, environments, discovery and assessment.";
  m.attr("__version__") = std::string(kVersion);
  m.attr("revision") = std::string(kRevision);
  bindErrors(m);
  bindRegistry(m);
  bindFeatureSet(m);
  bindEnvironments(m);
  bindEnvironmentState(m);
  bindPythonEnvironments(m);
  bindTwins(m);
  bindTwinVectors(m);
  bindDiscovery(m);
  bindTrialRunner(m);
}

}  // namespace gpfd::python
