// python: the vector form of an environment stepped in Python (a Gymnasium VectorEnv: a
// vector_entry_point, an EnvPool task or the user's factory) as gpfd's batched environment
// (env/batch.hpp), so that the lockstep player advances all the episodes of a call with one call
// of the vector environment's step per time step. gpfd.vector_source.VectorAdapter makes, seeds,
// resets and checks the vector environment and words every error; this side writes the actions,
// calls step and reads what it returns, holding the GIL only meanwhile. gpfd's own vector
// environment (gpfd.vector.GpfdVectorEnv, whose step is a thin wrapper over its C++ engine
// EnvBatch) is stepped through that engine directly, without Python or the GIL.
//
// Lanes: the player compacts its lanes as episodes end (moveLane), but a vector environment cannot
// move an episode from one sub-environment to another, so logical lane l plays in sub-environment
// physical_[l]. Sub-environments that play no episode step along with the others (a vector step
// steps all); what they return is not read. Episodes start only in resetAll, all together, so
// every autoreset mode gives the same episodes: the step that ends an episode is booked and its
// lane retired before any autoreset matters (same-step: the final observation comes from
// info["final_obs"]; disabled: a sub-environment whose episode ended is reset through
// options={"reset_mask": ...} before it is stepped again).
#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "bindings.hpp"
#include "env_batch.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

// An array returned by the vector environment, read in place: float64, float32, bool or a
// 32/64-bit integer, any strides.
class ReadView {
 public:
  // False when `value` is not such an array of `ndim` dimensions with `rows` rows (and `cols`
  // columns for two).
  bool bind(nb::handle value, std::size_t ndim, std::size_t rows, std::size_t cols = 1) {
    if (!nb::try_cast(value, array_, false) || array_.ndim() != ndim) return false;
    raw_ = array_.data();
    if (array_.shape(0) != rows || (ndim == 2 && array_.shape(1) != cols)) return false;
    const nb::dlpack::dtype type = array_.dtype();
    if (type == nb::dtype<double>()) {
      kind_ = Kind::F64;
    } else if (type == nb::dtype<float>()) {
      kind_ = Kind::F32;
    } else if (type == nb::dtype<bool>()) {
      kind_ = Kind::Bool;
    } else if (type == nb::dtype<std::int64_t>()) {
      kind_ = Kind::I64;
    } else if (type == nb::dtype<std::int32_t>()) {
      kind_ = Kind::I32;
    } else {
      return false;
    }
    rowStride_ = array_.stride(0);
    colStride_ = ndim == 2 ? array_.stride(1) : 0;
    return true;
  }
  // A C++ array of `rows` x `cols`, row-major (gpfd's own vector environment's buffers).
  void bindRaw(const double* data, std::size_t cols) {
    raw_ = data;
    kind_ = Kind::F64;
    rowStride_ = static_cast<std::int64_t>(cols);
    colStride_ = 1;
  }
  void bindRaw(const bool* data) {
    raw_ = data;
    kind_ = Kind::Bool;
    rowStride_ = 1;
    colStride_ = 0;
  }
  bool isBool() const { return kind_ == Kind::Bool; }
  bool isFloat() const { return kind_ == Kind::F64 || kind_ == Kind::F32; }

  double at(std::size_t row, std::size_t col = 0) const {
    const std::int64_t i =
        static_cast<std::int64_t>(row) * rowStride_ + static_cast<std::int64_t>(col) * colStride_;
    switch (kind_) {
      case Kind::F64:
        return static_cast<const double*>(raw_)[i];
      case Kind::F32:
        return static_cast<const float*>(raw_)[i];
      case Kind::Bool:
        return static_cast<const bool*>(raw_)[i] ? 1.0 : 0.0;
      case Kind::I64:
        return static_cast<double>(static_cast<const std::int64_t*>(raw_)[i]);
      case Kind::I32:
        return static_cast<const std::int32_t*>(raw_)[i];
    }
    return 0.0;
  }

 private:
  enum class Kind { F64, F32, Bool, I64, I32 };
  nb::ndarray<nb::ro, nb::device::cpu> array_;
  const void* raw_ = nullptr;
  Kind kind_ = Kind::F64;
  std::int64_t rowStride_ = 0, colStride_ = 0;
};

// What the batched form needs of its scalar environment: its name, variables and action space
// (BatchEnvironment::scalar). Its lanes live in the vector environment, so it plays no episode;
// unlike a copy of the Python environment, it makes no Gymnasium environment.
class ScalarShape final : public env::Environment {
 public:
  explicit ScalarShape(const env::Environment& of)
      : name_(of.name()), params_(of.params()), names_(of.stateNames()), space_(of.actionSpace()) {}
  std::string name() const override { return name_; }
  Params params() const override { return params_; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override { return space_; }
  void reset(Rng&) override { refuse(); }
  std::span<const double> state() const override { return {}; }
  void setState(std::span<const double>) override { refuse(); }
  env::StepResult step(std::span<const double>) override { refuse(); }

 private:
  [[noreturn]] static void refuse() {
    throw std::logic_error("the vector form's scalar shape plays no episode");
  }
  std::string name_;
  Params params_;
  std::vector<std::string> names_;
  env::ActionSpace space_;
};

class PythonVectorBatch final : public env::BatchEnvironment {
 public:
  // `adapter` is a gpfd.vector_source.VectorAdapter. Called with the GIL held.
  PythonVectorBatch(std::unique_ptr<env::Environment> scalar, env::BatchIsa isa, nb::object adapter)
      : BatchEnvironment(std::move(scalar), isa), adapter_(std::move(adapter)) {}

  ~PythonVectorBatch() override {
    nb::gil_scoped_acquire gil;
    try {
      adapter_.attr("close")();
    } catch (nb::python_error& e) {
      e.discard_as_unraisable(__func__);
    }
    keep_.clear();
    finals_.reset();
    step_.reset();
    actions_.reset();
    adapter_.reset();
  }

  void reset(Rng& /*rng*/, const env::BatchBuffers& /*io*/, std::size_t /*lane*/) override {
    throw InputError("the vector form of " + scalar().name() +
                         " starts the episodes of all its lanes together (resetAll), not one "
                         "lane alone",
                     "vector environment");
  }

  void resetAll(std::span<Rng> rngs, const env::BatchBuffers& io) override {
    // Lane l's seed is the draw PythonEnvironment::reset makes from the same stream, so that the
    // stream then goes on to the same actions and a vector form that seeds each lane plays the
    // per-environment path's episodes.
    std::vector<std::uint64_t> seeds(rngs.size());
    for (std::size_t l = 0; l < rngs.size(); ++l) seeds[l] = rngs[l]() >> 1;
    nb::gil_scoped_acquire gil;
    const nb::object obs = adapter_.attr("reset")(seeds);
    lanes_ = nb::cast<std::size_t>(adapter_.attr("num_envs"));
    step_ = adapter_.attr("step_function");
    actions_ = adapter_.attr("actions");
    bindActions();
    bindNative(adapter_.attr("native_engine"));
    start_ = nb::cast<std::int64_t>(adapter_.attr("start"));
    disabled_ = nb::cast<bool>(adapter_.attr("resets_ended"));
    elapsedKey_ = nb::cast<std::string>(adapter_.attr("elapsed_key"));
    physical_.resize(lanes_);
    std::iota(physical_.begin(), physical_.end(), std::size_t{0});
    ended_.assign(lanes_, 0);
    steps_ = 0;
    ReadView view;
    if (!view.bind(obs, 2, lanes_, stateDim())) {
      throw std::logic_error("VectorAdapter.reset must return float64 observations (N, d)");
    }
    for (std::size_t l = 0; l < rngs.size(); ++l) {
      for (std::size_t i = 0; i < stateDim(); ++i) io.state[i * io.stride + l] = view.at(l, i);
      io.elapsed[l] = 0;
    }
  }

  void step(const env::BatchBuffers& io) const override {
    ++steps_;
    if (native_ != nullptr) {
      nativeStep(io);
      return;
    }
    nb::gil_scoped_acquire gil;
    keep_.clear();
    if (disabled_) resetEnded(io);
    writeActions(io);
    nb::object result;
    try {
      result = step_(actions_);
    } catch (nb::python_error& e) {
      adapter_.attr("step_raised")(e.value(), steps_, activeLanes(io.lanes));
      throw std::logic_error("VectorAdapter.step_raised must raise");
    }
    if (!PyTuple_Check(result.ptr()) || PyTuple_GET_SIZE(result.ptr()) != 5) {
      adapter_.attr("bad_result")(result, steps_);
      throw std::logic_error("VectorAdapter.bad_result must raise");
    }
    const nb::handle info(PyTuple_GET_ITEM(result.ptr(), 4));
    Outputs out;
    out.obs = read(PyTuple_GET_ITEM(result.ptr(), 0), "observations", 2, stateDim());
    out.reward = read(PyTuple_GET_ITEM(result.ptr(), 1), "rewards", 1);
    out.terminated = read(PyTuple_GET_ITEM(result.ptr(), 2), "terminated", 1);
    out.truncated = read(PyTuple_GET_ITEM(result.ptr(), 3), "truncated", 1);
    // Same-step autoreset: the observation that ended an episode is in info["final_obs"].
    if (hasItem(info, "_final_obs")) {
      finals_ = nb::cast<nb::tuple>(adapter_.attr("final_observations")(info, steps_));
      out.finalMask = read(finals_[0], "info['_final_obs']", 1);
      out.finalObs = read(finals_[1], "info['final_obs']", 2, stateDim());
      out.withFinal = true;
    }
    if (!elapsedKey_.empty() && hasItem(info, elapsedKey_.c_str())) {
      out.elapsed = read(nb::handle(PyDict_GetItemString(info.ptr(), elapsedKey_.c_str())),
                         "info['" + elapsedKey_ + "']", 1);
      out.withElapsed = true;
    }
    book(io, out);
  }

  void moveLane(std::size_t from, std::size_t to) override {
    std::swap(physical_[from], physical_[to]);
  }

 private:
  // What one vector step returned, read in place: rows are sub-environments.
  struct Outputs {
    ReadView obs, reward, terminated, truncated;
    ReadView finalMask, finalObs;  // withFinal: info["_final_obs"], info["final_obs"].
    ReadView elapsed;              // withElapsed: info[elapsedKey_].
    bool withFinal = false, withElapsed = false;
  };

  // Lane by lane, what the lane's sub-environment returned, checked, into the player's buffers.
  void book(const env::BatchBuffers& io, const Outputs& out) const {
    for (std::size_t l = 0; l < io.lanes; ++l) {
      const std::size_t p = physical_[l];
      const bool ended = out.terminated.at(p) != 0.0 || out.truncated.at(p) != 0.0;
      ended_[p] = ended ? 1 : 0;
      ++io.elapsed[l];
      const bool isFinal = out.withFinal && out.finalMask.at(p) != 0.0;
      if (isFinal && !ended) resetOnItsOwn(p, io.elapsed[l], "info['_final_obs'] marks it");
      if (out.withElapsed && out.elapsed.at(p) != io.elapsed[l]) {
        resetOnItsOwn(p, io.elapsed[l],
                      fmt::format("info['{}'] says {}", elapsedKey_, out.elapsed.at(p)));
      }
      const ReadView& row = isFinal ? out.finalObs : out.obs;
      for (std::size_t i = 0; i < stateDim(); ++i) {
        const double v = row.at(p, i);
        if (!std::isfinite(v)) badObservation(p, io.elapsed[l], i, v);
        io.state[i * io.stride + l] = v;
      }
      io.reward[l] = out.reward.at(p);
      io.terminated[l] = out.terminated.at(p) != 0.0 ? 1 : 0;
      io.truncated[l] = out.truncated.at(p) != 0.0 ? 1 : 0;
    }
    for (std::size_t l = io.lanes; l < lanes_; ++l) {
      const std::size_t p = physical_[l];
      ended_[p] = ended_[p] || out.terminated.at(p) != 0.0 || out.truncated.at(p) != 0.0;
    }
  }

  // gpfd's own vector environment (GpfdVectorEnv): its C++ engine (EnvBatch) steps, called from
  // here without Python, the GIL not taken: what GpfdVectorEnv.step does, less the arrays it makes.
  void nativeStep(const env::BatchBuffers& io) const {
    if (disabled_) {
      nb::gil_scoped_acquire gil;
      resetEnded(io);
    }
    const std::size_t components = actionComponents();
    for (std::size_t l = 0; l < io.lanes; ++l) {
      for (std::size_t c = 0; c < components; ++c) {
        const double a = io.action[c * io.stride + l];
        // As the action array of the space's dtype would hold it.
        native_->actions[physical_[l] * components + c] =
            actionKind_ == ActionKind::F32 ? static_cast<float>(a) : a;
      }
    }
    NativeBuffers& n = *native_;
    native_->engine->step(n.actions.data(),
                          {n.obs.data(), n.rewards.data(), n.terminated.get(), n.truncated.get(),
                           n.finalObs.data(), n.finalMask.get()});
    Outputs out;
    out.obs.bindRaw(n.obs.data(), stateDim());
    out.reward.bindRaw(n.rewards.data(), 1);
    out.terminated.bindRaw(n.terminated.get());
    out.truncated.bindRaw(n.truncated.get());
    out.withFinal = native_->engine->autoreset() == Autoreset::SameStep;
    if (out.withFinal) {
      out.finalMask.bindRaw(n.finalMask.get());
      out.finalObs.bindRaw(n.finalObs.data(), stateDim());
    }
    book(io, out);
  }

  void bindNative(nb::handle engine) {
    if (engine.is_none()) {
      native_.reset();
      return;
    }
    auto n = std::make_unique<NativeBuffers>();
    n->engine = nb::cast<EnvBatch*>(engine);
    if (n->engine->size() != lanes_ || n->engine->stateDim() != stateDim() ||
        n->engine->actionComponents() != actionComponents()) {
      throw std::logic_error("VectorAdapter.native_engine does not match the vector environment");
    }
    n->actions.assign(lanes_ * actionComponents(), 0.0);
    n->obs.assign(lanes_ * stateDim(), 0.0);
    n->finalObs.assign(lanes_ * stateDim(), 0.0);
    n->rewards.assign(lanes_, 0.0);
    n->terminated = std::make_unique<bool[]>(lanes_);
    n->truncated = std::make_unique<bool[]>(lanes_);
    n->finalMask = std::make_unique<bool[]>(lanes_);
    native_ = std::move(n);
  }

  void bindActions() {
    nb::ndarray<nb::device::cpu> array;
    if (!nb::try_cast(actions_, array, false)) {
      throw std::logic_error("VectorAdapter.actions must be a NumPy array");
    }
    actionData_ = array.data();
    const nb::dlpack::dtype type = array.dtype();
    if (type == nb::dtype<std::int64_t>()) {
      actionKind_ = ActionKind::I64;
    } else if (type == nb::dtype<double>()) {
      actionKind_ = ActionKind::F64;
    } else if (type == nb::dtype<float>()) {
      actionKind_ = ActionKind::F32;
    } else {
      throw std::logic_error("VectorAdapter.actions must be int64, float64 or float32");
    }
  }

  // Lane l's action into its sub-environment's row of the action array: a discrete choice plus
  // the space's start, a continuous one as the space's dtype (what gpfd.user_env.Adapter sends).
  void writeActions(const env::BatchBuffers& io) const {
    const std::size_t components = actionComponents();
    for (std::size_t l = 0; l < io.lanes; ++l) {
      const std::size_t p = physical_[l];
      for (std::size_t c = 0; c < components; ++c) {
        const double a = io.action[c * io.stride + l];
        const std::size_t i = p * components + c;
        switch (actionKind_) {
          case ActionKind::I64:
            static_cast<std::int64_t*>(actionData_)[i] = static_cast<std::int64_t>(a) + start_;
            break;
          case ActionKind::F64:
            static_cast<double*>(actionData_)[i] = a;
            break;
          case ActionKind::F32:
            static_cast<float*>(actionData_)[i] = static_cast<float>(a);
            break;
        }
      }
    }
  }

  // Disabled autoreset: the sub-environments whose episode ended are reset (no seed) before they
  // are stepped again; the reset must leave the running lanes as they are.
  void resetEnded(const env::BatchBuffers& io) const {
    std::vector<std::uint8_t> mask(ended_.begin(), ended_.end());
    if (std::find(mask.begin(), mask.end(), 1) == mask.end()) return;
    const nb::object obs =
        adapter_.attr("reset_ended")(nb::cast(std::vector<bool>(mask.begin(), mask.end())), steps_);
    ReadView view;
    if (!view.bind(obs, 2, lanes_, stateDim())) {
      throw std::logic_error("VectorAdapter.reset_ended must return float64 observations (N, d)");
    }
    for (std::size_t l = 0; l < io.lanes; ++l) {
      const std::size_t p = physical_[l];
      for (std::size_t i = 0; i < stateDim(); ++i) {
        const double before = io.state[i * io.stride + l];
        if (view.at(p, i) != before && !(std::isnan(before) && std::isnan(view.at(p, i)))) {
          resetOnItsOwn(p, io.elapsed[l],
                        "reset(options={'reset_mask': ...}) of other lanes "
                        "changed its observation");
        }
      }
    }
    ended_.assign(lanes_, 0);
  }

  // `value` as an array of `ndim` dimensions (rows: the sub-environments), read in place where it
  // is one of ReadView's types, else converted (or refused with EnvError) by the adapter.
  ReadView read(nb::handle value, const std::string& what, std::size_t ndim,
                std::size_t cols = 1) const {
    ReadView view;
    if (view.bind(value, ndim, lanes_, cols) && (ndim == 2 ? view.isFloat() : true)) return view;
    const nb::object converted = adapter_.attr("as_array")(value, what, steps_);
    keep_.push_back(converted);
    if (!view.bind(converted, ndim, lanes_, cols)) {
      throw std::logic_error("VectorAdapter.as_array gave an array of the wrong shape");
    }
    return view;
  }

  static bool hasItem(nb::handle info, const char* key) {
    return PyDict_Check(info.ptr()) && PyDict_GET_SIZE(info.ptr()) > 0 &&
           PyDict_GetItemString(info.ptr(), key) != nullptr;
  }

  // The errors (gpfd.EnvError, worded by the adapter); the GIL is taken where not held.
  [[noreturn]] void resetOnItsOwn(std::size_t lane, std::int32_t episodeStep,
                                  const std::string& how) const {
    nb::gil_scoped_acquire gil;
    adapter_.attr("reset_on_its_own")(steps_, lane, episodeStep, how);
    throw std::logic_error("VectorAdapter.reset_on_its_own must raise");
  }
  [[noreturn]] void badObservation(std::size_t lane, std::int32_t episodeStep, std::size_t index,
                                   double value) const {
    nb::gil_scoped_acquire gil;
    adapter_.attr("bad_observation")(steps_, lane, episodeStep, index, value);
    throw std::logic_error("VectorAdapter.bad_observation must raise");
  }

  std::vector<std::size_t> activeLanes(std::size_t count) const {
    std::vector<std::size_t> lanes(physical_.begin(), physical_.begin() + count);
    std::sort(lanes.begin(), lanes.end());
    return lanes;
  }

  enum class ActionKind { I64, F64, F32 };

  nb::object adapter_;
  // As the adapter's vector environment has them (read at each resetAll).
  std::int64_t start_ = 0;     // A discrete space's first action.
  bool disabled_ = false;      // Autoreset disabled: ended sub-environments need a reset.
  std::string elapsedKey_;     // The key of info that counts the steps of each episode, if any.
  nb::object step_, actions_;  // The vector environment's step and the action array it receives.
  void* actionData_ = nullptr;
  ActionKind actionKind_ = ActionKind::F64;
  std::size_t lanes_ = 0;                 // Sub-environments.
  std::vector<std::size_t> physical_;     // The sub-environment of each lane.
  mutable std::vector<char> ended_;       // Per sub-environment: its episode ended (disabled mode).
  mutable std::int64_t steps_ = 0;        // Vector steps since resetAll.
  mutable std::vector<nb::object> keep_;  // Converted arrays, alive while read.
  mutable nb::tuple finals_;              // The final observations of a same-step autoreset.
  // gpfd's own vector environment: its engine and the buffers of its step.
  struct NativeBuffers {
    EnvBatch* engine = nullptr;
    std::vector<double> actions, obs, rewards, finalObs;
    std::unique_ptr<bool[]> terminated, truncated, finalMask;
  };
  std::unique_ptr<NativeBuffers> native_;
};

}  // namespace

env::BatchForm pythonVectorForm(const std::string& name) {
  env::BatchForm form;
  form.available = [name](const env::Environment&) {
    nb::gil_scoped_acquire gil;
    return nb::cast<bool>(nb::module_::import_("gpfd.vector_source").attr("has_vector_form")(name));
  };
  form.make = [name](const env::Environment& prototype,
                     env::BatchIsa isa) -> std::unique_ptr<env::BatchEnvironment> {
    auto scalar = std::make_unique<ScalarShape>(prototype);
    const env::ActionSpace space = scalar->actionSpace();
    const int choices = space.continuous() ? 0 : space.choices.front();  // One component.
    nb::gil_scoped_acquire gil;
    nb::object adapter =
        nb::module_::import_("gpfd.vector_source")
            .attr("make_vector_adapter")(name, scalar->stateDim(), choices, space.low, space.high);
    return std::make_unique<PythonVectorBatch>(std::move(scalar), isa, std::move(adapter));
  };
  return form;
}

}  // namespace gpfd::python
