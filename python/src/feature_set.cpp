// python: the binding of gpfd.FeatureSet (python/gpfd/discovery/features.py adds load and parse).
// Calling a set on observations runs the JIT-compiled genome: evaluate() for one state, the batch
// kernel for a matrix of states, with the GIL released for batches.
#include "feature_set.hpp"

#include <fmt/format.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "bindings.hpp"
#include "gpfd/expr/export.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/expr/wire.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {

FeatureSet::FeatureSet(expr::FeaturesFile file, std::string name)
    : file_(std::move(file)),
      map_(std::make_shared<const jit::CompiledFeatureMap>(file_.genome, file_.variables.size())),
      name_(std::move(name)) {}

namespace {

using namespace nb::literals;
using ReadArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;
using WriteArray = nb::ndarray<double, nb::c_contig, nb::device::cpu>;

// Below this many states the GIL is kept: releasing and taking it back costs more than the work.
constexpr std::size_t kReleaseGilFrom = 16;

// Parses features text. Without `variables`, a file that names none is read over
// `fallbackVariables` (the environment's, when the caller knows it).
expr::FeaturesFile parseWithFallback(const std::string& text, const std::string& source,
                                     const std::string& env,
                                     const std::optional<expr::VariableNames>& variables,
                                     const std::optional<expr::VariableNames>& fallbackVariables) {
  if (variables) return expr::parseFeaturesFile(text, source, *variables, env);
  try {
    return expr::parseFeaturesFile(text, source, {}, env);
  } catch (const InputError&) {
    if (!fallbackVariables) throw;
    return expr::parseFeaturesFile(text, source, *fallbackVariables, env);
  }
}

std::string typeName(nb::handle value) { return pyText(value.type().attr("__name__")); }

// A float64 C-contiguous view of `obs`, without a copy when it already is one; other real dtypes
// are converted (one copy). TypeError for non-numeric or complex data.
ReadArray observations(nb::handle obs) {
  ReadArray view;
  if (nb::try_cast(obs, view, false)) return view;
  const nb::module_ np = numpy();
  nb::object array = np.attr("asarray")(obs);
  const std::string kind = nb::cast<std::string>(array.attr("dtype").attr("kind"));
  if (kind != "f" && kind != "i" && kind != "u") {
    throw nb::type_error(
        fmt::format("FeatureSet: observations must be real numbers, got dtype {} ({})",
                    pyText(array.attr("dtype")), typeName(obs))
            .c_str());
  }
  array = np.attr("ascontiguousarray")(array, "dtype"_a = np.attr("float64"));
  return nb::cast<ReadArray>(array);
}

// ValueError naming the first non-finite value of the n x dim matrix, if any.
void checkFinite(const double* values, std::size_t n, std::size_t dim,
                 const expr::VariableNames& names) {
  double probe = 0.0;  // NaN iff some value is NaN or infinite.
  for (std::size_t i = 0; i < n * dim; ++i) probe += values[i] * 0.0;
  if (!std::isnan(probe)) return;
  for (std::size_t i = 0; i < n * dim; ++i) {
    if (!std::isfinite(values[i])) {
      throw nb::value_error(fmt::format("FeatureSet: observation {} holds {} in column {} ({}); "
                                        "observations must be finite",
                                        i / dim, values[i], i % dim, names[i % dim])
                                .c_str());
    }
  }
}

nb::object call(const FeatureSet& set, nb::handle obs, nb::handle out) {
  const ReadArray in = observations(obs);
  const std::size_t dim = set.inputDim(), k = set.outputDim();
  const auto shapeText = [&] {
    std::string text = "(";
    for (std::size_t i = 0; i < in.ndim(); ++i)
      text += (i ? ", " : "") + std::to_string(in.shape(i));
    return text + (in.ndim() == 1 ? ",)" : ")");
  };
  if ((in.ndim() != 1 && in.ndim() != 2) || in.shape(in.ndim() - 1) != dim) {
    throw nb::value_error(fmt::format("FeatureSet: expected observations of shape ({},) or (N, "
                                      "{}) over {}, got shape {}",
                                      dim, dim, fmt::join(set.file().variables, ", "), shapeText())
                              .c_str());
  }
  const bool single = in.ndim() == 1;
  const std::size_t n = single ? 1 : in.shape(0);

  nb::object result;
  double* target = nullptr;
  if (out.is_none()) {
    if (single) {
      auto array = newArray<double>({k});
      target = array.data();
      result = nb::cast(array);
    } else {
      auto array = newArray<double>({n, k});
      target = array.data();
      result = nb::cast(array);
    }
  } else {
    WriteArray given;
    const bool fits = nb::try_cast(out, given, false) && given.ndim() == in.ndim() &&
                      (single ? given.shape(0) == k : given.shape(0) == n && given.shape(1) == k);
    if (!fits) {
      throw nb::value_error(
          fmt::format("FeatureSet: out must be a writable C-contiguous float64 array of shape {}",
                      single ? fmt::format("({},)", k) : fmt::format("({}, {})", n, k))
              .c_str());
    }
    target = given.data();
    result = nb::borrow(out);
  }

  const double* states = in.data();
  const auto& map = set.map();
  if (n < kReleaseGilFrom) {
    checkFinite(states, n, dim, set.file().variables);
    if (n == 1) {
      map.evaluate(states, target);
    } else if (n > 1) {
      map.evaluateBatch(states, n, target);
    }
    return result;
  }
  {
    nb::gil_scoped_release release;
    checkFinite(states, n, dim, set.file().variables);
    map.evaluateBatch(states, n, target);
  }
  return result;
}

// parse/load: the expected environment and variables come from gpfd.discovery.features.expectation,
// which knows gpfd's and Gymnasium's environments.
FeatureSet fromText(const std::string& text, const std::string& source, nb::handle env,
                    nb::handle variables, const nb::kwargs& params, const std::string& name) {
  const nb::tuple e = nb::cast<nb::tuple>(
      nb::module_::import_("gpfd.discovery.features").attr("expectation")(env, variables, params));
  return FeatureSet(parseWithFallback(text, source, nb::cast<std::string>(e[0]),
                                      nb::cast<std::optional<expr::VariableNames>>(e[1]),
                                      nb::cast<std::optional<expr::VariableNames>>(e[2])),
                    name);
}

std::string repr(const FeatureSet& set) {
  return fmt::format("FeatureSet({}{} features over {})",
                     set.file().env.empty() ? "" : "env='" + set.file().env + "', ",
                     set.outputDim(), fmt::join(set.file().variables, ", "));
}

}  // namespace

void bindFeatureSet(nb::module_& m) {
  nb::class_<FeatureSet>(m, "FeatureSet",
                         "Discovered features, compiled to native code. Call it on observations.")
      .def(
          "__init__",
          [](FeatureSet* self, const std::string& text, const std::string& source,
             const std::string& env, const std::optional<expr::VariableNames>& variables,
             const std::optional<expr::VariableNames>& fallbackVariables, const std::string& name) {
            new (self) FeatureSet(
                parseWithFallback(text, source, env, variables, fallbackVariables), name);
          },
          nb::arg("text"), nb::arg("source") = "<string>", nb::arg("env") = "",
          nb::arg("variables") = nb::none(), nb::arg("fallback_variables") = nb::none(),
          nb::arg("name") = "features")
      .def_static(
          "parse",
          [](const std::string& text, nb::handle env, nb::handle variables, nb::kwargs params) {
            return fromText(text, "<string>", env, variables, params, "features");
          },
          nb::arg("text"), nb::arg("env") = nb::none(), nb::arg("variables") = nb::none(),
          nb::arg("params"),
          "Features from text in the features-file format (or bare infix lines). `env` (a gpfd "
          "environment name, e.g. 'swimmer', or a Gymnasium environment) and `variables` say "
          "what the features read; keywords are the environment's parameters (segments=5).")
      .def_static(
          "load",
          [](const std::string& path, nb::handle env, nb::handle variables, nb::kwargs params) {
            return fromText(readFile(path), path, env, variables, params,
                            std::filesystem::path(path).stem().string());
          },
          nb::arg("path"), nb::arg("env") = nb::none(), nb::arg("variables") = nb::none(),
          nb::arg("params"), "Reads a features file (best.features, ...); see parse.")
      .def("__call__", &call, nb::arg("obs"), nb::arg("out") = nb::none(),
           "The features of one observation (shape (d,) -> (k,)) or of N (shape (N, d) -> (N, "
           "k)), as float64. `out`, if given, receives them (a C-contiguous float64 array).")
      .def_prop_ro(
          "env", [](const FeatureSet& s) { return s.file().env; },
          "The environment the features read: a gpfd environment ('cartpole') or a Gymnasium "
          "id; '' where none was named.")
      .def_prop_ro(
          "variables", [](const FeatureSet& s) { return s.file().variables; },
          "The names of the variables the features read, in the observation's order.")
      .def_prop_ro(
          "meta", [](const FeatureSet& s) { return s.file().meta; },
          "The features file's `# key: value` lines (experiment, seed, verdict, ...).")
      .def_prop_ro("name", &FeatureSet::name,
                   "The set's name: the features file's stem (best), else 'features'.")
      .def_prop_ro("input_dim", &FeatureSet::inputDim, "How many variables it reads: d.")
      .def_prop_ro("n_features", &FeatureSet::outputDim, "How many features it computes: k.")
      .def_prop_ro(
          "native", [](const FeatureSet& s) { return s.map().isNative(); },
          "Whether one observation runs JIT-compiled code.")
      .def_prop_ro(
          "native_batch", [](const FeatureSet& s) { return s.map().hasNativeBatch(); },
          "Whether batches run the JIT-compiled AVX2 kernel.")
      .def("__len__", &FeatureSet::outputDim)
      .def(
          "show",
          [](const FeatureSet& s, const std::string& format, bool simplify) {
            if (format != "infix" && format != "sexpr") {
              throw InputError("show prints infix or sexpr, not '" + format + "'", "format");
            }
            const auto genome = simplify ? expr::simplify(s.file().genome) : s.file().genome;
            return expr::exportAs(genome, s.file().variables, format);
          },
          nb::arg("format") = "infix", nb::arg("simplify") = false,
          "The features, one per line, as `gpfd features show` prints them.")
      .def(
          "export",
          [](const FeatureSet& s, const std::string& format, bool simplify) {
            const auto genome = simplify ? expr::simplify(s.file().genome) : s.file().genome;
            return expr::exportAs(genome, s.file().variables, format);
          },
          nb::arg("format") = "python", nb::arg("simplify") = false,
          "The features as code or text, as `gpfd features export` writes them: infix, sexpr, "
          "c, python (a NumPy function) or latex.")
      .def(
          "save",
          [](const FeatureSet& s, const std::string& path) {
            expr::writeFeaturesFile(path, s.file());
          },
          nb::arg("path"), "Writes a features file (atomically).")
      .def(
          "to_text", [](const FeatureSet& s) { return expr::formatFeaturesFile(s.file()); },
          "The features file's text.")
      .def("__repr__", &repr)
      .def("__getstate__",
           [](const FeatureSet& s) {
             return std::make_pair(expr::formatFeaturesFile(s.file()), s.name());
           })
      .def("__setstate__", [](FeatureSet& s, const std::pair<std::string, std::string>& state) {
        new (&s) FeatureSet(expr::parseFeaturesFile(state.first, "<pickle>"), state.second);
      });
  // The genome wire format of the MPI and Python workers (gpfd/expr/wire.hpp), for its tests.
  m.def(
      "genome_to_wire",
      [](const FeatureSet& s) {
        const std::string record = expr::wire::encodeGenome(s.file().genome);
        return nb::bytes(record.data(), record.size());
      },
      nb::arg("features"), "The record of the features' genome in the genome wire format.");
  m.def(
      "genome_from_wire",
      [](const nb::bytes& record, const expr::VariableNames& variables, const std::string& env) {
        expr::FeaturesFile file;
        file.env = env;
        file.variables = variables;
        // As the workers read it (trial_fitness_group, the MPI worker): checked over variables.
        file.genome = expr::wire::decodeGenome(std::string_view(record.c_str(), record.size()),
                                               static_cast<int>(variables.size()));
        return FeatureSet(std::move(file), "wire");
      },
      nb::arg("record"), nb::arg("variables"), nb::arg("env") = "",
      "The features of a genome wire record over `variables`.");
}

}  // namespace gpfd::python
