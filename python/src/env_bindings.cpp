// python: the binding of EnvBatch as gpfd._core.EnvBatch, which gpfd.envs (one instance) and
// gpfd.vector (N instances, one C++ call per step) drive.
#include <fmt/format.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>

#include "bindings.hpp"
#include "env_batch.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

using namespace nb::literals;
using ReadArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;
using MaskArray = nb::ndarray<const bool, nb::c_contig, nb::device::cpu>;

// Instance i's legal actions, shaped as the action space's choices (Tetris: orientations x
// columns).
nb::ndarray<nb::numpy, bool> legalActions(const EnvBatch& batch, std::size_t i) {
  const auto& choices = batch.actionSpace().choices;
  std::vector<std::size_t> shape(choices.begin(), choices.end());
  auto out = newArray<bool>(shape);
  batch.legalActions(i, out.data());
  return out;
}

// Every instance's legal actions: n x the choices.
nb::ndarray<nb::numpy, bool> allLegalActions(const EnvBatch& batch) {
  const auto& choices = batch.actionSpace().choices;
  std::vector<std::size_t> shape{batch.size()};
  shape.insert(shape.end(), choices.begin(), choices.end());
  auto out = newArray<bool>(shape);
  for (std::size_t i = 0; i < batch.size(); ++i) {
    batch.legalActions(i, out.data() + i * batch.actionMaskSize());
  }
  return out;
}

// One action as actionComponents() doubles: a number, or anything NumPy reads as that many.
std::vector<double> oneAction(const EnvBatch& batch, nb::handle action) {
  const std::size_t components = batch.actionComponents();
  std::vector<double> values(components);
  // A Python or NumPy scalar (arrays have a length, even 0-d ones).
  if (components == 1 && nb::hasattr(action, "__float__") && !nb::hasattr(action, "__len__")) {
    values[0] = nb::cast<double>(nb::float_(action));
    return values;
  }
  const nb::module_ np = numpy();
  const auto array = nb::cast<ReadArray>(
      np.attr("ascontiguousarray")(action, "dtype"_a = np.attr("float64")).attr("ravel")());
  if (array.size() != components) {
    throw InputError(fmt::format("an action has {} component{}, got {} values", components,
                                 components == 1 ? "" : "s", array.size()),
                     batch.prototype().name() + " action");
  }
  std::copy(array.data(), array.data() + components, values.begin());
  return values;
}

nb::tuple stepOne(EnvBatch& batch, nb::handle action) {
  const auto values = oneAction(batch, action);
  auto obs = newArray<double>({batch.stateDim()});
  double reward = 0.0;
  bool terminated = false, truncated = false;
  batch.step(values.data(), {obs.data(), &reward, &terminated, &truncated});
  return nb::make_tuple(obs, reward, terminated, truncated);
}

nb::tuple stepAll(EnvBatch& batch, const ReadArray& actions) {
  const std::size_t n = batch.size(), dim = batch.stateDim();
  if (actions.size() != n * batch.actionComponents()) {
    throw InputError(
        fmt::format("expected {} actions of {} component{} ({} values), got {} values", n,
                    batch.actionComponents(), batch.actionComponents() == 1 ? "" : "s",
                    n * batch.actionComponents(), actions.size()),
        "actions");
  }
  auto obs = newArray<double>({n, dim});
  auto rewards = newArray<double>({n});
  auto terminated = newArray<bool>({n});
  auto truncated = newArray<bool>({n});
  BatchStep out{obs.data(), rewards.data(), terminated.data(), truncated.data()};
  nb::object finalObs = nb::none(), finalMask = nb::none(), finalLegal = nb::none();
  if (batch.autoreset() == Autoreset::SameStep) {
    auto lastObs = newArray<double>({n, dim});
    auto lastMask = newArray<bool>({n});
    out.finalObs = lastObs.data();
    out.finalMask = lastMask.data();
    finalObs = nb::cast(lastObs);
    finalMask = nb::cast(lastMask);
    if (batch.stateDependentActions()) {
      auto legal = allLegalActions(batch);  // Shaped n x choices; the step overwrites its rows.
      out.finalLegal = legal.data();
      finalLegal = nb::cast(legal);
    }
  }
  {
    nb::gil_scoped_release release;
    batch.step(actions.data(), out);
  }
  return nb::make_tuple(obs, rewards, terminated, truncated, finalObs, finalMask, finalLegal);
}

nb::dict afterstates(const EnvBatch& batch, std::size_t i) {
  const auto* tetris = dynamic_cast<const env::Tetris*>(batch.scalarInstance(i));
  if (tetris == nullptr) {
    throw InputError("afterstates exist for Tetris only", batch.prototype().name());
  }
  env::TetrisAfterstates all;
  tetris->afterstates(all);
  const std::size_t k = all.placements.size(), dim = all.featureDim;
  auto actions = newArray<std::int64_t>({k, 2});
  auto features = newArray<double>({k, dim});
  auto rewards = newArray<double>({k});
  auto gameOver = newArray<bool>({k});
  for (std::size_t p = 0; p < k; ++p) {
    actions.data()[2 * p] = all.placements[p].orientation;
    actions.data()[2 * p + 1] = all.placements[p].column;
    rewards.data()[p] = all.placements[p].rowsRemoved;
    gameOver.data()[p] = all.placements[p].gameOver;
  }
  std::copy(all.features.begin(), all.features.end(), features.data());
  nb::dict out;
  out["actions"] = actions;
  out["features"] = features;
  out["rewards"] = rewards;
  out["game_over"] = gameOver;
  return out;
}

}  // namespace

void bindEnvironments(nb::module_& m) {
  nb::class_<EnvBatch>(m, "EnvBatch", "N instances of one gpfd environment, stepped together.")
      .def(
          "__init__",
          [](EnvBatch* self, const std::string& name, const nb::dict& params, std::size_t n,
             const std::string& autoreset, const std::string& engine) {
            new (self) EnvBatch(name, paramsFromDict(params, name), n, parseAutoreset(autoreset),
                                parseEngine(engine));
          },
          nb::arg("name"), nb::arg("params") = nb::dict(), nb::arg("num_envs") = 1,
          nb::arg("autoreset") = "next_step", nb::arg("engine") = "auto",
          "engine: auto (batched where the environment has a batched form), loop (one scalar "
          "environment per instance, the reference) or batched (InputError where there is none).")
      .def_prop_ro("num_envs", &EnvBatch::size)
      .def_prop_ro(
          "engine", [](const EnvBatch& b) { return b.batched() ? "batched" : "loop"; },
          "How the instances step: batched (one call of the batched environment) or loop.")
      .def_prop_ro("name", [](const EnvBatch& b) { return b.prototype().name(); })
      .def_prop_ro(
          "params",
          [](const EnvBatch& b) {
            const env::Environment& e = b.prototype();
            return typedParams(e.params(), env::Registry::global().info(e.name()).params);
          },
          "Every parameter with its value (float, int, bool or str, as declared), defaults "
          "filled in.")
      .def_prop_ro("state_names", [](const EnvBatch& b) { return b.prototype().stateNames(); })
      .def_prop_ro("action_components", &EnvBatch::actionComponents)
      .def_prop_ro(
          "action_choices", [](const EnvBatch& b) { return b.actionSpace().choices; },
          "The number of choices of each discrete action component; empty for continuous "
          "actions.")
      .def_prop_ro("state_dependent_actions", &EnvBatch::stateDependentActions,
                   "Whether the legal actions depend on the state (action_mask says which).")
      .def_prop_ro("action_low", [](const EnvBatch& b) { return b.actionSpace().low; })
      .def_prop_ro("action_high", [](const EnvBatch& b) { return b.actionSpace().high; })
      .def_prop_ro("action_names", [](const EnvBatch& b) { return b.actionSpace().names; })
      .def("seed", &EnvBatch::seed, nb::arg("index"), nb::arg("seed"))
      .def(
          "reset",
          [](EnvBatch& b, std::optional<MaskArray> mask) {
            if (mask && mask->size() != b.size()) {
              throw InputError(
                  fmt::format("reset_mask needs {} values, got {}", b.size(), mask->size()),
                  "reset_mask");
            }
            auto obs = newArray<double>({b.size(), b.stateDim()});
            b.reset(mask ? mask->data() : nullptr, obs.data());
            return obs;
          },
          nb::arg("mask") = nb::none(), "Resets the instances in mask (all by default).")
      .def(
          "reset_one",
          [](EnvBatch& b) {
            auto obs = newArray<double>({b.stateDim()});
            b.reset(nullptr, obs.data());
            return obs;
          },
          "Resets a batch of one and returns its observation.")
      .def("step", &stepAll, nb::arg("actions"),
           "Steps every instance: (obs, rewards, terminated, truncated, final_obs, final_mask, "
           "final_action_masks); the last three are None unless autoreset is same_step, the last "
           "unless the legal actions also depend on the state.")
      .def("step_one", &stepOne, nb::arg("action"),
           "Steps a batch of one: (obs, reward, terminated, truncated).")
      .def(
          "state",
          [](const EnvBatch& b, std::size_t i) {
            auto obs = newArray<double>({b.stateDim()});
            b.state(i, obs.data());
            return obs;
          },
          nb::arg("index") = 0)
      .def(
          "set_state",
          [](EnvBatch& b, std::size_t i, const ReadArray& state) {
            b.setState(i, std::span<const double>(state.data(), state.size()));
          },
          nb::arg("index"), nb::arg("state"))
      .def("action_mask", &legalActions, nb::arg("index") = 0,
           "Discrete actions: instance index's legal ones now (bool, shaped as action_choices).")
      .def("action_masks", &allLegalActions,
           "Discrete actions: every instance's legal ones now (num_envs x action_choices).")
      .def("afterstates", &afterstates, nb::arg("index") = 0,
           "Tetris: every legal placement with the state it leads to.");
}

}  // namespace gpfd::python
