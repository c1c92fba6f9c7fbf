// python: the vector form of an environment stepped in Python (a Gymnasium VectorEnv: a
// vector_entry_point, an EnvPool task or the user's factory) as gpfd's batched environment
// (env/batch.hpp), so that the lockstep player advances all the episodes of a call with one call
// of the vector environment's step per time step. gpfd.adapters.vector_adapter.VectorAdapter makes,
// seeds, resets and checks the vector environment and words every error; vector_hub.cpp writes the
// actions, calls step and reads what it returns. Made in a member of a lockstep group
// (lockstep_group.hpp), the batched form plays its lanes in the group's one vector environment,
// with those of the group's other fitness evaluations; elsewhere in a vector environment of its
// own.
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/util/error.hpp"
#include "lockstep_group.hpp"
#include "python_call.hpp"
#include "vector_hub.hpp"

namespace gpfd::python {
namespace {

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

// Lanes of one member of a VectorHub.
class PythonVectorBatch final : public env::BatchEnvironment {
 public:
  PythonVectorBatch(std::unique_ptr<env::Environment> scalar, env::BatchIsa isa,
                    std::shared_ptr<VectorHub> hub, std::size_t member)
      : BatchEnvironment(std::move(scalar), isa), hub_(std::move(hub)), member_(member) {}

  void reset(Rng& /*rng*/, const env::BatchBuffers& /*io*/, std::size_t /*lane*/) override {
    throw InputError("the vector form of " + scalar().name() +
                         " starts the episodes of all its lanes together (resetAll), not one "
                         "lane alone",
                     "vector environment");
  }
  void resetAll(std::span<Rng> rngs, const env::BatchBuffers& io) override {
    hub_->resetAll(member_, rngs, io);
  }
  void step(const env::BatchBuffers& io) const override { hub_->step(member_, io); }
  void moveLane(std::size_t from, std::size_t to) override { hub_->moveLane(member_, from, to); }

 private:
  std::shared_ptr<VectorHub> hub_;
  std::size_t member_;  // A group's members leave when their job ends (LockstepGroup::leave).
};

}  // namespace

env::BatchForm pythonVectorForm(const std::string& name) {
  env::BatchForm form;
  form.available = [name](const env::Environment&) {
    return withPython([&] {
      return nb::cast<bool>(
          nb::module_::import_("gpfd.adapters.sources").attr("has_vector_form")(name));
    });
  };
  form.make = [name](const env::Environment& prototype,
                     env::BatchIsa isa) -> std::unique_ptr<env::BatchEnvironment> {
    auto scalar = std::make_unique<ScalarShape>(prototype);
    const env::ActionSpace space = scalar->actionSpace();
    const int choices = space.continuous() ? 0 : space.choices.front();  // One component.
    const std::size_t stateDim = scalar->stateDim(), components = space.components;
    auto makeHub = [&](std::size_t members) {
      return withPython([&] {
        nb::object adapter =
            nb::module_::import_("gpfd.adapters.vector_adapter")
                .attr("make_vector_adapter")(name, stateDim, choices, space.low, space.high);
        return std::make_shared<VectorHub>(std::move(adapter), stateDim, components, members);
      });
    };
    if (LockstepGroup* group = LockstepGroup::current()) {
      return std::make_unique<PythonVectorBatch>(std::move(scalar), isa, group->hub(name, makeHub),
                                                 LockstepGroup::currentMember());
    }
    return std::make_unique<PythonVectorBatch>(std::move(scalar), isa, makeHub(1), 0);
  };
  return form;
}

}  // namespace gpfd::python
