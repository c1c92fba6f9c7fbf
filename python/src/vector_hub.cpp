// python: the shared vector environment of a lockstep group (vector_hub.hpp). The rounds, then
// what a round does: writes the members' actions, calls step and reads what it returns, holding
// the GIL only meanwhile; gpfd's own vector environment (gpfd.vector.GpfdVectorEnv, whose step is a
// thin wrapper over its C++ engine EnvBatch) is stepped through that engine directly, without
// Python or the GIL.
//
// Episodes start only in a reset of the whole vector environment, so every autoreset mode gives
// the same episodes: the step that ends an episode is booked and its lane retired before any
// autoreset matters (same-step: the final observation comes from info["final_obs"]; disabled: a
// sub-environment whose episode ended is reset through options={"reset_mask": ...} before it is
// stepped again). The lockstep player compacts its lanes as episodes end (moveLane), but a vector
// environment cannot move an episode from one sub-environment to another, so each member keeps a
// map from its lanes to its sub-environments.
#include "vector_hub.hpp"

#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gpfd/env/numpy_scalar.hpp"
#include "gpfd/fibers/scheduler.hpp"
#include "python_call.hpp"

namespace gpfd::python {

VectorHub::VectorHub(nb::object adapter, std::size_t stateDim, std::size_t actionComponents,
                     std::size_t members)
    : stateDim_(stateDim),
      components_(actionComponents),
      members_(members),
      playing_(members),
      adapter_(std::move(adapter)) {}

VectorHub::~VectorHub() {
  withPython([&] {
    try {
      adapter_.attr("close")();
    } catch (nb::python_error& e) {
      e.discard_as_unraisable(__func__);
    }
    keep_.clear();
    finals_.reset();
    step_.reset();
    stepSubset_.reset();
    actions_.reset();
    adapter_.reset();
  });
}

// ---- the rounds ---------------------------------------------------------------------------------

void VectorHub::resetAll(std::size_t m, std::span<Rng> rngs, const env::BatchBuffers& io) {
  // Lane l's seed is the draw PythonEnvironment::reset makes from the same stream, so that the
  // stream then goes on to the same actions and a vector form that seeds each lane plays the
  // per-environment path's episodes.
  std::vector<std::uint64_t> seeds(rngs.size());
  for (std::size_t l = 0; l < rngs.size(); ++l) seeds[l] = rngs[l]() >> 1;
  members_[m].seeds = std::move(seeds);
  await(m, Wants::Reset, io);
}

void VectorHub::step(std::size_t m, const env::BatchBuffers& io) { await(m, Wants::Step, io); }

void VectorHub::moveLane(std::size_t m, std::size_t from, std::size_t to) {
  std::swap(members_[m].physical[from], members_[m].physical[to]);
}

void VectorHub::leave(std::size_t m) {
  if (!members_[m].playing) return;
  members_[m].playing = false;
  --playing_;
  if (!failure_ && roundDue() && runRoundOnThreadStack()) throwFailure(true);
}

void VectorHub::await(std::size_t m, Wants wants, const env::BatchBuffers& io) {
  if (failure_) throwFailure(false);
  Member& me = members_[m];
  me.wants = wants;
  me.io = &io;
  ++waiting_;
  if (roundDue() && runRoundOnThreadStack()) throwFailure(true);
  // A member of a group hands over to the others until a round has run its call.
  if (me.wants != Wants::Nothing) {
    fibers::Scheduler::waitUntil([&me] { return me.wants == Wants::Nothing; });
  }
  if (failure_) throwFailure(false);
}

bool VectorHub::runRoundOnThreadStack() {
  bool failed = false;
  fibers::Scheduler::onThreadStack([&] { failed = runRound(); });
  return failed;
}

bool VectorHub::runRound() {
  // The members that ask for a step; where none does, all (each asks for a reset).
  const bool steps = std::any_of(members_.begin(), members_.end(), [](const Member& member) {
    return member.playing && member.wants == Wants::Step;
  });
  due_.clear();
  for (std::size_t m = 0; m < members_.size(); ++m) {
    if (members_[m].playing && (!steps || members_[m].wants == Wants::Step)) due_.push_back(m);
  }
  try {
    if (steps) {
      stepMembers(due_);
    } else {
      resetMembers(due_);
    }
  } catch (...) {
    failure_ = std::current_exception();
  }
  for (std::size_t m : due_) members_[m].wants = Wants::Nothing;
  waiting_ -= due_.size();
  if (failure_) {
    for (Member& member : members_) member.wants = Wants::Nothing;
    waiting_ = 0;
  }
  return failure_ != nullptr;
}

void VectorHub::throwFailure(bool ranIt) {
  if (ranIt) std::rethrow_exception(failure_);
  throw LockstepGroupFailed();
}

// ---- a round's reset ----------------------------------------------------------------------------

void VectorHub::resetMembers(const std::vector<std::size_t>& resetting) {
  // Each member keeps its sub-environments while it needs no more (the layout then never changes
  // in a group of one); those of members that left or ask for fewer lanes start no episode.
  for (std::size_t m : resetting) {
    members_[m].size = std::max(members_[m].size, members_[m].seeds.size());
  }
  std::size_t total = 0;
  for (Member& member : members_) {
    member.offset = total;
    total += member.size;
  }
  nb::gil_scoped_acquire gil;
  nb::list seeds;
  for (const Member& member : members_) {
    const bool resets = member.playing && member.wants == Wants::Reset;
    for (std::size_t l = 0; l < member.size; ++l) {
      if (resets && l < member.seeds.size()) {
        seeds.append(member.seeds[l]);
      } else {
        seeds.append(nb::none());
      }
    }
  }
  const nb::object obs = adapter_.attr("reset")(seeds);
  lanes_ = nb::cast<std::size_t>(adapter_.attr("num_envs"));
  step_ = adapter_.attr("step_function");
  actions_ = adapter_.attr("actions");
  bindActions();
  bindNative(adapter_.attr("native_engine"));
  start_ = nb::cast<std::int64_t>(adapter_.attr("start"));
  disabled_ = nb::cast<bool>(adapter_.attr("resets_ended"));
  elapsedKey_ = nb::cast<std::string>(adapter_.attr("elapsed_key"));
  subsets_ = nb::cast<bool>(adapter_.attr("steps_subsets"));
  stepSubset_ = subsets_ ? adapter_.attr("step_subset") : nb::object();
  elapsedWhat_ = "info['" + elapsedKey_ + "']";
  stepped_.resize(lanes_);
  std::iota(stepped_.begin(), stepped_.end(), std::size_t{0});
  rowOf_ = stepped_;
  ended_.assign(lanes_, 0);
  steps_ = 0;
  ReadView view;
  if (!view.bind(obs, 2, lanes_, stateDim_)) {
    throw std::logic_error("VectorAdapter.reset must return float64 observations (N, d)");
  }
  for (std::size_t m : resetting) {
    Member& member = members_[m];
    member.physical.resize(member.size);
    std::iota(member.physical.begin(), member.physical.end(), std::size_t{0});
    const env::BatchBuffers& io = *member.io;
    for (std::size_t l = 0; l < member.seeds.size(); ++l) {
      for (std::size_t i = 0; i < stateDim_; ++i) {
        io.state[i * io.stride + l] = view.at(member.offset + l, i);
      }
      io.elapsed[l] = 0;
    }
  }
}

// ---- a round's step -----------------------------------------------------------------------------

namespace {

bool hasItem(nb::handle info, const char* key) {
  return PyDict_Check(info.ptr()) && PyDict_Size(info.ptr()) > 0 &&
         PyDict_GetItemString(info.ptr(), key) != nullptr;
}

}  // namespace

void VectorHub::stepMembers(const std::vector<std::size_t>& stepping) {
  ++steps_;
  if (native_ != nullptr) {
    nativeStep(stepping);
    return;
  }
  nb::gil_scoped_acquire gil;
  keep_.clear();
  if (disabled_) resetEnded(stepping);
  writeActions(stepping);
  // The rows of what step returns: every sub-environment, or (a vector form that steps subsets)
  // those that play an episode, in order.
  if (subsets_) {
    stepped_ = activeSubEnvironments(stepping);
    for (std::size_t r = 0; r < stepped_.size(); ++r) rowOf_[stepped_[r]] = r;
  }
  nb::object result;
  try {
    result = subsets_ ? stepSubset_(nb::cast(stepped_)) : step_(actions_);
  } catch (nb::python_error& e) {
    // An interruption (KeyboardInterrupt, SystemExit) is not the environment's failure.
    if (!e.matches(PyExc_Exception)) throw;
    adapter_.attr("step_raised")(e.value(), steps_, activeSubEnvironments(stepping));
    throw std::logic_error("VectorAdapter.step_raised must raise");
  }
  if (!PyTuple_Check(result.ptr()) || PyTuple_Size(result.ptr()) != 5) {
    adapter_.attr("bad_result")(result, steps_);
    throw std::logic_error("VectorAdapter.bad_result must raise");
  }
  const nb::handle info(PyTuple_GetItem(result.ptr(), 4));
  Outputs out;
  out.obs = read(PyTuple_GetItem(result.ptr(), 0), "observations", 2, stateDim_);
  out.reward = read(PyTuple_GetItem(result.ptr(), 1), "rewards", 1);
  out.terminated = read(PyTuple_GetItem(result.ptr(), 2), "terminated", 1);
  out.truncated = read(PyTuple_GetItem(result.ptr(), 3), "truncated", 1);
  // Same-step autoreset: the observation that ended an episode is in info["final_obs"].
  if (hasItem(info, "_final_obs")) {
    finals_ = nb::cast<nb::tuple>(adapter_.attr("final_observations")(
        info, steps_, subsets_ ? nb::cast(stepped_) : nb::none()));
    out.finalMask = read(finals_[0], "info['_final_obs']", 1);
    out.finalObs = read(finals_[1], "info['final_obs']", 2, stateDim_);
    out.withFinal = true;
  }
  if (!elapsedKey_.empty() && hasItem(info, elapsedKey_.c_str())) {
    out.elapsed =
        read(nb::handle(PyDict_GetItemString(info.ptr(), elapsedKey_.c_str())), elapsedWhat_, 1);
    out.withElapsed = true;
  }
  for (std::size_t m : stepping) book(members_[m], out);
  markEnded(out);
}

// Lane by lane, what the lane's sub-environment returned, checked, into the member's buffers.
void VectorHub::book(const Member& member, const Outputs& out) {
  const env::BatchBuffers& io = *member.io;
  for (std::size_t l = 0; l < io.lanes; ++l) {
    const std::size_t p = member.offset + member.physical[l], r = rowOf_[p];
    const bool ended = out.terminated.at(r) != 0.0 || out.truncated.at(r) != 0.0;
    ++io.elapsed[l];
    const bool isFinal = out.withFinal && out.finalMask.at(r) != 0.0;
    if (isFinal && !ended) resetOnItsOwn(p, io.elapsed[l], "info['_final_obs'] marks it");
    if (out.withElapsed && out.elapsed.at(r) != io.elapsed[l]) {
      resetOnItsOwn(p, io.elapsed[l],
                    fmt::format("info['{}'] says {}", elapsedKey_, out.elapsed.at(r)));
    }
    const ReadView& row = isFinal ? out.finalObs : out.obs;
    for (std::size_t i = 0; i < stateDim_; ++i) {
      const double v = row.at(r, i);
      if (!std::isfinite(v)) badObservation(p, io.elapsed[l], i, v);
      io.state[i * io.stride + l] = v;
    }
    io.reward[l] = out.reward.at(r);
    io.terminated[l] = out.terminated.at(r) != 0.0 ? 1 : 0;
    io.truncated[l] = out.truncated.at(r) != 0.0 ? 1 : 0;
  }
}

// Disabled autoreset: which sub-environments' episodes ended, playing or not.
void VectorHub::markEnded(const Outputs& out) {
  for (std::size_t r = 0; r < stepped_.size(); ++r) {
    if (out.terminated.at(r) != 0.0 || out.truncated.at(r) != 0.0) ended_[stepped_[r]] = 1;
  }
}

// gpfd's own vector environment (GpfdVectorEnv): its C++ engine (EnvBatch) steps, called from
// here without Python, the GIL not taken: what GpfdVectorEnv.step does, less the arrays it makes.
void VectorHub::nativeStep(const std::vector<std::size_t>& stepping) {
  if (disabled_) {
    nb::gil_scoped_acquire gil;
    resetEnded(stepping);
  }
  NativeBuffers& n = *native_;
  forEachLane(stepping, [&](const env::BatchBuffers& io, std::size_t l, std::size_t p) {
    for (std::size_t c = 0; c < components_; ++c) {
      const double a = io.action[c * io.stride + l];
      // As the action array of the space's dtype would hold it (toFloat32: GCC 12 has dropped
      // such a cast, numpy_scalar.hpp).
      n.actions[p * components_ + c] =
          actionKind_ == ActionKind::F32 ? env::numpy_scalar::toFloat32(a) : a;
    }
  });
  n.engine->step(n.actions.data(), {n.obs.data(), n.rewards.data(), n.terminated.get(),
                                    n.truncated.get(), n.finalObs.data(), n.finalMask.get()});
  Outputs out;
  out.obs.bindRaw(n.obs.data(), stateDim_);
  out.reward.bindRaw(n.rewards.data(), 1);
  out.terminated.bindRaw(n.terminated.get());
  out.truncated.bindRaw(n.truncated.get());
  out.withFinal = n.engine->autoreset() == Autoreset::SameStep;
  if (out.withFinal) {
    out.finalMask.bindRaw(n.finalMask.get());
    out.finalObs.bindRaw(n.finalObs.data(), stateDim_);
  }
  for (std::size_t m : stepping) book(members_[m], out);
  markEnded(out);
}

void VectorHub::bindNative(nb::handle engine) {
  if (engine.is_none()) {
    native_.reset();
    return;
  }
  auto n = std::make_unique<NativeBuffers>();
  n->engine = nb::cast<EnvBatch*>(engine);
  if (n->engine->size() != lanes_ || n->engine->stateDim() != stateDim_ ||
      n->engine->actionComponents() != components_) {
    throw std::logic_error("VectorAdapter.native_engine does not match the vector environment");
  }
  n->actions.assign(lanes_ * components_, 0.0);
  n->obs.assign(lanes_ * stateDim_, 0.0);
  n->finalObs.assign(lanes_ * stateDim_, 0.0);
  n->rewards.assign(lanes_, 0.0);
  n->terminated = std::make_unique<bool[]>(lanes_);
  n->truncated = std::make_unique<bool[]>(lanes_);
  n->finalMask = std::make_unique<bool[]>(lanes_);
  native_ = std::move(n);
}

void VectorHub::bindActions() {
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

// Each lane's action into its sub-environment's row of the action array: a discrete choice plus
// the space's start, a continuous one as the space's dtype (what gpfd.user_env.Adapter sends).
void VectorHub::writeActions(const std::vector<std::size_t>& stepping) {
  forEachLane(stepping, [&](const env::BatchBuffers& io, std::size_t l, std::size_t p) {
    for (std::size_t c = 0; c < components_; ++c) {
      const double a = io.action[c * io.stride + l];
      const std::size_t i = p * components_ + c;
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
  });
}

// Disabled autoreset: the sub-environments whose episode ended are reset (no seed) before they
// are stepped again; the reset must leave the playing lanes as they are.
void VectorHub::resetEnded(const std::vector<std::size_t>& stepping) {
  if (std::find(ended_.begin(), ended_.end(), 1) == ended_.end()) return;
  const nb::object obs = adapter_.attr("reset_ended")(
      nb::cast(std::vector<bool>(ended_.begin(), ended_.end())), steps_);
  ReadView view;
  if (!view.bind(obs, 2, lanes_, stateDim_)) {
    throw std::logic_error("VectorAdapter.reset_ended must return float64 observations (N, d)");
  }
  forEachLane(stepping, [&](const env::BatchBuffers& io, std::size_t l, std::size_t p) {
    for (std::size_t i = 0; i < stateDim_; ++i) {
      const double before = io.state[i * io.stride + l];
      if (view.at(p, i) != before && !(std::isnan(before) && std::isnan(view.at(p, i)))) {
        resetOnItsOwn(p, io.elapsed[l],
                      "reset(options={'reset_mask': ...}) of other lanes changed its observation");
      }
    }
  });
  ended_.assign(lanes_, 0);
}

// `value` as an array of `ndim` dimensions (rows: the sub-environments), read in place where it
// is one of ReadView's types, else converted (or refused with EnvError) by the adapter.
ReadView VectorHub::read(nb::handle value, const std::string& what, std::size_t ndim,
                         std::size_t cols) {
  ReadView view;
  const std::size_t rows = stepped_.size();
  if (view.bind(value, ndim, rows, cols) && (ndim == 2 ? view.isFloat() : true)) return view;
  const nb::object converted = adapter_.attr("as_array")(value, what, steps_, rows);
  keep_.push_back(converted);
  if (!view.bind(converted, ndim, rows, cols)) {
    throw std::logic_error("VectorAdapter.as_array gave an array of the wrong shape");
  }
  return view;
}

std::vector<std::size_t> VectorHub::activeSubEnvironments(
    const std::vector<std::size_t>& stepping) const {
  std::vector<std::size_t> active;
  forEachLane(stepping,
              [&](const env::BatchBuffers&, std::size_t, std::size_t p) { active.push_back(p); });
  std::sort(active.begin(), active.end());
  return active;
}

// The errors (gpfd.EnvError, worded by the adapter); the GIL is taken where not held.
void VectorHub::resetOnItsOwn(std::size_t subEnv, std::int32_t episodeStep,
                              const std::string& how) const {
  nb::gil_scoped_acquire gil;
  adapter_.attr("reset_on_its_own")(steps_, subEnv, episodeStep, how);
  throw std::logic_error("VectorAdapter.reset_on_its_own must raise");
}

void VectorHub::badObservation(std::size_t subEnv, std::int32_t episodeStep, std::size_t index,
                               double value) const {
  nb::gil_scoped_acquire gil;
  adapter_.attr("bad_observation")(steps_, subEnv, episodeStep, index, value);
  throw std::logic_error("VectorAdapter.bad_observation must raise");
}

}  // namespace gpfd::python
